// plyfit drape --roll-width and plyfit laminate's stagger end to end on the built-in cylinder
// sector (R 10, H 20, 90 degrees; the warp along its generators, the ply R pi / 2 = 15.71 wide
// across it): the pieces and seams in report.json, flat.dxf and net.step against closed forms,
// a ply narrower than the roll unchanged, bad values naming their option, and a laminate of
// four plies whose seams keep the stagger, measured on the part here.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/rejected.hpp"

#include <cmath>
#include <set>

using namespace plyfit::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr double kR = 10, kH = 20, kPi = 3.14159265358979323846;
constexpr double kWidth = kR * kPi / 2;  // the ply across the warp
constexpr double kD = 0.2;               // spacing
// Areas of the cut outline within 0.1 % of the exact R alpha H at d = 1/100 of the part.
constexpr double kAreaRel = 1e-3;
// How far a point interpolated in the net lies inside the cylinder: the chord's sagitta.
constexpr double kSag = kD * kD / (8 * kR);

const std::string kCylinder =
    "--mold builtin:cylinder:R=10,H=20,angle=90 --seed 7.0710678118654755,7.0710678118654755,10 "
    "--rosette 0,0,1 --spacing 0.2";

json report_of(const Scratch& s, const std::string& dir) {
  return json::parse(slurp(s.file(dir + "/report.json")));
}

// The smallest distance between two sets of polylines (vertices to segments, both ways).
double point_segment(const json& p, const json& a, const json& b) {
  double ab[3], ap[3], ee = 0, t = 0;
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k].get<double>() - a[k].get<double>();
    ap[k] = p[k].get<double>() - a[k].get<double>();
    ee += ab[k] * ab[k];
    t += ab[k] * ap[k];
  }
  t = ee > 0 ? std::clamp(t / ee, 0.0, 1.0) : 0.0;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += std::pow(ap[k] - t * ab[k], 2);
  return std::sqrt(d2);
}

double seams_distance(const json& a, const json& b) {
  double best = INFINITY;
  for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}})
    for (const auto& seam : *from)
      for (const auto& line : seam["polylines"])
        for (const auto& p : line)
          for (const auto& other : *to)
            for (const auto& l : other["polylines"])
              for (std::size_t k = 0; k + 1 < l.size(); ++k)
                best = std::min(best, point_segment(p, l[k], l[k + 1]));
  return best;
}

}  // namespace

TEST_CASE("cli splices: a cylinder ply 2.5 roll widths wide is cut into 3 pieces") {
  Scratch s("splices_cylinder");
  const double W = kWidth / 2.5;
  for (const double o : {0.0, 0.5}) {
    INFO("overlap " << o);
    const std::string dir = o == 0.0 ? "butt" : "lap";
    const CliRun r = plyfit_run("drape " + kCylinder + " --ply-name P1 --roll-width " +
                                    std::to_string(W) + " --splice-overlap " + std::to_string(o) +
                                    " --outputs json,dxf,step -o '" + s.file(dir) + "'",
                                s);
    INFO(r.err);
    REQUIRE(r.code == 0);
    const json j = report_of(s, dir);
    REQUIRE(j.contains("pieces"));
    REQUIRE(j["pieces"].size() == 3);
    CHECK(j["pieces"][0]["name"] == "P1A");
    CHECK(j["pieces"][2]["name"] == "P1C");
    double sum = 0;
    for (const auto& p : j["pieces"]) {
      CHECK(p["width"].get<double>() <= W * (1 + 1e-9));
      sum += p["area"].get<double>();
    }
    // The union of the pieces is the ply; each of the two seams' overlap strips o x H counts
    // twice.
    CHECK(sum == Approx(kR * kPi / 2 * kH + 2 * o * kH).epsilon(kAreaRel));
    CHECK(sum - 2 * o * kH == Approx(j["flat_outline"]["area"].get<double>()).epsilon(1e-9));
    const json& seams = j["splices"]["seams"];
    REQUIRE(seams.size() == 2);
    CHECK(j["splices"]["roll_width"].get<double>() == Approx(W).epsilon(1e-6));
    CHECK(j["splices"]["overlap"].get<double>() == o);
    for (const auto& seam : seams) {
      // A generator of the cylinder, the full height.
      CHECK(seam["length_3d"].get<double>() == Approx(kH).epsilon(kAreaRel));
      for (const auto& line : seam["polylines"])
        for (const auto& p : line)
          CHECK(std::hypot(p[0].get<double>(), p[1].get<double>()) == Approx(kR).margin(2 * kSag));
    }
    // flat.dxf: a layer per piece, the seams; net.step: the seams as curves.
    const std::string dxf = slurp(s.file(dir + "/flat.dxf"));
    for (const char* layer : {"PIECE_P1A", "PIECE_P1B", "PIECE_P1C", "SEAMS"})
      CHECK(dxf.find(std::string("\n") + layer + "\n") != std::string::npos);
    CHECK(slurp(s.file(dir + "/net.step")).find("'splice_seams'") != std::string::npos);
  }
}

TEST_CASE("cli splices: a ply narrower than the roll is one piece, its outputs unchanged") {
  Scratch s("splices_narrow");
  const CliRun a = plyfit_run("drape " + kCylinder + " -o '" + s.file("plain") + "'", s);
  const CliRun b =
      plyfit_run("drape " + kCylinder + " --roll-width 1270 -o '" + s.file("roll") + "'", s);
  REQUIRE(a.code == 0);
  REQUIRE(b.code == 0);
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(s.file("plain")))
    files.insert(e.path().filename().string());
  REQUIRE(files.count("flat.dxf") == 1);
  for (const auto& f : files) {
    INFO(f);
    if (f == "report.json") {
      json x = report_of(s, "plain"), y = report_of(s, "roll");
      x.erase("timing_ms");
      y.erase("timing_ms");
      CHECK(x == y);
      CHECK_FALSE(y.contains("pieces"));
    } else {
      CHECK(slurp(s.file("plain/" + f)) == slurp(s.file("roll/" + f)));
    }
  }
}

TEST_CASE("cli splices: bad values are errors naming the option") {
  Scratch s("splices_bad");
  check_rejected(
      "drape " + kCylinder,
      {
          {"--roll-width 0.39", 2, "roll_narrower_than_cells", "--roll-width"},
          {"--roll-width 6 --splice-overlap -1", 2, "splice_overlap_negative", "--splice-overlap"},
          {"--roll-width 6 --splice-overlap 6", 2, "splice_overlap_too_wide", "--splice-overlap"},
          {"--roll-width 6 --splice-overlap 5.9", 2, "splice_overlap_too_wide", "--splice-overlap"},
          {"--roll-width x", 2, "not_a_number", "--roll-width"},
          {"--roll-width nan", 2, "not_finite", "--roll-width"},
          {"--roll-width 6 --splice-overlap inf", 2, "not_finite", "--splice-overlap"},
      },
      s);
  // In a scene file the error names the file's key.
  spit(s.file("scene.ini"), "[material]\nroll-width = 0.1\n");
  const CliRun r = plyfit_run(
      "drape '" + s.file("scene.ini") + "' " + kCylinder + " -o '" + s.file("out") + "'", s);
  CHECK(error_code(r) == "roll_narrower_than_cells");
  CHECK(r.err.find("key 'roll-width'") != std::string::npos);
  // A laminate's stagger.
  spit(s.file("lam.ini"), "[laminate]\nsplice-stagger = -1\n[ply A]\n");
  const CliRun l = plyfit_run("laminate lam.ini -o out", s, s.path.string());
  CHECK(error_code(l) == "splice_stagger_negative");
  CHECK(l.err.find("splice-stagger") != std::string::npos);
}

TEST_CASE("cli splices: a laminate's seams keep the stagger distance on the part") {
  Scratch s("splices_stagger");
  const double W = kWidth / 2.5, stagger = 0.8;
  std::string text =
      "[laminate]\nmold = builtin:cylinder:R=10,H=20,angle=90\n"
      "seed = 7.0710678118654755,7.0710678118654755,10\nrosette = 0,0,1\nspacing = 0.2\n"
      "outputs = json\nroll-width = " +
      std::to_string(W) + "\nsplice-stagger = " + std::to_string(stagger) + "\n";
  // Four plies of one fibre direction (0 and 180 degrees) and one across them (90: its seams,
  // circles round the axis, cross theirs and are not staggered from them).
  for (const char* ply :
       {"[ply P1]\nangle = 0\n", "[ply P2]\nangle = 180\n", "[ply P3]\nangle = 0\n",
        "[ply P4]\nangle = 0\n", "[ply Q]\nangle = 90\n"})
    text += std::string("\n") + ply;
  spit(s.file("lam.ini"), text);
  for (const char* jobs : {"1", "2"}) {
    INFO("-j " << jobs);
    const std::string out = std::string("out") + jobs;
    const CliRun r =
        plyfit_run("laminate lam.ini -o " + out + " -j " + jobs + " --quiet", s, s.path.string());
    INFO(r.err);
    REQUIRE(r.code == 0);
    std::vector<json> seams;
    for (const char* p : {"P1", "P2", "P3", "P4"}) {
      const json j = report_of(s, out + "/" + p);
      REQUIRE(j.contains("pieces"));
      CHECK(j["pieces"].size() == 3);
      for (const auto& piece : j["pieces"]) CHECK(piece["width"].get<double>() <= W * (1 + 1e-9));
      CHECK(j["splices"]["stagger_met"] == true);
      seams.push_back(j["splices"]["seams"]);
    }
    for (std::size_t a = 0; a < seams.size(); ++a)
      for (std::size_t b = a + 1; b < seams.size(); ++b) {
        INFO("plies " << a << " and " << b);
        CHECK(seams_distance(seams[a], seams[b]) >= stagger);
      }
    // The ply book gives each seam's distance to the plies below it.
    const json book = json::parse(slurp(s.file(out + "/plybook.json")));
    for (const auto& p : book["plies"]) {
      if (p["name"] == "Q" || p["name"] == "P1") continue;
      for (const auto& seam : p["seams"])
        CHECK(seam["stagger_distance_mm"].get<double>() >= stagger);
    }
  }
  // Equal runs whatever -j.
  for (const char* p : {"P1", "P2", "P3", "P4"}) {
    json a = report_of(s, std::string("out1/") + p), b = report_of(s, std::string("out2/") + p);
    a.erase("timing_ms");
    b.erase("timing_ms");
    CHECK(a == b);
  }
}
