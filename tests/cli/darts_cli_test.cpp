// plyfit drape --dart FILE[:PICK]: a ply cut along curves on the part, through the binary: the
// report's darts, flat.dxf's DART layer, net.step's darts; errors as codes naming the option.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <string>

using namespace plyfit::test;
using nlohmann::json;

namespace {
const std::string kPlate =
    "drape --mold builtin:plate --seed 50,30.5,0 --rosette 1,0,0 --spacing 1 --quiet";

std::string write(const Scratch& tmp, const std::string& name, const std::string& text) {
  const std::string path = tmp.file(name);
  spit(path, text);
  return path;
}
}  // namespace

TEST_CASE("cli: a dart on the plate is reported, drawn in flat.dxf and carried in net.step") {
  Scratch tmp("darts_cli");
  // From the plate's edge y = 0 up to (40, 20): an open CSV polyline.
  const std::string csv = write(tmp, "dart.csv", "30,0,0\n40,20,0\n");
  const CliRun plain = plyfit_run(kPlate + " -o '" + tmp.file("plain") + "'", tmp);
  REQUIRE(plain.code == 0);
  const CliRun cut = plyfit_run(kPlate + " --dart '" + csv + "' -o '" + tmp.file("cut") + "'", tmp);
  INFO(cut.err);
  REQUIRE(cut.code == 0);
  const json p = json::parse(slurp(tmp.file("plain") + "/report.json"));
  const json c = json::parse(slurp(tmp.file("cut") + "/report.json"));
  CHECK(p.count("darts") == 0);
  REQUIRE(c["darts"]["darts"].size() == 1);
  CHECK(c["darts"]["source"][0] == csv);
  const json& d = c["darts"]["darts"][0];
  CHECK(d["length"].get<double>() == Approx(std::sqrt(500.0)).epsilon(1e-12));
  // A plane: both sides drape as the uncut ply; the cut lines coincide.
  CHECK(d["removed_area"].get<double>() < 1e-9);
  CHECK(d["opening_area"].get<double>() < 1e-9);
  CHECK(d["links_cut"].get<int>() > 0);
  CHECK(c["status"] == "ok");
  CHECK(c["nodes"]["mapped"] == p["nodes"]["mapped"]);
  CHECK(c["flat_outline"]["area"].get<double>() ==
        Approx(p["flat_outline"]["area"].get<double>()).epsilon(1e-12));
  const std::string dxf = slurp(tmp.file("cut") + "/flat.dxf");
  CHECK(dxf.find("\nDART\n") != std::string::npos);
  CHECK(slurp(tmp.file("plain") + "/flat.dxf").find("\nDART\n") == std::string::npos);
  CHECK(slurp(tmp.file("cut") + "/net.step").find("'darts'") != std::string::npos);
}

TEST_CASE("cli: dart errors: a missing file, a curve off the mold, name the option") {
  Scratch tmp("darts_cli_errors");
  const CliRun missing = plyfit_run(kPlate + " --dart '" + tmp.file("none.csv") + "' -o o", tmp);
  INFO(missing.err);
  CHECK(missing.code != 0);
  CHECK(error_code(missing) == "curve_file_cannot_open");
  CHECK(missing.err.find("--dart") != std::string::npos);
  const std::string high = write(tmp, "high.csv", "30,0,5\n40,20,5\n");
  const CliRun off = plyfit_run(kPlate + " --dart '" + high + "' -o o", tmp);
  INFO(off.err);
  CHECK(error_code(off) == "dart_off_mold");
  CHECK(off.err.find("--dart") != std::string::npos);
}

TEST_CASE("cli: --darts takes auto or none, and names the option otherwise") {
  Scratch tmp("darts_cli_auto");
  const CliRun bad = plyfit_run(kPlate + " --darts foo -o o", tmp);
  INFO(bad.err);
  CHECK(error_code(bad) == "unknown_value");
  CHECK(bad.err.find("--darts") != std::string::npos);
  // A plate needs no dart: one drape, laid, no dart proposed.
  const CliRun plate = plyfit_run(kPlate + " --darts auto -o '" + tmp.file("plate") + "'", tmp);
  INFO(plate.err);
  REQUIRE(plate.code == 0);
  const json c = json::parse(slurp(tmp.file("plate") + "/report.json"));
  CHECK(c["darts"]["auto"] == true);
  CHECK(c["darts"]["drapes"] == 1);
  CHECK(c["darts"]["laid"] == true);
  CHECK(c["darts"]["darts"].empty());
}

TEST_CASE("cli: automatic darts lay the closed hemisphere sample within a 40 degree lock") {
  Scratch tmp("darts_cli_hemisphere");
  const std::string scene = std::string(PLYFIT_SOURCE_DIR) + "/samples/hemisphere.ini";
  const std::string flags = " --lock-angle 40 --outputs json --quiet -o '";
  const CliRun plain = plyfit_run("drape '" + scene + "'" + flags + tmp.file("plain") + "'", tmp);
  REQUIRE(plain.code == 0);
  const json p = json::parse(slurp(tmp.file("plain") + "/report.json"));
  REQUIRE(p["nodes"]["shear_limit"].get<int>() > 0);  // the lock stops the cloth without darts
  const CliRun cut =
      plyfit_run("drape '" + scene + "' --darts auto" + flags + tmp.file("cut") + "'", tmp);
  INFO(cut.err);
  REQUIRE(cut.code == 0);
  const json c = json::parse(slurp(tmp.file("cut") + "/report.json"));
  CHECK(c["darts"]["laid"] == true);
  CHECK(c["darts"]["drapes"].get<int>() <= 3);
  CHECK(c["nodes"]["conflict"] == 0);
  CHECK(c["nodes"]["shear_limit"] == 0);
  CHECK(c["shear_max_deg"].get<double>() <= 40.0);
  CHECK(c["status"] == "ok");
}
