// plyfit drape --seed-curve FILE[:PICK]: the base path follows a curve of a CSV file, through
// the binary; its errors as codes.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <string>

using namespace plyfit::test;
using nlohmann::json;

namespace {
const std::string kPlate =
    "drape --mold builtin:plate --seed 50,30.5,0 --rosette 1,0,0 --ply-angle 90 --spacing 1 "
    "--quiet";

std::string write(const Scratch& tmp, const std::string& name, const std::string& text) {
  const std::string path = tmp.file(name);
  spit(path, text);
  return path;
}

json report(const std::string& out) {
  return json::parse(slurp(out + "/report.json"));
}
}  // namespace

TEST_CASE("cli: a seed curve along the plate's section gives the plane case's drape") {
  Scratch tmp("seed_curve_cli");
  // The warp at 90 deg from +X about +Z runs along +Y: the section x = 50 across the plate
  // (0..100 x 0..60), an open polyline, the second of two blocks. Both paths stop at the
  // plate's edges, half a link past their last nodes.
  const std::string csv = write(tmp, "lines.csv",
                                "10,10,0\n90,10,0\n\n"
                                "50,0,0\n50,20,0\n50,40,0\n50,60,0\n");
  const CliRun plane = plyfit_run(kPlate + " -o '" + tmp.file("plane") + "'", tmp);
  INFO(plane.err);
  REQUIRE(plane.code == 0);
  const CliRun curve =
      plyfit_run(kPlate + " --seed-curve '" + csv + ":1' -o '" + tmp.file("curve") + "'", tmp);
  INFO(curve.err);
  REQUIRE(curve.code == 0);
  const json p = report(tmp.file("plane")), c = report(tmp.file("curve"));
  CHECK(c["inputs"]["seed_curve"] == "file");
  CHECK(c["inputs"]["seed_curve_file"] == csv + ":1");
  CHECK(c["ply"]["seed_curve"] == "curve");
  CHECK(c["status"] == "ok");
  CHECK(c["nodes"]["mapped"] == p["nodes"]["mapped"]);
  CHECK(c["flat_outline_exact"]["area"].get<double>() ==
        Approx(p["flat_outline_exact"]["area"].get<double>()).epsilon(1e-12));
  CHECK(c["ply"]["laid_angle_deg"].get<double>() == Approx(90.0).margin(1e-9));
}

TEST_CASE("cli: seed curve errors: several curves, off the mold, missing the seed") {
  Scratch tmp("seed_curve_cli_errors");
  const std::string two = write(tmp, "two.csv", "0,10,0\n100,10,0\n\n0,30,0\n100,30,0\n");
  const CliRun several = plyfit_run(kPlate + " --seed-curve '" + two + "' -o o", tmp);
  INFO(several.err);
  CHECK(error_code(several) == "seed_curve_one_curve");
  const std::string high = write(tmp, "high.csv", "50,0,5\n50,60,5\n");
  const CliRun off = plyfit_run(kPlate + " --seed-curve '" + high + "' -o o", tmp);
  INFO(off.err);
  CHECK(error_code(off) == "seed_curve_off_mold");
  const CliRun miss = plyfit_run(kPlate + " --seed-curve '" + two + ":0' -o o", tmp);
  INFO(miss.err);
  CHECK(error_code(miss) == "seed_not_on_curve");
  const CliRun word = plyfit_run(kPlate + " --seed-curve geodesc -o o", tmp);
  CHECK(error_code(word) == "unknown_value");
}
