// plyfit info FILE --face N: a point of the face near its middle (inside its trims), its
// outward normal, and drape flags that start a drape there. On the real faces of the CAD
// corpus: info_face_corpus_test.cpp.

#include <plyfit/importers/importers.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/info_face_checks.hpp"
#include "support/face_of.hpp"
#include "test_util.hpp"

#include <cmath>
#include <regex>
#include <string>
#include <utility>
#include <vector>

using namespace plyfit;
using namespace plyfit::test;
using nlohmann::json;

TEST_CASE("cli: plyfit info --face gives the octant's middle, its outward normal and flags") {
  Scratch tmp("info_face");
  const std::string file = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/sphere-octant.step";
  const CliRun r = plyfit_run("info '" + file + "' --face 0 --json", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  // The octant of the sphere R = 20: a point on it, the normal radial and outward, the base
  // plane through the normal (its normal tangent), sweeps opposite and tangent.
  const Vec3 p = vec(j["point"]), n = vec(j["normal"]), b = vec(j["base_normal"]),
             t = vec(j["base_tangent"]);
  constexpr double kRel = 1e-9;
  CHECK(std::abs(p.norm() - 20.0) <= kRel * 20);
  CHECK((n - p / 20.0).norm() <= kRel);
  CHECK(std::abs(b.norm() - 1.0) <= kRel);
  CHECK(std::abs(b.dot(n)) <= kRel);
  CHECK(std::abs(t.dot(n)) <= kRel);
  CHECK((t.cross(b) - n).norm() <= kRel);  // (base, sweep) turns about +n like (x, y) about +z
  CHECK(vec(j["sweep3d"][0]) == b);
  CHECK(vec(j["sweep3d"][1]) == -b);
  // Near the middle: the octant's uv centre is inside it, and x = y there by symmetry.
  for (int a = 0; a < 3; ++a) CHECK(p[a] > 0.25 * 20);
  CHECK(std::abs(p.x() - p.y()) <= kRel * 20);
  drape_from(file, j["flags"].get<std::string>(), tmp);
  // The text form gives the same flags.
  const CliRun text = plyfit_run("info '" + file + "' --face 0", tmp);
  REQUIRE(text.code == 0);
  CHECK(text.out.find("flags: " + j["flags"].get<std::string>() + "\n") != std::string::npos);
}

TEST_CASE("cli: plyfit info --face finds a point inside the trims of the trimmed samples") {
  // The plate's middle (50, 30) is the centre of its hole; the dish's middle is in its hole.
  Scratch tmp("info_face_samples");
  for (const std::string name : {"plate-hole.igs", "dish.step", "tube-window.step"}) {
    const std::string file = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/" + name;
    INFO(name);
    check_face_start(file, 0, tmp);
  }
}

TEST_CASE("cli: plyfit info --face errors") {
  Scratch tmp("info_face_errors");
  const std::string file = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/sphere-octant.step";
  CliRun r = plyfit_run("info '" + file + "' --face 3", tmp);
  CHECK(r.code == 1);
  CHECK_FALSE(error_code(r).empty());
  CHECK(r.err.find(file) != std::string::npos);
  for (const auto& [face, code] : std::vector<std::pair<std::string, std::string>>{
           {"-1", "not_an_integer"}, {"x", "not_a_number"}}) {
    r = plyfit_run("info '" + file + "' --face " + face, tmp);
    CHECK(r.code == 2);
    CHECK(error_code(r) == code);
    CHECK(r.err.rfind("plyfit: error: --face: ", 0) == 0);
  }
}
