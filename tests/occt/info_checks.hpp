#pragma once
// plyfit info run as a program, checked against the library's listing of the same file (used
// on the sample molds and on the CAD corpus).

#include <plyfit/importers/importers.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "occt/occt_reference.hpp"

namespace plyfit::test {

/// plyfit info FILE as a table: exit 0, nothing on stderr, the header, one line per face
/// (`faces`), the summary and the warnings line, and nothing from OpenCASCADE's own printers.
inline Run check_info_table(const std::string& path, const TempDir& dir, int faces) {
  const Run r = run_plyfit("info '" + path + "'", dir);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 2 + faces + 2);
  CHECK(r.out.find("***") == std::string::npos);
  return r;
}

/// A file and what its `plyfit info` table must show: its number of faces and lines of text.
struct InfoListing {
  std::string path;
  int faces;
  std::vector<std::string> lines;
};

/// check_info_table() on each file of `cases`, and each of its expected lines in the output.
inline void check_info_listings(const std::vector<InfoListing>& cases, const TempDir& dir) {
  for (const InfoListing& c : cases) {
    INFO(c.path);
    const Run r = check_info_table(c.path, dir, c.faces);
    for (const std::string& line : c.lines) CHECK(r.out.find(line) != std::string::npos);
  }
}

/// `plyfit info --json PATH` succeeds and its first warning has `code` (and `text` holding
/// `fragment`, when one is given).
inline void check_info_json_warns(const std::string& path, const TempDir& dir,
                                  const std::string& code, const std::string& fragment = "") {
  const Run r = run_plyfit("info --json '" + path + "'", dir);
  REQUIRE(r.code == 0);
  const auto warnings = nlohmann::json::parse(r.out)["warnings"];
  REQUIRE_FALSE(warnings.empty());
  CHECK(warnings[0]["code"] == code);
  CHECK(warnings[0]["text"].get<std::string>().find(fragment) != std::string::npos);
}

/// Runs `plyfit info --json PATH` and checks that every face entry matches the library's
/// listing; returns the parsed output.
inline nlohmann::json check_info_json(const std::string& path, const TempDir& dir) {
  const Run r = run_plyfit("info --json '" + path + "'", dir);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Mold& m = (*file)->mold();
  REQUIRE(j["faces"].size() == m.faces.size());
  for (size_t i = 0; i < m.faces.size(); ++i) {
    const auto& jf = j["faces"][i];
    CHECK(jf["index"] == static_cast<int>(i));
    CHECK(jf["kind"] == m.faces[i].kind);
    CHECK(jf["trimmed"] == m.faces[i].trimmed);
    CHECK(jf["holes"] == m.faces[i].holes);
    CHECK(jf["degree"][0] == m.faces[i].degree_u);
    CHECK(jf["poles"][1] == m.faces[i].poles_v);
    CHECK(jf["area_mm2"].get<double>() == Approx(m.faces[i].area).epsilon(kRoundoffRel));
    CHECK(jf["bbox_mm"]["max"][2].get<double>() ==
          Approx(m.faces[i].bbox.max.z()).epsilon(kRoundoffRel));
  }
  return j;
}

}  // namespace plyfit::test
