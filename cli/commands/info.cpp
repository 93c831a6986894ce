// plyfit info FILE [--json] [--format F]: lists a mold file's faces without converting them.
// plyfit info FILE --face N [--json]: converts face N alone and gives a point near its middle,
// its outward normal, and initial conditions for a drape from there.
// plyfit info FILE --neighbours [--json]: sews every face into one shell and lists each face's
// neighbours (crease angles) and free boundary.
// plyfit info FILE --curves [--json]: lists the file's curves (for ply boundaries and seed
// curves).

#include "commands/commands.hpp"
#include "report/curves_report.hpp"
#include "report/info_report.hpp"
#include "report/links_report.hpp"

#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/optimize.hpp>

#include <iostream>

namespace plyfit::cli {

namespace {

// Largest face index accepted (as plyfit drape's --face).
constexpr long kMaxFace = 1L << 30;

const OptionTable& info_options() {
  static const OptionTable table = {
      help_option(),
      {"json", "", "", "print the listing as JSON"},
      {"format", "KEY", "", "importer to use (step, iges), overriding the extension"},
      {"face", "N", "",
       "face N alone: a point near its middle, its outward normal and drape flags from there"},
      {"neighbours", "", "",
       "sew every face into one shell: each face's neighbours, crease angles and free boundary"},
      {"curves", "", "",
       "the file's curves (free curves and wire edges, else face edges): index, name, kind, "
       "length, closed, end points"},
      {"file", "FILE", "", "mold file (STEP or IGES)"},
  };
  return table;
}

const CommandHelp kInfoHelp = {
    "plyfit info FILE [--face N | --neighbours | --curves] [--json] [--format F]",
    "Lists a mold file's faces: index, name, surface kind, degrees, poles, rational,\n"
    "trimmed (holes), reversed, area and bounding box (mm), then a summary.\n"
    "With --face N: face N alone, a point near its middle (inside its trims), the\n"
    "outward normal there and plyfit drape flags for a start from that point.\n"
    "With --neighbours: every face sewn into one shell; per face, the faces it shares\n"
    "edges with (and the crease angle there) and its free boundary (runs, length).\n"
    "With --curves: the file's curves, for --boundary and --seed-curve FILE[:PICK]: its free\n"
    "curves and wire edges (else its faces' edges), index, name, kind, length, closed, ends.\n"};

// Face `index` converted alone, and a start near its middle.
int describe_face(importers::MoldFile& file, const std::string& path, int index, bool json) {
  auto info = file.describe(index);
  if (!info) return error_exit(kExitFailure, info.error());
  auto data = file.convert_face(index);
  if (!data) return error_exit(kExitFailure, data.error());
  auto face = MoldSurface::from_face(std::move(data).value());
  if (!face) return error_exit(kExitFailure, Error(face.error()).in(path).at_face(index));
  auto s = face_start(*face);
  if (!s) return error_exit(kExitFailure, Error(s.error()).in(path).at_face(index));
  print_face_start(path, index, *info, *s, json, std::cout);
  return kExitOk;
}

// Every face of the file sewn into one shell, and each face's links.
int list_neighbours(importers::MoldFile& file, const std::string& path, bool json) {
  auto data = file.convert_shell(file.all_faces());
  if (!data) return error_exit(kExitFailure, data.error());
  const std::vector<int> sources = data->source_faces;
  auto shell = MoldSurface::from_shell(std::move(data).value());
  if (!shell) return error_exit(kExitFailure, Error(shell.error()).in(path));
  print_links(path, face_links(*shell, sources), file.summary().warnings, json, std::cout);
  return kExitOk;
}

// The file's curves (which need not bound any face).
int list_curves(const std::string& path, const importers::ImportOptions& options, bool json) {
  auto curves = importers::read_curves(path, options);
  if (!curves)
    return error_exit(kExitFailure,
                      Error{ErrorCode::kCurveFileUnreadable, path}.because(curves.error()));
  print_curves(path, *curves, json, std::cout);
  return kExitOk;
}

int run_info(const Options& o) {
  const std::string path = o.all("file").front();
  auto face = o.given("face") ? o.integer("face", 0, kMaxFace) : Result<long>(-1);
  if (!face) return error_exit(kExitUsage, face.error(), o.namer());
  const int modes = (*face >= 0) + o.given("neighbours") + o.given("curves");
  if (modes > 1)
    return error_exit(
        kExitUsage,
        Error{ErrorCode::kOptionsExclusive,
              o.given("curves") ? "curves" : "neighbours",
              {*face >= 0 ? "face" : "neighbours", o.given("curves") ? "curves" : "neighbours"}},
        o.namer());

  importers::ImportOptions options;
  options.format = o.text("format").value_or("");
  if (o.given("curves")) return list_curves(path, options, o.given("json"));
  auto file = importers::open_mold(path, options);
  if (!file) return error_exit(kExitFailure, file.error());
  if (*face >= 0) return describe_face(**file, path, static_cast<int>(*face), o.given("json"));
  if (o.given("neighbours")) return list_neighbours(**file, path, o.given("json"));
  if (o.given("json"))
    std::cout << listing_json((*file)->mold());
  else
    print_listing((*file)->mold(), std::cout);
  return kExitOk;
}

const CommandRegistrar kRegisterInfo{
    options_command("info", "list a mold file's faces (kind, degrees, trims, area, bbox)", 10,
                    {info_options, {"file", "mold file"}, kInfoHelp}, run_info)};

}  // namespace

}  // namespace plyfit::cli
