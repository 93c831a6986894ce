// plyfit drape --boundary (--boundary-offset): a ply bounded by closed curves of a CSV file,
// through the binary; every bad boundary a one-line error with its code.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/drape_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

using namespace plyfit::test;
using nlohmann::json;

namespace {
constexpr double kPiT = 3.14159265358979323846;

// A CSV circle of radius r about (cx, cy, z), n points, with a comment line.
std::string circle_csv(double cx, double cy, double z, double r, int n = 720) {
  std::string s = "# a circle\n";
  char buf[128];
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPiT * i / n;
    std::snprintf(buf, sizeof buf, "%.12g, %.12g, %.12g\n", cx + r * std::cos(t),
                  cy + r * std::sin(t), z);
    s += buf;
  }
  return s;
}

std::string write(const Scratch& tmp, const std::string& name, const std::string& text) {
  const std::string path = tmp.file(name);
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST_CASE("cli: the issue's command drapes a 45 deg ply whose outline is the circle") {
  Scratch tmp("boundary_cli");
  const std::string csv = write(tmp, "circle.csv", circle_csv(50, 30, 0, 20));
  const json j = drape_report(
      "--mold builtin:plate --seed 50,30,0 --rosette 1,0,0 --ply-angle 45 --boundary '" + csv +
          "' --spacing 1 --quiet",
      tmp);
  CHECK(j["status"] == "ok");
  CHECK(j["ply"]["laid_angle_deg"].get<double>() == Approx(45.0).margin(1e-9));
  const double exact = 400 * kPiT;
  CHECK(j["flat_outline_exact"]["area"].get<double>() == Approx(exact).epsilon(1e-3));
  const auto& b = j["ply"]["boundary"];
  CHECK(b["area"].get<double>() == Approx(exact).epsilon(1e-3));
  REQUIRE(b["loops"].size() == 1);
  CHECK(b["loops"][0]["length"].get<double>() == Approx(40 * kPiT).epsilon(1e-4));
  double worst = 0.0;
  for (const auto& loop : j["flat_outline_exact"]["loops"])
    for (const auto& p : loop["points"])
      worst = std::max(worst, std::abs(std::hypot(p[0].get<double>(), p[1].get<double>()) - 20));
  CHECK(worst < 0.01);
  // net.step carries the boundary's loops on the mold.
  CHECK(slurp(tmp.file("out") + "/net.step").find("boundary_curves") != std::string::npos);
}

TEST_CASE("cli: a scene's boundary is relative to it, and --dump-scene keeps it and its offset") {
  Scratch tmp("boundary_cli_scene");
  write(tmp, "loops.csv", circle_csv(50, 30, 0, 20) + "\n" + circle_csv(50, 30, 0, 5, 90));
  const std::string scene =
      write(tmp, "ply.ini",
            "[mold]\nmold = builtin:plate\n[ply]\nspacing = 1\n[start]\nseed = 40,30,0\n"
            "boundary = loops.csv:0,1\nboundary-offset = 1\n");
  const CliRun d = plyfit_run("drape '" + scene + "' --dump-scene", tmp);
  INFO(d.err);
  REQUIRE(d.code == 0);
  CHECK(d.out.find("boundary = ") != std::string::npos);
  CHECK(d.out.find("loops.csv:0,1") != std::string::npos);
  CHECK(d.out.find("boundary-offset = 1") != std::string::npos);
  const json j = drape_report("'" + scene + "' --outputs json --quiet", tmp);
  // Grown by 1: the ring between radii 21 and 4 (the inner loop is a cut-out, shrunk by 1).
  const double ring = kPiT * (21.0 * 21.0 - 4.0 * 4.0);
  CHECK(j["ply"]["boundary"]["area"].get<double>() == Approx(ring).epsilon(2e-3));
  CHECK(j["flat_outline_exact"]["area"].get<double>() == Approx(ring).epsilon(2e-3));
}

TEST_CASE("cli: bad boundaries are one-line errors with their codes") {
  Scratch tmp("boundary_cli_errors");
  const std::string base = "drape --mold builtin:plate --spacing 1 --seed 50,30,0 -o '" +
                           tmp.file("o") + "' --boundary ";
  // (A gap between curves needs open curves: a CSV block is closed; the kernel tests it.)
  struct Case {
    std::string file, code;
  };
  const std::string circle = write(tmp, "circle.csv", circle_csv(50, 30, 0, 20));
  for (const Case& c : {
           Case{write(tmp, "high.csv", circle_csv(50, 30, 3, 20)), "boundary_off_mold"},
           Case{write(tmp, "off.csv", circle_csv(10, 10, 0, 5)), "boundary_seed_outside"},
           Case{write(tmp, "empty.csv", "# nothing\n\n"), "boundary_empty"},
           Case{write(tmp, "bad.csv", "1,2,3\n4,5\n"), "curve_file_syntax"},
           Case{write(tmp, "two.csv", "1,2,0\n4,5,0\n"), "boundary_curve_points"},
           Case{tmp.file("missing.csv"), "curve_file_cannot_open"},
           Case{write(tmp, "loops.txt", "1,2,3\n"), "curve_file_format"},
           Case{circle + ":3", "curve_not_found"},
       }) {
    CAPTURE(c.file);
    const CliRun r = plyfit_run(base + "'" + c.file + "'", tmp);
    CHECK(r.code != 0);
    CHECK(r.err.find("[" + c.code + "]") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("cli: a boundary across a file's shell drapes as across the built-in shell") {
  // The circle of radius 24 of the flange + fillet + wall's development crosses its three
  // faces and both shared edges twice; read from STEP or IGES, the shell's shared edges are
  // polylines of many segments, each face's use cut by the boundary. Developable: the flat
  // outline's area is the circle's, 576 pi.
  Scratch tmp("boundary_cli_file_shell");
  const std::string samples = std::string(PLYFIT_SOURCE_DIR) + "/samples/";
  const double exact = 576 * kPiT;
  for (const std::string& mold :
       {std::string("builtin:flange-fillet-wall"), samples + "molds/flange-fillet-wall.step",
        samples + "molds/flange-fillet-wall.igs"}) {
    CAPTURE(mold);
    const json j =
        drape_report("--mold '" + mold +
                         "' --faces all --spacing 1 --seed -5,30,0 --rosette 0,1,0 --boundary '" +
                         samples + "plies/flange-fillet-wall-circle.csv' --quiet --outputs json",
                     tmp);
    CHECK(j["status"] == "ok");
    CHECK(j["ply"]["boundary"]["area"].get<double>() == Approx(exact).epsilon(1e-3));
    CHECK(j["flat_outline_exact"]["area"].get<double>() == Approx(exact).epsilon(1e-3));
  }
}

TEST_CASE("cli: loops winding round a tube bound a band, or the side that holds the seed") {
  // samples/molds/tube.step: the cylinder of radius 10 from z = 0 to 20, one face closed on
  // itself. A circle round it is no area on the face but a side of it: two circles make the
  // band between them, one the side that holds the seed.
  Scratch tmp("boundary_cli_winding");
  const auto ring = [](double z) {
    std::string s;
    char buf[128];
    for (int i = 0; i < 360; ++i) {
      const double t = 2 * kPiT * i / 360;
      std::snprintf(buf, sizeof buf, "%.12g, %.12g, %.12g\n", 10 * std::cos(t), 10 * std::sin(t),
                    z);
      s += buf;
    }
    return s;
  };
  const std::string band = write(tmp, "band.csv", ring(5) + "\n" + ring(15));
  const std::string one = write(tmp, "ring.csv", ring(5));
  const std::string tube = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/tube.step";
  // Each circle lies on the tube, at one height: in the face's (u, v) a line across it, so the
  // region is the tube's own between heights, 2 pi r per unit of height.
  const double per_mm = 2 * kPiT * 10;
  struct Case {
    std::string csv, seed;
    double area;
  };
  for (const Case& c : {Case{band, "0,10,10", 10 * per_mm}, Case{one, "0,10,10", 15 * per_mm},
                        Case{one, "0,10,2", 5 * per_mm}}) {
    CAPTURE(c.csv, c.seed);
    const json j = drape_report("--mold '" + tube + "' --seed " + c.seed +
                                    " --rosette 0,0,1 --spacing 0.5 --boundary '" + c.csv +
                                    "' --quiet --outputs json",
                                tmp);
    CHECK(j["ply"]["boundary"]["area"].get<double>() == Approx(c.area).epsilon(1e-5));
  }
  const CliRun off =
      plyfit_run("drape --mold '" + tube + "' --seed 0,10,2 --spacing 0.5 --boundary '" + band +
                     "' -o '" + tmp.file("o2") + "'",
                 tmp);
  CHECK(off.err.find("[boundary_seed_outside]") != std::string::npos);
}
