#pragma once
// Checks of plyfit info --face output shared by info_face_test.cpp and its corpus twin.

#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/types.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "support/face_of.hpp"

#include <string>

namespace plyfit::test {

/// A JSON array of three numbers as a vector.
inline Vec3 vec(const nlohmann::json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

// The plyfit info --face flags run as a drape: it must map nodes from a start on the face.
inline void drape_from(const std::string& file, const std::string& flags, const Scratch& tmp) {
  const CliRun r = plyfit_run("drape --mold '" + file + "' " + flags +
                                  " --spacing 1 --outputs json --quiet -o '" + tmp.file("d") + "'",
                              tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json rep = nlohmann::json::parse(slurp(tmp.file("d") + "/report.json"));
  CHECK(rep["nodes"]["mapped"].get<int>() > 0);
  CHECK(rep["start"]["moved"].get<double>() <= 1e-6);  // the point is on the face (9 digits)
}

// plyfit info FILE --face N --json: its point lies inside the face's trims, on the face (with
// the face's normal there), and its flags start a drape.
inline void check_face_start(const std::string& file, int face, const Scratch& tmp) {
  const CliRun r =
      plyfit_run("info '" + file + "' --face " + std::to_string(face) + " --json", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  auto f = importers::load_face(file, face);
  REQUIRE(f.ok());
  const Vec2 uv(j["uv"][0].get<double>(), j["uv"][1].get<double>());
  CHECK(test::face_of(*f).contains(uv));
  CHECK((f->eval1(uv).p - vec(j["point"])).norm() <= 1e-9 * f->size());
  CHECK((f->normal(uv).n - vec(j["normal"])).norm() <= 1e-9);
  drape_from(file, j["flags"].get<std::string>(), tmp);
}

}  // namespace plyfit::test
