// Regression over the sample scenes (samples/*.ini): each is draped by the built plyfit and
// its report.json figures are compared with samples/golden/<scene>.json. Counts must match
// exactly; angles, areas, energies and the start's move to kGoldenRel relative; residuals
// are only bounded. PLYFIT_UPDATE_GOLDENS=1 rewrites the goldens instead (see
// scripts/update-goldens); every change of a golden figure is explained in its commit.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

using namespace plyfit::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// Relative agreement of the real-valued golden figures.
constexpr double kGoldenRel = 1e-9;
/// Bounds of the residuals: thread and base-path links keep their length, and the base path
/// its plane, to this fraction of the spacing; mapped points lie on the face to this fraction
/// of the face size.
constexpr double kLinkResidualRel = 1e-9;
constexpr double kSurfaceResidualRel = 1e-9;
/// Figures that are zero in exact arithmetic come out as round-off (a developable face's shear
/// energy ~1e-24, a start on the face moving ~1e-15): a relative test is meaningless there, so
/// these absolute floors are added to the tolerance: energy (a sum of cos^2) and the start's
/// move as a fraction of the face size.
constexpr double kEnergyRoundoff = 1e-18;
constexpr double kMoveRoundoffRel = 1e-12;

const std::vector<std::string> kExact = {"/status",        "/nodes/mapped",    "/nodes/auxiliary",
                                         "/nodes/outside", "/nodes/off_ply",   "/nodes/shear_limit",
                                         "/nodes/failed",  "/area_mesh_points"};
const std::vector<std::string> kRelative = {
    "/flat_area",        "/surface_area", "/coverage",          "/thread_angle/min",
    "/thread_angle/max", "/shear_energy", "/flat_outline/area", "/flat_outline/perimeter",
    "/mold/face/area",   "/start/moved"};

std::string samples_dir() {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples";
}

std::vector<fs::path> sample_scenes() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(samples_dir()))
    if (e.path().extension() == ".ini") v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

/// The compared figures of a report, keyed by JSON pointer.
json golden_of(const json& report) {
  json g = json::object();
  for (const auto& p : kExact) g[p] = report.at(json::json_pointer(p));
  for (const auto& p : kRelative) g[p] = report.at(json::json_pointer(p));
  return g;
}

json drape_report(const fs::path& scene, const Scratch& tmp) {
  const std::string out = tmp.file(scene.stem().string());
  const CliRun r =
      plyfit_run("drape '" + scene.string() + "' -o '" + out + "' --outputs json --quiet", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(slurp(out + "/report.json"));
}

}  // namespace

TEST_CASE("samples: every sample scene matches its golden report figures") {
  Scratch tmp("goldens");
  const bool update = std::getenv("PLYFIT_UPDATE_GOLDENS") != nullptr;
  const std::string golden_dir = samples_dir() + "/golden";
  const auto scenes = sample_scenes();
  REQUIRE(scenes.size() >= 12);
  for (const auto& scene : scenes) {
    const std::string name = scene.stem().string();
    INFO("scene " << name);
    const json report = drape_report(scene, tmp);
    const std::string golden_path = golden_dir + "/" + name + ".json";
    if (update) {
      fs::create_directories(golden_dir);
      json g = golden_of(report);
      g["scene"] = scene.filename().string();
      spit(golden_path, g.dump(2) + "\n");
      continue;
    }
    REQUIRE(fs::exists(golden_path));
    const json golden = json::parse(slurp(golden_path));
    for (const auto& p : kExact) {
      INFO(p);
      CHECK(report.at(json::json_pointer(p)) == golden.at(p));
    }
    const json& box = report["mold"]["face"]["bbox"];
    double size2 = 0.0;
    for (int k = 0; k < 3; ++k)
      size2 += std::pow(box["max"][k].get<double>() - box["min"][k].get<double>(), 2);
    const double size = std::sqrt(size2);
    for (const auto& p : kRelative) {
      INFO(p);
      const double a = report.at(json::json_pointer(p)).get<double>();
      const double g = golden.at(p).get<double>();
      const double floor = p == "/shear_energy"  ? kEnergyRoundoff
                           : p == "/start/moved" ? kMoveRoundoffRel * size
                                                 : 0.0;
      CHECK(std::abs(a - g) <= kGoldenRel * std::abs(g) + floor);
    }
    CHECK(report["residual"]["edge_length_max_rel"].get<double>() <= kLinkResidualRel);
    CHECK(report["residual"]["base_plane_max_rel"].get<double>() <= kLinkResidualRel);
    CHECK(report["residual"]["surface_distance_max"].get<double>() <= kSurfaceResidualRel * size);
  }
  if (update) return;
  // No golden without its scene.
  for (const auto& e : fs::directory_iterator(golden_dir)) {
    INFO("golden " << e.path().filename().string());
    CHECK(fs::exists(samples_dir() + "/" + e.path().stem().string() + ".ini"));
  }
}

TEST_CASE("samples: the goldens are plausible") {
  const double pi = 3.14159265358979323846;
  for (const auto& scene : sample_scenes()) {
    const std::string name = scene.stem().string();
    INFO("scene " << name);
    const json g = json::parse(slurp(samples_dir() + "/golden/" + name + ".json"));
    CHECK(g["/status"] == "ok");
    CHECK(g["/nodes/failed"] == 0);
    CHECK(g["/nodes/mapped"].get<int>() > 400);
    // The ply covers part of the face, never more than all of it.
    CHECK(g["/coverage"].get<double>() > 0.25);
    CHECK(g["/coverage"].get<double>() <= 1.0);
    CHECK(g["/thread_angle/min"].get<double>() > 0.0);
    CHECK(g["/thread_angle/max"].get<double>() < pi);
    CHECK(g["/thread_angle/min"].get<double>() <= g["/thread_angle/max"].get<double>());
  }
  auto golden = [](const std::string& name) {
    return json::parse(slurp(samples_dir() + "/golden/" + name + ".json"));
  };
  // Table 1 (b) is symmetric about the plane x = z: gamma min + gamma max = pi.
  const json b = golden("sphere-octant-b");
  CHECK(std::abs(b["/thread_angle/min"].get<double>() + b["/thread_angle/max"].get<double>() - pi) <
        1e-9);
  // Table 1 (a) and (c) start at the pole: the start does not move. (b)'s start (10, 0, 10)
  // moves to the sphere: by R - |(10, 0, 10)| = 20 - 10 sqrt 2.
  CHECK(golden("sphere-octant-a")["/start/moved"].get<double>() == 0.0);
  CHECK(std::abs(b["/start/moved"].get<double>() - (20.0 - 10.0 * std::sqrt(2.0))) < 1e-12 * 20);
  // The octant's area is pi R^2 / 2.
  CHECK(std::abs(b["/mold/face/area"].get<double>() - pi * 200.0) < 1e-9 * pi * 200.0);
  // The cylinder is developable: every thread angle is 90 degrees (to round-off).
  const json cyl = golden("cylinder-sector");
  CHECK(std::abs(cyl["/thread_angle/min"].get<double>() - pi / 2) < 1e-9);
  CHECK(std::abs(cyl["/thread_angle/max"].get<double>() - pi / 2) < 1e-9);
  CHECK(cyl["/shear_energy"].get<double>() < 1e-12);
  // The blob with a 50 degree lock angle stops some nodes at the shear limit, and no mapped
  // thread angle passes the lock: gamma in [40, 140] degrees.
  const json blob = golden("surf114-blob");
  CHECK(blob["/nodes/shear_limit"].get<int>() > 0);
  CHECK(blob["/thread_angle/min"].get<double>() >= 40.0 * pi / 180 - 1e-12);
  CHECK(blob["/thread_angle/max"].get<double>() <= 140.0 * pi / 180 + 1e-12);
}
