// plyfit drape --faces connected (the faces reached from the seed's face across edges no
// sharper than --max-crease) and plyfit info --neighbours, through the binary, on sample molds
// whose topology is known.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

using namespace plyfit::test;
using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The fillet joins flange and wall tangentially: what the sampled normals make of the crease
// (degrees) stays below this.
constexpr double kTangentCreaseDeg = 1e-3;
// Straight free sides: the boundary polyline's length is the side's, to the file's precision.
constexpr double kStraightLengthRel = 1e-9;
// The fillet's free sides are quarter circles: its boundary polyline's chords fall short of
// the arc by at most this (relative).
constexpr double kArcLengthRel = 1e-3;

std::string sample(const std::string& name) {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/" + name;
}

json drape_report(const std::string& flags, const Scratch& tmp) {
  const std::string out = tmp.file("out");
  const CliRun r = plyfit_run("drape " + flags + " --outputs json --quiet -o '" + out + "'", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(slurp(out + "/report.json"));
}

std::vector<int> faces_of(const json& report) {
  return report["inputs"]["faces"].get<std::vector<int>>();
}

}  // namespace

TEST_CASE("faces connected: a seed on the flange reaches the fillet and the wall (tangent joins)") {
  Scratch tmp("faces_connected");
  const std::string mold = "--mold '" + sample("flange-fillet-wall.step") + "'";
  for (const char* limit : {"", " --max-crease 60", " --max-crease 0.001"}) {
    CAPTURE(limit);
    const json j =
        drape_report(mold + " --faces connected" + limit + " --seed -20,30,0 --spacing 2", tmp);
    CHECK(faces_of(j) == std::vector<int>{0, 1, 2});
    CHECK(j["status"] == "ok");
  }
  // From the wall, and with --faces-at choosing the face (the seed elsewhere on the shell).
  CHECK(faces_of(drape_report(
            mold + " --faces connected --seed 10,30,-30 --rosette 0,1,0 --spacing 2", tmp)) ==
        std::vector<int>{0, 1, 2});
  CHECK(faces_of(drape_report(
            mold + " --faces connected --faces-at 10,30,-30 --seed -20,30,0 --spacing 2", tmp)) ==
        std::vector<int>{0, 1, 2});
  // The built-in shell as well.
  CHECK(faces_of(drape_report(
            "--mold builtin:flange-fillet-wall --faces connected --seed -20,30,0 --spacing 2",
            tmp)) == std::vector<int>{0, 1, 2});
}

TEST_CASE("faces connected: bad values and missing points are refused with their codes") {
  Scratch tmp("faces_connected_errors");
  const std::string mold = "drape --mold '" + sample("flange-fillet-wall.step") + "' --spacing 2 ";
  const std::string out = " -o '" + tmp.file("o") + "'";
  struct Case {
    std::string flags, code;
  };
  for (const Case& c : std::vector<Case>{
           {"--faces connected --seed -20,30,0 --max-crease 0", "[out_of_range]"},
           {"--faces connected --seed -20,30,0 --max-crease -5", "[out_of_range]"},
           {"--faces connected --seed -20,30,0 --max-crease 180.5", "[out_of_range]"},
           {"--faces connected --seed -20,30,0 --max-crease nan", "[not_finite]"},
           {"--faces connected --start2d 0,0 --base2d 1,0 --sweep2d 0,1 --start3d -20,30,0 "
            "--base-normal 0,1,0 --sweep3d 0,1,0",
            "[connected_needs_point]"},
           {"--faces all --seed -20,30,0 --max-crease 30", "[option_without]"},
           {"--face 0 --seed -20,30,0 --max-crease 30", "[option_without]"},
           {"--faces connected --face 1 --seed -20,30,0", "[options_exclusive]"},
       }) {
    CAPTURE(c.flags);
    const CliRun r = plyfit_run(mold + c.flags + out, tmp);
    CHECK(r.code == 2);
    CHECK(r.err.find(c.code) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("faces connected: --dump-scene keeps faces = connected and max-crease") {
  Scratch tmp("faces_connected_scene");
  const CliRun r = plyfit_run("drape --mold '" + sample("flange-fillet-wall.step") +
                                  "' --faces connected --max-crease 30 --seed -20,30,0 "
                                  "--spacing 2 --dump-scene",
                              tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("faces = connected") != std::string::npos);
  CHECK(r.out.find("max-crease = 30") != std::string::npos);
}

TEST_CASE("info --neighbours: the flange, fillet and wall sample's topology") {
  Scratch tmp("info_neighbours");
  const CliRun r =
      plyfit_run("info '" + sample("flange-fillet-wall.step") + "' --neighbours --json", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json faces = json::parse(r.out)["faces"];
  REQUIRE(faces.size() == 3);
  // Flange (0) - fillet (1) - wall (2), the defaults L = 40, r = 10, Hw = 40, W = 60.
  const std::vector<std::vector<int>> neighbours = {{1}, {0, 2}, {1}};
  const std::vector<int> runs = {1, 2, 1};
  const std::vector<double> lengths = {40 + 60 + 40, 2 * (kPi * 10 / 2), 40 + 60 + 40};
  for (std::size_t k = 0; k < 3; ++k) {
    CAPTURE(k);
    const json& f = faces[k];
    CHECK(f["index"] == static_cast<int>(k));
    std::vector<int> ns;
    for (const json& n : f["neighbours"]) {
      ns.push_back(n["face"].get<int>());
      CHECK(n["crease_deg"].get<double>() < kTangentCreaseDeg);
    }
    CHECK(ns == neighbours[k]);
    CHECK(f["free_runs"] == runs[k]);
    CHECK(f["free_length_mm"].get<double>() ==
          Approx(lengths[k]).epsilon(k == 1 ? kArcLengthRel : kStraightLengthRel));
  }

  const CliRun text =
      plyfit_run("info '" + sample("flange-fillet-wall.step") + "' --neighbours", tmp);
  REQUIRE(text.code == 0);
  CHECK(text.out.find("0: 0, 2: 0") != std::string::npos);
}

TEST_CASE("info --neighbours: the sphere as eight octants, each joined to three, no free edge") {
  Scratch tmp("info_neighbours_sphere");
  const CliRun r = plyfit_run("info '" + sample("sphere-8.step") + "' --neighbours --json", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json faces = json::parse(r.out)["faces"];
  REQUIRE(faces.size() == 8);
  std::set<std::pair<int, int>> pairs;
  for (const json& f : faces) {
    CHECK(f["neighbours"].size() == 3);
    CHECK(f["free_runs"] == 0);
    CHECK(f["free_length_mm"].get<double>() == 0.0);
    for (const json& n : f["neighbours"]) {
      CHECK(n["crease_deg"].get<double>() < kTangentCreaseDeg);
      pairs.insert({f["index"].get<int>(), n["face"].get<int>()});
    }
  }
  // Each neighbour relation both ways: 12 edges, 24 ordered pairs.
  CHECK(pairs.size() == 24);
  for (const auto& [a, b] : pairs) CHECK(pairs.count({b, a}) == 1);

  const CliRun both =
      plyfit_run("info '" + sample("sphere-8.step") + "' --neighbours --face 1", tmp);
  CHECK(both.code == 2);
  CHECK(both.err.find("[options_exclusive]") != std::string::npos);
}
