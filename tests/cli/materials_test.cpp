// The materials table: --material picks an entry of plyfit's own table (data/materials.ini,
// built in) or of --materials FILE; its warning and limit angles are the defaults of
// --warn-angle and --lock-angle; one-line errors name the table and list the known names.
// Also: the manual (docs/) agrees with the table and with samples/sphere-octant-a.ini.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/markdown.hpp"

#include <regex>
#include <set>

using namespace plyfit::test;
using nlohmann::json;

namespace {

const std::string& kFlags = kOctantFlags;

// The value of the first `key = ...` line of a dumped scene or another INI text.
std::string dumped(const std::string& dump, const std::string& key) {
  const std::regex re("(^|\n)" + key + " = ([^\n]*)");
  std::smatch m;
  return std::regex_search(dump, m, re) ? m[2].str() : std::string("<absent>");
}

// The [sections] of an INI text.
std::set<std::string> sections(const std::string& ini) {
  std::set<std::string> out;
  const std::regex re(R"((^|\n)\[([A-Za-z0-9_-]+)\])");
  for (auto it = std::sregex_iterator(ini.begin(), ini.end(), re); it != std::sregex_iterator();
       ++it)
    out.insert((*it)[2].str());
  return out;
}

}  // namespace

TEST_CASE("cli: the default material warns at 25 degrees and imposes no lock") {
  Scratch tmp("materials_default");
  const CliRun d = plyfit_run("drape " + kFlags + " --dump-scene", tmp);
  INFO(d.err);
  REQUIRE(d.code == 0);
  CHECK(dumped(d.out, "material") == "woven");
  CHECK(dumped(d.out, "lock-angle") == "90");
  CHECK(dumped(d.out, "warn-angle") == "25");
  CHECK(dumped(d.out, "ply-angle") == "0");
  CHECK(dumped(d.out, "dxf-threads") == "false");
  CHECK(dumped(d.out, "materials") == "<absent>");
  // The drape's report says so too, with the material's label.
  const CliRun r =
      plyfit_run("drape " + kFlags + " --outputs json -o '" + tmp.file("o") + "'", tmp);
  REQUIRE(r.code == 0);
  const json j = json::parse(slurp(tmp.file("o") + "/report.json"));
  CHECK(j["inputs"]["material"] == "woven");
  CHECK(j["inputs"]["material_label"] == "woven fabric");
  CHECK(j["inputs"]["lock_angle_deg"] == 90.0);
  CHECK(j["inputs"]["warn_angle_deg"] == Approx(25.0).epsilon(1e-15));
  CHECK(j["inputs"]["ply_angle_deg"] == 0.0);
  CHECK(j["nodes"]["shear_limit"] == 0);
}

TEST_CASE("cli: a material sets the lock and warning angles unless the flags do") {
  Scratch tmp("materials_pick");
  struct Case {
    std::string flags, lock, warn;
  };
  for (const Case& c : std::vector<Case>{
           {"--material carbon-twill", "40", "30"},
           {"--material glass-satin8", "50", "40"},
           {"--material carbon-twill --lock-angle 60", "60", "30"},
           {"--material carbon-twill --lock-angle 20", "20", "15"},  // at most lock - 5
           {"--material carbon-twill --warn-angle 12", "40", "12"},
           {"--lock-angle 20", "20", "15"},
       }) {
    INFO(c.flags);
    const CliRun d = plyfit_run("drape " + kFlags + " " + c.flags + " --dump-scene", tmp);
    INFO(d.err);
    REQUIRE(d.code == 0);
    CHECK(dumped(d.out, "lock-angle") == c.lock);
    CHECK(dumped(d.out, "warn-angle") == c.warn);
  }
  // The limit stops the drape: case (a) shears to 49.5 degrees, the twill locks at 40.
  const CliRun r = plyfit_run(
      "drape " + kFlags + " --material carbon-twill --outputs json -o '" + tmp.file("o") + "'",
      tmp);
  REQUIRE(r.code == 0);
  const json j = json::parse(slurp(tmp.file("o") + "/report.json"));
  CHECK(j["nodes"]["shear_limit"].get<int>() > 0);
  CHECK(j["shear_max_deg"].get<double>() <= 40.0);
  CHECK(j["inputs"]["material_label"] == "carbon 2/2 twill");
}

TEST_CASE("cli: an unknown material or a bad table is a one-line error naming the table") {
  Scratch tmp("materials_errors");
  CliRun r = plyfit_run("drape " + kFlags + " --material kevlar --dump-scene", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "unknown_material");
  // The option, the table, the name asked for and the known ones.
  CHECK(r.err.rfind("plyfit: error: --material: plyfit's materials table (data/materials.ini): ",
                    0) == 0);
  CHECK(r.err.find("'kevlar'") != std::string::npos);
  CHECK(r.err.find("carbon-twill") != std::string::npos);

  const std::string own = tmp.file("own.ini");
  spit(own, "# mine\n[wet-layup]\nlabel = my fabric\nwarning = 20\nlimit = 38\n");
  r = plyfit_run("drape " + kFlags + " --materials '" + own + "' --material wet-layup --dump-scene",
                 tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(dumped(r.out, "lock-angle") == "38");
  CHECK(dumped(r.out, "warn-angle") == "20");
  CHECK(dumped(r.out, "materials") == own);
  // Your own table replaces plyfit's: the default material is not in it.
  r = plyfit_run("drape " + kFlags + " --materials '" + own + "' --dump-scene", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "unknown_material");
  CHECK(r.err.rfind("plyfit: error: --material: " + own + ": ", 0) == 0);
  CHECK(r.err.find("'woven'") != std::string::npos);
  CHECK(r.err.find("wet-layup") != std::string::npos);

  // A bad table: the option, the file and line, the code.
  struct Bad {
    std::string text, place, code;
  };
  for (const Bad& b : std::vector<Bad>{
           {"[a]\nwarning = 20\nlimit = 3O\n", ":3", "material_angle_not_a_number"},
           {"[a]\nwarning = 95\nlimit = none\n", ":2", "material_angle_range"},
           {"[a]\nwarning = 40\nlimit = 30\n", ":1", "warning_above_limit"},
           {"[a]\nwarning = 20\n", ":1", "material_angle_missing"},
           {"[a]\nwarn = 20\nlimit = 30\n", ":2", "unknown_key"},
           {"warning = 20\n", ":1", "key_outside_material"},
           {"[a b]\n", ":1", "material_name_invalid"},
           {"[a]\nwarning = 1\nlimit = 2\n[a]\n", ":4", "material_repeated"},
           {"[a]\nlabel =\nwarning = 1\nlimit = 2\n", ":2", "material_label_empty"},
           {"[a]\nwarning = 1\nlimit = 2\nno equals sign\n", ":4", "ini_syntax"},
           {"# nothing\n", "", "no_materials"},
       }) {
    INFO(b.text);
    spit(own, b.text);
    r = plyfit_run("drape " + kFlags + " --materials '" + own + "' --material a --dump-scene", tmp);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(error_code(r) == b.code);
    CHECK(r.err.rfind("plyfit: error: --materials: " + own + b.place + ": ", 0) == 0);
  }
  r = plyfit_run("drape " + kFlags + " --materials '" + tmp.file("none.ini") + "' --dump-scene",
                 tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "materials_cannot_open");
  CHECK(r.err.rfind("plyfit: error: --materials: " + tmp.file("none.ini") + ": ", 0) == 0);
  // From a scene: the path is relative to the scene's folder, and a bad value fails the job (1).
  spit(own, "[wet-layup]\nwarning = 20\nlimit = 38\n");
  spit(tmp.file("s.ini"),
       "[mold]\nmold = builtin:sphere-octant\n[ply]\nspacing = 1\n[start]\n"
       "start2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\nstart3d = 0,0,20\n"
       "base-normal = 0,1,0\nsweep3d = 0,1,0\n[material]\n"
       "materials = own.ini\nmaterial = wet-layup\n");
  r = plyfit_run("drape '" + tmp.file("s.ini") + "' --dump-scene", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(dumped(r.out, "lock-angle") == "38");
  spit(tmp.file("s.ini"), slurp(tmp.file("s.ini")) + "ply-angle = 200\n");
  r = plyfit_run("drape '" + tmp.file("s.ini") + "' --dump-scene", tmp);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "out_of_range");
  CHECK(r.err.rfind("plyfit: error: " + tmp.file("s.ini") + ": key 'ply-angle': ", 0) == 0);
  // A bad table named by a scene fails the job (1), the scene's key named.
  spit(own, "[wet-layup]\nwarning = 20\n");
  spit(tmp.file("s.ini"),
       slurp(tmp.file("s.ini")).substr(0, slurp(tmp.file("s.ini")).find("ply-angle")));
  r = plyfit_run("drape '" + tmp.file("s.ini") + "' --dump-scene", tmp);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "material_angle_missing");
  CHECK(r.err.rfind("plyfit: error: " + tmp.file("s.ini") + ": key 'materials': " + own + ":1: ",
                    0) == 0);
}

TEST_CASE(
    "cli: docs/materials.md lists every material of the table with its label and angles, "
    "and docs/scene-files.md shows the sample scene as it is") {
  const std::string doc = source_file("docs/materials.md");
  const std::string table = source_file("data/materials.ini");
  const auto names = sections(table);
  REQUIRE(names.size() >= 5);
  for (const auto& n : names) {
    INFO(n);
    const auto row = table_row(doc, "`" + n + "`");
    REQUIRE(row);
    REQUIRE(row->size() == 5);
    std::string entry = table.substr(table.find("[" + n + "]"));
    entry = entry.substr(0, entry.find("\n[", 1));  // this section alone
    CHECK((*row)[1].find(dumped(entry, "label")) != std::string::npos);
    CHECK((*row)[2] == dumped(entry, "warning") + "°");
    const std::string limit = dumped(entry, "limit");
    CHECK((*row)[3] == (limit == "none" ? limit : limit + "°"));
    const std::string roll = dumped(entry, "roll-width");
    CHECK((*row)[4] == (roll == "<absent>" ? "none" : roll + " mm"));
  }
  // The scene example is samples/sphere-octant-a.ini, verbatim.
  const std::string sample = source_file("samples/sphere-octant-a.ini");
  CHECK(source_file("docs/scene-files.md").find("```ini\n" + sample + "```\n") !=
        std::string::npos);
}

TEST_CASE("cli: report.json echoes the angles as given, not through radians and back") {
  // 30 and 15 degrees become 29.999999999999996 and 14.999999999999998 through radians.
  Scratch tmp("materials_echo");
  for (const auto& [flags, warn] : std::vector<std::pair<std::string, double>>{
           {"--warn-angle 30", 30.0}, {"--material cpd-example", 15.0}}) {
    INFO(flags);
    const CliRun r = plyfit_run(
        "drape " + kFlags + " " + flags + " --outputs json -o '" + tmp.file("o") + "'", tmp);
    REQUIRE(r.code == 0);
    const json j = json::parse(slurp(tmp.file("o") + "/report.json"));
    CHECK(j["inputs"]["warn_angle_deg"].get<double>() == warn);
  }
}

TEST_CASE("cli: --dump-scene writes the effective min-width") {
  // Not given: the default the flat pattern takes, half the larger spacing.
  Scratch tmp("materials_min_width");
  const CliRun d = plyfit_run("drape " + kFlags + " --dump-scene", tmp);
  REQUIRE(d.code == 0);
  const std::string spacing = dumped(d.out, "spacing");
  REQUIRE(spacing != "<absent>");
  CHECK(std::stod(dumped(d.out, "min-width")) == 0.5 * std::stod(spacing));
  const CliRun g = plyfit_run("drape " + kFlags + " --min-width 0.25 --dump-scene", tmp);
  REQUIRE(g.code == 0);
  CHECK(dumped(g.out, "min-width") == "0.25");
}
