#pragma once
// Checks of plyfit info --face output shared by info_face_test.cpp and its corpus twin.

#include <plyfit/kernel/types.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

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

}  // namespace plyfit::test
