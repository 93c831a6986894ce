// plyfit drape --boundary FILE:NAME on a real CAD file of the corpus (../shared/cad): a name
// picks every curve that bears it.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/drape_report.hpp"
#include "corpus.hpp"

#include <string>

using namespace plyfit::test;
using nlohmann::json;

TEST_CASE("cli: a boundary picked by name takes every curve of that name") {
  // PRO20359-L1.igs (CATIA V4): its one face's border is 47 curves all named 'FAC418(1690)'
  // (plyfit info --curves). Picked by that name they chain into the face's outline: the
  // region is the whole face, its area the face's own (OpenCASCADE's, in plyfit info).
  Scratch tmp("boundary_by_name");
  const std::string file = shared_cad("PRO20359-L1.igs");
  const CliRun info = plyfit_run("info '" + file + "' --face 0 --json", tmp);
  INFO(info.err);
  REQUIRE(info.code == 0);
  const double face_area = json::parse(info.out)["area_mm2"].get<double>();
  const json j = drape_report("--mold '" + file +
                                  "' --face 0 --seed -699.1,580.04,461.34 --rosette 0,1,0 "
                                  "--boundary '" +
                                  file + ":FAC418(1690)' --spacing 2 --quiet --outputs json",
                              tmp);
  REQUIRE(j["ply"]["boundary"]["loops"].size() == 1);
  CHECK(j["ply"]["boundary"]["area"].get<double>() == Approx(face_area).epsilon(1e-4));
}
