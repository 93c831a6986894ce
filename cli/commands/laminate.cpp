// plyfit laminate LAMINATE.ini -o DIR [-j N]: drapes every ply of a laminate (job/
// laminate_run.hpp: the mold loaded once, N plies at a time on threads) into DIR/<ply>/, then
// writes the ply book (plybook.html, .json, .csv) and the cut drawing (cut.dxf) and prints a
// table of the plies.

#include "commands/commands.hpp"
#include "job/laminate_run.hpp"
#include "report/text_format.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/laminate.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace plyfit::cli {
namespace {

namespace fs = std::filesystem;

std::atomic<bool> g_cancel{false};
void on_interrupt(int) {
  g_cancel.store(true);
}

const OptionTable& laminate_options() {
  static const OptionTable table = {
      help_option(),
      jobs_option("plies"),
      output_option("DIR", "output folder (each ply into DIR/<ply name>/)"),
      quiet_option(),
      {"splice-stagger", "MM", "",
       "seams of plies of one fibre direction keep at least this far apart on the part (mm; "
       "instead of the file's splice-stagger)"},
  };
  return table;
}

// The laminate file's own keys, as "key = VALUE": they are no flags.
void print_laminate_keys(std::ostream& os) {
  os << "\nlaminate file keys (besides every scene key; docs/laminate.md):\n";
  for (const auto& k : laminate_keys())
    os << "  " << pad(k.key + " = " + k.value, 20) << "  " << k.help
       << (k.def.empty() ? "" : " [" + k.def + "]") << "\n";
}

const CommandHelp kLaminateHelp = {
    "plyfit laminate LAMINATE.ini -o DIR [-j N]",
    "Drapes every ply of a laminate file ([laminate]: the mold, the rosette, the roll width\n"
    "and the plies' default scene keys; then one [ply NAME] section per ply: sequence, angle\n"
    "and the scene keys that differ). The mold is read once; N plies are draped at a time,\n"
    "each into DIR/<ply name>/ with the usual files; a failing ply fails alone. Then writes\n"
    "DIR/plybook.html (the ply book: table and pictures), plybook.json, plybook.csv and\n"
    "cut.dxf (every ply's cut outline on one roll). Exit 0 when every ply succeeded (ok or\n"
    "partial) and every file was written, 1 otherwise, 130 when interrupted.\n",
    print_laminate_keys};

// A ply split for its roll: its pieces and seams as the shop documents show them.
void add_pieces(exporters::PlySheet& s, const SplicePlan& plan) {
  for (const SplicePiece& p : plan.pieces) s.pieces.push_back({p.name, p.area, p.width(), p.loops});
  for (const Seam& seam : plan.seams) s.seams.push_back({seam.x, seam.stagger_distance});
  s.splice_stagger = plan.stagger;
  s.stagger_met = plan.stagger_met;
}

exporters::PlySheet sheet_of(const PlyRun& r) {
  exporters::PlySheet s;
  s.sequence = r.ply.sequence;
  s.name = r.ply.name;
  if (r.job) {
    s.angle_deg = r.job->ply_angle_deg;
    s.material =
        r.job->exports.material_label.empty() ? r.job->material : r.job->exports.material_label;
  } else {  // its keys are wrong: what they say, as far as it reads
    const Options o(r.ply.raw, drape_options());
    const auto angle = o.number("ply-angle");
    s.angle_deg = o.given("ply-angle") && angle ? *angle : 0.0;
    s.material = o.text("material").value_or("");
  }
  s.status = r.outcome.status;
  s.error = r.outcome.error;
  s.error_code = r.outcome.error_code;
  if (r.succeeded()) {
    s.flat_area = r.outcome.flat_outline_area;
    s.shear_max_deg = r.outcome.shear_max_deg;
    s.warnings = r.outcome.warnings;
    s.files = r.outcome.files;
    s.cut = r.outcome.cut;
    if (r.outcome.splices && r.outcome.splices->split()) add_pieces(s, *r.outcome.splices);
  }
  return s;
}

void print_table(const exporters::Plybook& book, std::ostream& os) {
  std::vector<std::vector<std::string>> rows = {{"seq", "ply", "angle", "material", "status",
                                                 "flat area (mm2)", "max shear (deg)", "warnings"}};
  for (const auto& p : book.plies) {
    const bool ran = p.status == "ok" || p.status == "partial";
    rows.push_back({std::to_string(p.sequence), p.name, fixed(p.angle_deg, 1), p.material, p.status,
                    ran ? fixed(p.flat_area, 1) : "-", ran ? fixed(p.shear_max_deg, 3) : "-",
                    std::to_string(p.warnings.size())});
  }
  print_columns(rows, os);
}

// The ply book and the cut drawing; false when one could not be written or a ply was left out
// of the drawing.
bool write_documents(const exporters::Plybook& book, const fs::path& dir) {
  const exporters::CutSheet cut = exporters::cut_sheet(book);
  bool ok = cut.left_out.empty();
  for (const auto& e : cut.left_out) {
    Error named = e;
    named.input = "ply " + e.input;
    print_error(named);
  }
  for (const auto& [file, text] :
       {std::pair{dir / "plybook.json", exporters::plybook_json(book)},
        std::pair{dir / "plybook.csv", exporters::plybook_csv(book)},
        std::pair{dir / "plybook.html", exporters::plybook_html(book, dir.string())},
        std::pair{dir / "cut.dxf", cut.dxf}}) {
    if (auto st = exporters::write_file_atomic(file.string(), text); !st) {
      print_error(st.error());
      ok = false;
    }
  }
  return ok;
}

int run_laminate(const Options& o) {
  auto jobs = jobs_value(o);
  if (!jobs) return error_exit(kExitUsage, jobs.error(), o.namer());
  if (!o.given("output")) return error_exit(kExitUsage, o.missing("output"), o.namer());
  const fs::path dir = *o.text("output");
  auto laminate = read_laminate(o.all("laminate").front(), dir.string());
  if (!laminate) return error_exit(kExitFailure, laminate.error());
  if (o.given("splice-stagger")) {
    auto stagger = o.number("splice-stagger");
    if (!stagger) return error_exit(kExitUsage, stagger.error(), o.namer());
    if (!(*stagger >= 0.0))
      return error_exit(kExitUsage,
                        Error{ErrorCode::kSpliceStaggerNegative, "splice-stagger", {*stagger}},
                        o.namer());
    laminate->splice_stagger = *stagger;
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    return error_exit(kExitFailure,
                      Error{ErrorCode::kCannotCreateFolder, dir.string(), {ec.message()}});

  g_cancel.store(false);
  const CatchInterrupts interrupts(on_interrupt);
  const bool quiet = o.given("quiet");
  const auto runs =
      drape_plies(*laminate, static_cast<int>(*jobs), &g_cancel, [quiet](const PlyRun& r) {
        if (!r.error_line.empty())
          std::cerr << "plyfit: error: ply " << r.ply.name << ": " << r.error_line << "\n";
        else if (!quiet)
          std::cerr << "plyfit: ply " << r.ply.name << ": " << r.outcome.status << "\n";
      });
  exporters::Plybook book;
  book.laminate = laminate->path;
  book.roll_width = laminate->roll_width;
  for (const auto& r : runs) book.plies.push_back(sheet_of(r));
  const bool written = write_documents(book, dir);
  print_table(book, std::cout);
  if (g_cancel.load()) return kExitInterrupted;
  const bool all_ok =
      std::all_of(runs.begin(), runs.end(), [](const PlyRun& r) { return r.succeeded(); });
  return all_ok && written ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterLaminate{options_command(
    "laminate", "drape a laminate's plies and write its ply book and cut drawing", 35,
    {laminate_options, {"laminate", "laminate file"}, kLaminateHelp}, run_laminate)};

}  // namespace
}  // namespace plyfit::cli
