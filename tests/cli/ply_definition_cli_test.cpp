// plyfit drape --seed --rosette --ply-angle (--seed-curve): the ply a composites engineer
// defines, through the binary: the drape, flat.dxf's label and report.json agree.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/drape_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace plyfit::test;
using nlohmann::json;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// report.json (and flat.dxf) of a quiet drape with `flags`.
json quiet_report(const std::string& flags, const Scratch& tmp) {
  return drape_report(flags + " --outputs json,dxf --quiet", tmp);
}
}  // namespace

TEST_CASE(
    "cli: a plate ply at 0/45/90/-45 from seed and rosette has its outline turned by the angle") {
  for (double deg : {0.0, 45.0, 90.0, -45.0}) {
    CAPTURE(deg);
    Scratch tmp("ply_definition");
    const json j = quiet_report("--mold builtin:plate --seed 50,30,0 --rosette 1,0,0 --ply-angle " +
                                    std::to_string(deg) + " --spacing 1",
                                tmp);
    CHECK(j["status"] == "ok");
    CHECK(j["ply"]["defined_by"] == "seed");
    CHECK(j["ply"]["laid_angle_deg"].get<double>() == Approx(deg).margin(1e-9));
    const double a = deg * kDeg;
    const auto w = j["ply"]["fibre_direction"];
    CHECK(w[0].get<double>() == Approx(std::cos(a)).margin(1e-12));
    CHECK(w[1].get<double>() == Approx(std::sin(a)).margin(1e-12));
    // The outline's extent in ply coordinates: 60 x 100 turned by the angle (the warp, ply y,
    // along X at 0 deg).
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto& loop : j["flat_outline_exact"]["loops"])
      for (const auto& p : loop["points"])
        for (int k = 0; k < 2; ++k) {
          lo[k] = std::min(lo[k], p[k].get<double>());
          hi[k] = std::max(hi[k], p[k].get<double>());
        }
    const double c = std::abs(std::cos(a)), s = std::abs(std::sin(a));
    CHECK(hi[0] - lo[0] == Approx(100 * s + 60 * c).margin(1e-9));
    CHECK(hi[1] - lo[1] == Approx(100 * c + 60 * s).margin(1e-9));
    // flat.dxf's label says the same angle.
    const std::string dxf = slurp(tmp.file("out/flat.dxf"));
    char label[64];
    std::snprintf(label, sizeof label, "PLY ANGLE: %g", deg);
    CHECK(dxf.find(label) != std::string::npos);
  }
}

TEST_CASE("cli: the start flags with --ply-angle lay their drape turned by it") {
  Scratch tmp("ply_definition");
  const json j = quiet_report(
      "--mold builtin:plate --spacing 1 --start2d 0,0 --base2d 1,0 --sweep2d 0,1 --sweep2d 0,-1 "
      "--start3d 50,30,0 --base-normal 0,1,0 --sweep3d 0,1,0 --sweep3d 0,-1,0 --ply-angle 30 "
      "--rosette 1,0,0",
      tmp);
  // Base path along +X is ply +x: the warp is +Y (90 deg from X), turned by 30: 120 deg.
  CHECK(j["ply"]["defined_by"] == "start");
  CHECK(j["ply"]["laid_angle_deg"].get<double>() == Approx(120.0).margin(1e-9));
  CHECK(j["base_tangent"][0].get<double>() == Approx(std::cos(30 * kDeg)).margin(1e-12));
}

TEST_CASE("cli: a geodesic seed curve is echoed and checked in report.json") {
  Scratch tmp("ply_definition");
  const json j = quiet_report(
      "--mold builtin:cylinder:R=10,H=40,angle=180 --seed 0,10,20 --rosette 0,0,1 "
      "--ply-angle 30 --spacing 0.5 --seed-curve geodesic",
      tmp);
  CHECK(j["inputs"]["seed_curve"] == "geodesic");
  CHECK(j["ply"]["seed_curve"] == "geodesic");
  CHECK(j["residual"]["base_plane_max_rel"].get<double>() < 1e-10);
  CHECK(j["shear_max_deg"].get<double>() < 0.01);
}

TEST_CASE("cli: bad ply definitions are one-line errors naming the option") {
  Scratch tmp("ply_definition");
  const std::string base = "drape --mold builtin:plate --spacing 1 -o '" + tmp.file("o") + "' ";
  struct Case {
    std::string flags, option, code;
  };
  for (const Case& c : {Case{"--seed 50,30,900", "--seed", "seed_off_mold"},
                        Case{"--seed 50,30,0 --rosette 0,0,1", "--rosette", "rosette_along_normal"},
                        Case{"--seed 50,30,0 --start3d 1,2,3", "--start3d", "options_exclusive"},
                        Case{"--seed 50,30,0 --seed-curve spiral", "--seed-curve", "unknown_value"},
                        Case{"--seed 50,30,0 --ply-angle 200", "--ply-angle", "out_of_range"}}) {
    CAPTURE(c.flags);
    const CliRun r = plyfit_run(base + c.flags, tmp);
    CHECK(r.code != 0);
    CHECK(r.err.find(c.option) != std::string::npos);
    CHECK(r.err.find("[" + c.code + "]") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("cli: --dump-scene of a ply keeps its meaning: the scene drapes the same ply") {
  Scratch tmp("ply_definition_dump");
  // Start keys on a face whose normal at the start is +X (the default rosette's direction):
  // without --rosette their own warp is 0 deg, and the dumped scene must say the same.
  const std::string start =
      "--mold builtin:cylinder --spacing 1 --start2d 0,0 --base2d 1,0 --sweep2d 0,1 "
      "--start3d 10,0,10 --base-normal 0,0,1 --sweep3d 0,0,1 --ply-angle 30";
  // A seed with its rosette and a geodesic seed curve.
  const std::string seed =
      "--mold builtin:cylinder:angle=180 --spacing 1 --seed 0,10,10 --rosette 0,0,1 "
      "--ply-angle -30 --seed-curve geodesic";
  for (const std::string& flags : {start, seed}) {
    CAPTURE(flags);
    const CliRun d = plyfit_run("drape " + flags + " --dump-scene", tmp);
    INFO(d.err);
    REQUIRE(d.code == 0);
    spit(tmp.file("scene.ini"), d.out);
    const CliRun a = plyfit_run(
        "drape " + flags + " --outputs json --quiet -o '" + tmp.file("direct") + "'", tmp);
    const CliRun b = plyfit_run("drape '" + tmp.file("scene.ini") +
                                    "' --outputs json --quiet -o '" + tmp.file("scene") + "'",
                                tmp);
    INFO(a.err << b.err);
    REQUIRE(a.code == 0);
    REQUIRE(b.code == 0);
    const json ja = json::parse(slurp(tmp.file("direct/report.json")));
    const json jb = json::parse(slurp(tmp.file("scene/report.json")));
    CHECK(ja["ply"] == jb["ply"]);
    CHECK(ja["nodes"] == jb["nodes"]);
    CHECK(ja["ply"]["laid_angle_deg"].get<double>() ==
          Approx(flags == start ? 30.0 : -30.0).margin(1e-9));
  }
}

TEST_CASE("cli: --faces-at drapes the face under the point") {
  Scratch tmp("ply_definition_faces_at");
  // The sample shell's flange, fillet and wall: three faces; the point plyfit info gives for
  // each face lies on it, and --faces-at finds that face again.
  const std::string file =
      std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/flange-fillet-wall.step";
  for (int face : {0, 1, 2}) {
    CAPTURE(face);
    const CliRun info =
        plyfit_run("info '" + file + "' --face " + std::to_string(face) + " --json", tmp);
    REQUIRE(info.code == 0);
    const json p = json::parse(info.out)["point"];
    const std::string at = std::to_string(p[0].get<double>()) + "," +
                           std::to_string(p[1].get<double>()) + "," +
                           std::to_string(p[2].get<double>());
    const json j = quiet_report(
        "--mold '" + file + "' --faces-at " + at + " --seed " + at + " --rosette 1,1,1 --spacing 2",
        tmp);
    CHECK(j["inputs"]["face"] == face);
  }
  const CliRun both = plyfit_run("drape --mold '" + file +
                                     "' --faces-at 0,0,0 --face 1 --seed 0,0,0 --spacing 2 -o '" +
                                     tmp.file("o") + "'",
                                 tmp);
  CHECK(both.code != 0);
  CHECK(both.err.find("[options_exclusive]") != std::string::npos);
}
