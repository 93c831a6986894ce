// plyfit info, run as a program: the text listing, --json, --format and the exit codes.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "importers/occt_reference.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: plyfit info lists the faces of a file") {
  TempDir dir("cli_info");
  const std::string path = shared_cad("occ22470.igs");
  const Run r = run_plyfit("info '" + path + "'", dir);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  // Header, one line per face, the summary and the warnings line.
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 2 + 18 + 2);
  CHECK(r.out.find("summary: 18 faces (bspline 18), 14 rational, 18 trimmed") != std::string::npos);
  CHECK(r.out.find("unit: millimetre") != std::string::npos);
  CHECK(r.out.find("schema: IGES 5.3") != std::string::npos);
  // Nothing from OpenCASCADE's own printers.
  CHECK(r.out.find("***") == std::string::npos);
  // Reader messages appear summarised after the summary line.
  const Run w = run_plyfit("info '" + shared_cad("trj7_c2-td-203.stp") + "'", dir);
  REQUIRE(w.code == 0);
  CHECK(w.out.find("\nwarning: load: 12 fails") != std::string::npos);
  CHECK(w.err.empty());
}

TEST_CASE("importers: plyfit info --json parses and matches the library's listing") {
  TempDir dir("cli_json");
  const std::string path = shared_cad("bug27693_cornetta-step.stp");
  const Run r = run_plyfit("info --json '" + path + "'", dir);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Mold& m = (*file)->mold();
  REQUIRE(j["faces"].size() == m.faces.size());
  CHECK(j["summary"]["kinds"]["bspline"] == 74);
  CHECK(j["summary"]["kinds"]["plane"] == 36);
  CHECK(j["unit"] == "millimetre");
  CHECK(j["schema"] == "AUTOMOTIVE_DESIGN");
  CHECK(j["format"] == "step");
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
  // Reader warnings reach the JSON too.
  const Run w = run_plyfit("info --json '" + shared_cad("trj7_c2-td-203.stp") + "'", dir);
  REQUIRE(w.code == 0);
  CHECK_FALSE(nlohmann::json::parse(w.out)["warnings"].empty());
}

TEST_CASE("importers: plyfit info exit codes: 1 for a bad file, 2 for a bad command line") {
  TempDir dir("cli_codes");
  Run r = run_plyfit("info '" + dir.file("missing.step") + "'", dir);
  CHECK(r.code == 1);
  CHECK(r.err == "plyfit: error: " + dir.file("missing.step") + ": no such file\n");
  r = run_plyfit("info", dir);
  CHECK(r.code == 2);
  r = run_plyfit("info --no-such-option '" + shared_cad("trj8_c2-db-214.stp") + "'", dir);
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  r = run_plyfit("info '" + shared_cad("trj8_c2-db-214.stp") + "' extra_argument", dir);
  CHECK(r.code == 2);
  // --format overrides the extension.
  write_bytes(dir.file("model.dat"), read_bytes(shared_cad("trj8_c2-db-214.stp")));
  r = run_plyfit("info '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 1);
  CHECK(r.err.find("supported: step, stp, iges, igs") != std::string::npos);
  r = run_plyfit("info --format step '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 0);
  r = run_plyfit("info --format iges '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 1);
  CHECK(r.err.find("looks like STEP") != std::string::npos);
  r = run_plyfit("info --help", dir);
  CHECK(r.code == 0);
  CHECK(r.out.find("--json") != std::string::npos);
}
