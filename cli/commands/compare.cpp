// plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]: drapes scenes on one
// mold face with different initial conditions and prints the comparison of the paper's
// Tables 2 and 4 (our figures and the paper's own thread angles), marking the best scene for
// each criterion among those that cover the face.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/optimize.hpp>
#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "job/scene_names.hpp"

#include <boost/program_options.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace plyfit::cli {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

/// Two figures closer than this (relative to the larger) tie: both are marked best. Counts
/// tie only when equal.
constexpr double kTieRel = 1e-9;

/// How a column is marked.
enum class Mark {
  kSmaller,  ///< the smallest figure among the compared scenes
  kLarger,   ///< the largest
  kCovers,   ///< every scene that covers the face (the outline coverage rule): the compared ones
  kNone,     ///< shown only
};

/// One column of the table.
struct Criterion {
  std::string key;     ///< CSV column and `best` entry
  std::string header;  ///< table header
  Mark mark;
  bool count;  ///< an integer count (exact ties)
  int digits;  ///< decimals shown
};

const std::vector<Criterion>& criteria() {
  static const std::vector<Criterion> list = {
      {"area", "area (mesh points)", Mark::kSmaller, true, 0},
      {"flat_area", "flat area", Mark::kSmaller, false, 2},
      {"gamma_min_deg", "gamma min (deg)", Mark::kLarger, false, 3},
      {"gamma_max_deg", "gamma max (deg)", Mark::kSmaller, false, 3},
      {"shear_max_deg", "max shear (deg)", Mark::kSmaller, false, 3},
      {"energy", "energy sum cos^2", Mark::kSmaller, false, 3},
      {"paper_gamma_min_deg", "paper gamma min (deg)", Mark::kLarger, false, 3},
      {"paper_gamma_max_deg", "paper gamma max (deg)", Mark::kSmaller, false, 3},
      {"paper_shear_max_deg", "paper max shear (deg)", Mark::kSmaller, false, 3},
      {"paper_energy", "paper energy", Mark::kSmaller, false, 3},
      {"coverage_pct", "cell coverage (%)", Mark::kNone, false, 2},
      {"outline_coverage_pct", "outline coverage (%)", Mark::kCovers, false, 2},
      {"shear_limit", "shear-limit stops", Mark::kSmaller, true, 0},
  };
  return list;
}

/// Index of the column `key` in criteria().
std::size_t column(const std::string& key) {
  for (std::size_t c = 0; c < criteria().size(); ++c)
    if (criteria()[c].key == key) return c;
  throw std::logic_error("no compare column " + key);
}

struct Row {
  std::string name, path;
  bool ok = false;       ///< draped (status ok or partial)
  bool partial = false;  ///< draped, status partial
  std::string error;
  std::vector<std::string> warnings;
  std::vector<double> values;  ///< one per criterion
  std::vector<bool> best;
  bool compared = false;  ///< status ok and covers the face: its figures compete for best
};

std::string fixed(double x, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << x;
  return os.str();
}

bool ties(double a, double b, bool count) {
  if (count) return a == b;
  return std::abs(a - b) <= kTieRel * std::max(std::abs(a), std::abs(b));
}

// The rule: a scene competes for best only when its drape is ok (not partial) and its flat
// pattern's outline covers at least the largest such coverage among the ok scenes (at most the
// whole face) less kCoverageSlack: a fitting that covers less of the face never wins by the
// figures it leaves out (fewer nodes, less energy, less area).
void mark_best(std::vector<Row>& rows) {
  const std::size_t cov = column("outline_coverage_pct");
  double top = -1.0;  // percent
  for (const auto& r : rows)
    if (r.ok && !r.partial) top = std::max(top, r.values[cov]);
  const double floor = std::min(top, 100.0) - 100.0 * kCoverageSlack;
  for (auto& r : rows) {
    r.best.assign(criteria().size(), false);
    r.compared = r.ok && !r.partial && r.values[cov] >= floor;
  }
  for (std::size_t c = 0; c < criteria().size(); ++c) {
    const Criterion& k = criteria()[c];
    if (k.mark == Mark::kNone) continue;
    if (k.mark == Mark::kCovers) {
      for (auto& r : rows) r.best[c] = r.compared;
      continue;
    }
    bool any = false;
    double best = 0.0;
    for (const auto& r : rows) {
      if (!r.compared) continue;
      const double v = r.values[c];
      if (!any || (k.mark == Mark::kLarger ? v > best : v < best)) best = v;
      any = true;
    }
    for (auto& r : rows)
      if (r.compared && ties(r.values[c], best, k.count)) r.best[c] = true;
  }
}

/// The marking rule, as the legends state it.
const char* const kRule =
    "best in its column among the compared scenes: those whose drape is ok (not partial) and "
    "whose flat pattern's outline covers the face as well as the best, within 0.5% (all marked "
    "in the outline coverage column); smallest area, flat area, gamma max, max shear, energy "
    "(ours and the paper's) and shear-limit stops; largest gamma min (ours and the paper's); "
    "ties within 1e-9 relative are all marked; the cell coverage is shown, not compared";

std::string cell(const Row& r, std::size_t c) {
  return fixed(r.values[c], criteria()[c].digits);
}

// The scenes that failed, the partial ones with their warnings, and those that cover less.
void print_notes(const std::vector<Row>& rows, std::ostream& os) {
  for (const auto& r : rows) {
    if (!r.ok) {
      os << r.name << ": error: " << r.error << "\n";
    } else if (r.partial) {
      os << r.name << ": partial, not compared";
      for (std::size_t k = 0; k < r.warnings.size(); ++k) os << (k ? "; " : ": ") << r.warnings[k];
      os << "\n";
    } else if (!r.compared) {
      os << r.name << ": not compared: its outline covers "
         << fixed(r.values[column("outline_coverage_pct")], 2)
         << "% of the face, more than 0.5% less than the best\n";
    }
  }
}

void print_text(const std::vector<Row>& rows, std::ostream& os) {
  std::vector<std::vector<std::string>> t;
  std::vector<std::string> head = {"scene"};
  for (const auto& k : criteria()) head.push_back(k.header);
  t.push_back(head);
  for (const auto& r : rows) {
    std::vector<std::string> line = {r.name};
    for (std::size_t c = 0; c < criteria().size(); ++c)
      line.push_back(r.ok ? cell(r, c) + (r.best[c] ? " *" : "  ") : "-");
    t.push_back(line);
  }
  std::vector<std::size_t> w(head.size(), 0);
  for (const auto& line : t)
    for (std::size_t c = 0; c < line.size(); ++c) w[c] = std::max(w[c], line[c].size());
  for (const auto& line : t) {
    std::string s;
    for (std::size_t c = 0; c < line.size(); ++c) {
      std::string v = line[c];
      // Scene names left-aligned, figures right-aligned.
      if (c == 0)
        v += std::string(w[c] - v.size(), ' ');
      else
        v = std::string(w[c] - v.size(), ' ') + v;
      s += (c ? "  " : "") + v;
    }
    os << s << "\n";
  }
  print_notes(rows, os);
  os << "* " << kRule << "\n";
}

void print_markdown(const std::vector<Row>& rows, std::ostream& os) {
  os << "| scene |";
  for (const auto& k : criteria()) os << " " << k.header << " |";
  os << "\n|---|";
  for (std::size_t c = 0; c < criteria().size(); ++c) os << "---:|";
  os << "\n";
  for (const auto& r : rows) {
    os << "| " << r.name << " |";
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok)
        os << " error |";
      else if (r.best[c])
        os << " **" << cell(r, c) << "** |";
      else
        os << " " << cell(r, c) << " |";
    }
    os << "\n";
  }
  os << "\n";
  print_notes(rows, os);
  os << "\nIn bold: " << kRule << ".\n";
}

void print_csv(const std::vector<Row>& rows, std::ostream& os) {
  os << "scene,status";
  for (const auto& k : criteria()) os << "," << k.key;
  os << ",best,note\n";
  for (const auto& r : rows) {
    os << r.name << "," << (!r.ok ? "error" : r.partial ? "partial" : "ok");
    std::string best;
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok) {
        os << ",";
        continue;
      }
      std::ostringstream v;
      v.precision(17);
      v << r.values[c];
      os << "," << v.str();
      if (r.best[c]) best += (best.empty() ? "" : ";") + criteria()[c].key;
    }
    // The note: the error, or a partial drape's warnings.
    std::string note = r.error;
    for (const auto& w : r.warnings)
      if (r.partial) note += (note.empty() ? "" : "; ") + w;
    for (char& ch : note)
      if (ch == '"') ch = '\'';
    os << "," << best << "," << (note.empty() ? "" : "\"" + note + "\"") << "\n";
  }
}

/// The mold a job drapes: resolved file (or built-in spec), face and side.
std::string mold_identity(const DrapeJob& job) {
  std::string m = job.mold;
  if (m.rfind("builtin:", 0) != 0) {
    std::error_code ec;
    const auto c = fs::weakly_canonical(m, ec);
    if (!ec) m = c.string();
  }
  return m + " face " + std::to_string(job.face) + (job.flip_normal ? " (flipped)" : "");
}

int run_compare(const std::vector<std::string>& args) {
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")("csv", "print CSV (full precision)")(
      "markdown", "print a Markdown table")(
      "output,o", po::value<std::string>(),
      "also write each scene's outputs into OUTROOT/<scene name>/")(
      "force", "compare scenes on different molds or faces anyway (with a warning)")(
      "scene", po::value<std::vector<std::string>>(), "scene files");
  po::positional_options_description pos;
  pos.add("scene", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("compare: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    std::cout << "usage: plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]\n\n"
                 "Drapes every scene (one mold face, different initial conditions) and prints,\n"
                 "per scene, the figures of the paper's Tables 2 and 4: area (mapped mesh\n"
                 "points), flat area (the flat pattern's outline), thread angles gamma min and\n"
                 "max, max shear, shear energy sum cos^2(gamma), the same three by the paper's\n"
                 "own thread angle (eq. 12), the coverage of the face by the mapped cells and\n"
                 "by the outline, and the nodes stopped by the shear limit. The best scene for\n"
                 "each criterion is marked among the ok scenes whose outline covers the face as\n"
                 "well as the best, within 0.5% (a fitting that covers less never wins). Scenes\n"
                 "on different molds or faces are refused unless --force.\n\n"
              << opts;
    return kExitOk;
  }
  if (!vm.count("scene")) {
    print_error("compare: no scene files (plyfit compare SCENE... [--csv | --markdown])");
    return kExitUsage;
  }
  if (vm.count("csv") && vm.count("markdown")) {
    print_error("compare: --csv and --markdown exclude each other");
    return kExitUsage;
  }
  const auto paths = vm["scene"].as<std::vector<std::string>>();
  const auto names = unique_scene_names(paths);
  // Load every scene first: a bad scene or a different mold stops before any drape.
  std::vector<DrapeJob> jobs;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    auto raw = raw_from_scene(paths[i]);
    if (!raw) {
      print_error("compare: " + exporters::describe(raw.error()));
      return kExitFailure;
    }
    auto job = make_job(*raw, false);
    if (!job) {
      print_error("compare: " + exporters::describe(job.error()));
      return kExitFailure;
    }
    job->outdir.clear();
    if (vm.count("output"))
      job->outdir = (fs::path(vm["output"].as<std::string>()) / names[i]).string();
    jobs.push_back(std::move(job).value());
  }
  for (std::size_t i = 1; i < jobs.size(); ++i) {
    if (mold_identity(jobs[i]) == mold_identity(jobs[0])) continue;
    const std::string msg = paths[i] + " drapes " + mold_identity(jobs[i]) + ", but " + paths[0] +
                            " drapes " + mold_identity(jobs[0]);
    if (!vm.count("force")) {
      print_error("compare: scenes on different molds: " + msg + " (--force compares them anyway)");
      return kExitUsage;
    }
    std::cerr << "plyfit: warning: comparing scenes on different molds: " << msg << "\n";
  }
  std::vector<Row> rows;
  bool all_ok = true;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    Row r;
    r.name = names[i];
    r.path = paths[i];
    auto out = run_job(jobs[i], nullptr, true);
    if (!out) {
      r.error = exporters::describe(out.error());
      all_ok = false;
    } else {
      const auto& m = out->metrics;
      r.ok = true;
      r.partial = out->status == "partial";
      r.warnings = out->warnings;
      r.values = {static_cast<double>(m.area_mesh_points),
                  out->flat_outline_area,
                  m.gamma_min * kRadToDeg,
                  m.gamma_max * kRadToDeg,
                  m.shear_max * kRadToDeg,
                  m.shear_energy,
                  m.paper.gamma_min * kRadToDeg,
                  m.paper.gamma_max * kRadToDeg,
                  m.paper.shear_max * kRadToDeg,
                  m.paper.energy,
                  100.0 * m.coverage,
                  100.0 * out->outline_coverage,
                  static_cast<double>(m.nodes.shear_limit)};
    }
    rows.push_back(std::move(r));
  }
  mark_best(rows);
  if (vm.count("csv"))
    print_csv(rows, std::cout);
  else if (vm.count("markdown"))
    print_markdown(rows, std::cout);
  else
    print_text(rows, std::cout);
  for (const auto& r : rows)
    if (!r.ok) print_error("compare: " + r.name + ": " + r.error);
  return all_ok ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterCompare{Command{
    "compare", "compare drapes of one mold face (the paper's Tables 2 and 4)", 40, run_compare}};

}  // namespace
}  // namespace plyfit::cli
