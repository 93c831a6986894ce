// plyfit info, run as a program on plyfit's own sample molds: the text listing, --json,
// --format and the exit codes (the same on the CAD corpus in cli_info_corpus_test.cpp).

#include <BRepPrimAPI_MakeBox.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "occt/info_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: plyfit info lists the faces of a file") {
  TempDir dir("cli_info");
  // OpenCASCADE's STEP reader makes the closed B-spline of the tube periodic, and says so:
  // reader messages appear summarised after the summary line.
  check_info_listings({{sample_mold("tube-window.step"),
                        1,
                        {"summary: 1 faces (bspline 1), 1 rational, 1 trimmed (1 with holes)",
                         "'tube-window'", "unit: millimetre", "schema: AUTOMOTIVE_DESIGN",
                         "\nwarning: transfer: 1 warning (1x 'Surface forced to be periodic')"}}},
                      dir);
}

TEST_CASE("importers: plyfit info --json parses and matches the library's listing") {
  TempDir dir("cli_json");
  for (const std::string name : {"dish.igs", "plate-hole.step", "tube-window.igs"}) {
    INFO(name);
    const auto j = check_info_json(sample_mold(name), dir);
    CHECK(j["summary"]["kinds"]["bspline"] == 1);
    CHECK(j["faces"][0]["trimmed"] == true);
    CHECK(j["faces"][0]["holes"] == 1);
    CHECK(j["unit"].get<std::string>().rfind("millimetre", 0) == 0);
    CHECK(j["format"] == (is_iges(name) ? "iges" : "step"));
    CHECK(j["schema"].get<std::string>().rfind(is_iges(name) ? "IGES 5.3" : "AUTOMOTIVE_DESIGN",
                                               0) == 0);
  }
  // Reader warnings reach the JSON too, by their codes (OpenCASCADE's text as data).
  check_info_json_warns(sample_mold("tube-window.step"), dir, "reader_messages",
                        "Surface forced to be periodic");
}

TEST_CASE("importers: plyfit info exit codes: 1 for a bad file, 2 for a bad command line") {
  TempDir dir("cli_codes");
  const std::string step = sample_mold("plate-hole.step");
  Run r = run_plyfit("info '" + dir.file("missing.step") + "'", dir);
  CHECK(r.code == 1);
  // One line naming the file, the error's code in brackets at its end.
  CHECK(r.err.rfind("plyfit: error: " + dir.file("missing.step") + ": ", 0) == 0);
  CHECK(error_code(r) == "file_missing");
  r = run_plyfit("info", dir);
  CHECK(r.code == 2);
  r = run_plyfit("info --no-such-option '" + step + "'", dir);
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  r = run_plyfit("info '" + step + "' extra_argument", dir);
  CHECK(r.code == 2);
  // --format overrides the extension.
  write_bytes(dir.file("model.dat"), read_bytes(step));
  r = run_plyfit("info '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "file_extension_unknown");
  r = run_plyfit("info --format step '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 0);
  r = run_plyfit("info --format iges '" + dir.file("model.dat") + "'", dir);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "file_wrong_format");
  r = run_plyfit("info --help", dir);
  CHECK(r.code == 0);
  CHECK(r.out.find("--json") != std::string::npos);
}

TEST_CASE("importers: plyfit info lists each face's neighbours and free edges from the file") {
  // The file's own topology (no sewing): a box's six faces each share their four edges with
  // four others; the flange + fillet + wall's faces share the two edges between them (STEP
  // and IGES alike); a tube's seam is no free edge, its two circles are.
  TempDir dir("cli_neighbours");
  STEPControl_Controller::Init();
  STEPControl_Writer w;
  REQUIRE(w.Transfer(BRepPrimAPI_MakeBox(10, 20, 30).Shape(), STEPControl_AsIs) ==
          IFSelect_RetDone);
  REQUIRE(w.Write(dir.file("box.step").c_str()) == IFSelect_RetDone);
  struct Case {
    std::string path;
    std::vector<std::vector<int>> neighbours;
    std::vector<int> free;
  };
  const std::vector<int> none;
  for (const Case& c : {Case{dir.file("box.step"), {}, {0, 0, 0, 0, 0, 0}},
                        Case{sample_mold("flange-fillet-wall.step"), {{1}, {0, 2}, {1}}, {3, 2, 3}},
                        Case{sample_mold("flange-fillet-wall.igs"), {{1}, {0, 2}, {1}}, {3, 2, 3}},
                        Case{sample_mold("tube.step"), {none}, {2}}}) {
    CAPTURE(c.path);
    const Run r = run_plyfit("info --json '" + c.path + "'", dir);
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["faces"].size() == c.free.size());
    for (std::size_t f = 0; f < c.free.size(); ++f) {
      CAPTURE(f);
      CHECK(j["faces"][f]["free_edges"] == c.free[f]);
      const auto nb = j["faces"][f]["neighbours"].get<std::vector<int>>();
      if (c.neighbours.empty())
        CHECK(nb.size() == 4);  // the box: the four faces round it
      else
        CHECK(nb == c.neighbours[f]);
    }
  }
}
