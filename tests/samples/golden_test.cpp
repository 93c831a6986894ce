// The sample scenes on plyfit's own molds against their goldens (golden_check.hpp), and the
// goldens' plausibility.

#include <catch2/catch.hpp>

#include "samples/golden_check.hpp"

#include <plyfit/kernel/types.hpp>

using namespace plyfit::test;
using plyfit::kDegToRad;
using plyfit::kPi;

TEST_CASE("samples: every sample scene matches its golden report figures") {
  const auto scenes = scenes_of(false);
  REQUIRE(scenes.size() >= 12);
  check_goldens(scenes);
  if (std::getenv("PLYFIT_UPDATE_GOLDENS") != nullptr) return;
  // No golden without its scene (the corpus scenes' too: their goldens are committed).
  const std::string golden_dir = samples_dir() + "/golden";
  for (const auto& e : fs::recursive_directory_iterator(golden_dir)) {
    if (e.is_directory()) continue;
    const fs::path rel = fs::relative(e.path(), golden_dir);
    INFO("golden " << rel.generic_string());
    CHECK(fs::exists(fs::path(samples_dir()) / fs::path(rel).replace_extension(".ini")));
  }
}

TEST_CASE("samples: the goldens are plausible") {
  for (const auto& scene : sample_scenes()) {
    const std::string name = scene_name(scene);
    INFO("scene " << name);
    const json g = json::parse(slurp(samples_dir() + "/golden/" + name + ".json"));
    CHECK(g["/status"] == "ok");
    CHECK(g["/nodes/failed"] == 0);
    CHECK(g["/nodes/mapped"].get<int>() > 400);
    // The ply covers part of the face, never more than all of it.
    CHECK(g["/coverage"].get<double>() > 0.25);
    CHECK(g["/coverage"].get<double>() <= 1.0);
    CHECK(g["/thread_angle/min"].get<double>() > 0.0);
    CHECK(g["/thread_angle/max"].get<double>() < kPi);
    CHECK(g["/thread_angle/min"].get<double>() <= g["/thread_angle/max"].get<double>());
  }
  auto golden = [](const std::string& name) {
    return json::parse(slurp(samples_dir() + "/golden/" + name + ".json"));
  };
  // Table 1 (b) is symmetric about the plane x = z: gamma min + gamma max = pi.
  const json b = golden("sphere-octant-b");
  CHECK(std::abs(b["/thread_angle/min"].get<double>() + b["/thread_angle/max"].get<double>() -
                 kPi) < 1e-9);
  // Table 1 (a) and (c) start at the pole: the start does not move. (b)'s start (10, 0, 10)
  // moves to the sphere: by R - |(10, 0, 10)| = 20 - 10 sqrt 2.
  CHECK(golden("sphere-octant-a")["/start/moved"].get<double>() == 0.0);
  CHECK(std::abs(b["/start/moved"].get<double>() - (20.0 - 10.0 * std::sqrt(2.0))) < 1e-12 * 20);
  // The octant's area is pi R^2 / 2.
  CHECK(std::abs(b["/mold/face/area"].get<double>() - kPi * 200.0) < 1e-9 * kPi * 200.0);
  // The cylinder is developable: every thread angle is 90 degrees (to round-off).
  const json cyl = golden("cylinder-sector");
  CHECK(std::abs(cyl["/thread_angle/min"].get<double>() - kPi / 2) < 1e-9);
  CHECK(std::abs(cyl["/thread_angle/max"].get<double>() - kPi / 2) < 1e-9);
  CHECK(cyl["/shear_energy"].get<double>() < 1e-12);
  // The blob with a 50 degree lock angle stops some nodes at the shear limit, and no mapped
  // thread angle passes the lock: gamma in [40, 140] degrees.
  const json blob = golden("surf114-blob");
  CHECK(blob["/nodes/shear_limit"].get<int>() > 0);
  CHECK(blob["/thread_angle/min"].get<double>() >= 40.0 * kDegToRad - 1e-12);
  CHECK(blob["/thread_angle/max"].get<double>() <= 140.0 * kDegToRad + 1e-12);
  // The plies' boundaries are closed forms: the plate's circle r = 20 (400 pi at every angle,
  // the outline too), the development circle r = 24 of the flange + fillet + wall (576 pi) and
  // the sphere's cap of 30 deg (2 pi R^2 (1 - cos 30 deg), R = 20).
  for (const char* angle : {"0", "45", "90", "m45"}) {
    const json p = golden(std::string("plies/plate-") + angle);
    INFO("plate " << angle);
    CHECK(std::abs(p["/ply/boundary/area"].get<double>() - 400 * kPi) < 1e-3 * 400 * kPi);
    CHECK(std::abs(p["/flat_outline_exact/area"].get<double>() - 400 * kPi) < 1e-3 * 400 * kPi);
  }
  const double fillet = 576 * kPi;
  CHECK(std::abs(golden("plies/flange-fillet-wall")["/ply/boundary/area"].get<double>() - fillet) <
        1e-3 * fillet);
  const double cap = 2 * kPi * 400 * (1 - std::cos(30 * kDegToRad));
  CHECK(std::abs(golden("plies/sphere-cap")["/ply/boundary/area"].get<double>() - cap) <
        5e-3 * cap);
}
