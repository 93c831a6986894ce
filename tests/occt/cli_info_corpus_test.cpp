// plyfit info on the real CAD files of the corpus: the text listing, --json, reader warnings.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "occt/info_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: plyfit info lists the faces of a real file") {
  TempDir dir("cli_info_corpus");
  check_info_listings({{shared_cad("occ22470.igs"),
                        18,
                        {"summary: 18 faces (bspline 18), 14 rational, 18 trimmed",
                         "unit: millimetre", "schema: IGES 5.3"}}},
                      dir);
  // Reader messages appear summarised after the summary line.
  const Run w = run_plyfit("info '" + shared_cad("trj7_c2-td-203.stp") + "'", dir);
  REQUIRE(w.code == 0);
  CHECK(w.out.find("\nwarning: ") != std::string::npos);
  CHECK(w.err.empty());
}

TEST_CASE("importers: plyfit info --json on a real file matches the library's listing") {
  TempDir dir("cli_json_corpus");
  const auto j = check_info_json(shared_cad("bug27693_cornetta-step.stp"), dir);
  CHECK(j["summary"]["kinds"]["bspline"] == 74);
  CHECK(j["summary"]["kinds"]["plane"] == 36);
  CHECK(j["unit"] == "millimetre");
  CHECK(j["schema"] == "AUTOMOTIVE_DESIGN");
  CHECK(j["format"] == "step");
  // Reader warnings reach the JSON too, by their codes.
  check_info_json_warns(shared_cad("trj7_c2-td-203.stp"), dir, "reader_messages");
}
