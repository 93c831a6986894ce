// plyfit drape --darts auto on a closed shell of the corpus (../shared/cad): the deflector.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "corpus.hpp"

using namespace plyfit::test;
using json = nlohmann::json;

TEST_CASE("cli: automatic darts on the deflector's closed shell part the fronts that met") {
  // The deflector's 18 faces sewn into one closed shell, seed on the outer wall: the cloth
  // wraps round and its fronts meet (conflict nodes; overlaps where a front came onto the
  // other's cloth). With --darts auto, darts along the lines where they met leave fewer of
  // both, in at most 3 drapes; the ply is not laid yet (docs/decisions/darts.md).
  Scratch tmp("darts_corpus_deflector");
  const std::string args = "drape --mold '" + shared_cad("occ22470.igs") +
                           "' --faces all --seed 100.09,79.13,55.13 --spacing 2 --outputs json "
                           "--quiet -o '";
  const CliRun plain = plyfit_run(args + tmp.file("plain") + "'", tmp);
  REQUIRE(plain.code == 0);
  const json p = json::parse(slurp(tmp.file("plain") + "/report.json"));
  REQUIRE(p["nodes"]["conflict"].get<int>() > 0);
  const CliRun cut = plyfit_run(args + tmp.file("cut") + "' --darts auto", tmp);
  INFO(cut.err);
  REQUIRE(cut.code == 0);
  const json c = json::parse(slurp(tmp.file("cut") + "/report.json"));
  INFO("without darts: " << p["nodes"]["conflict"] << " conflict, " << p["nodes"]["overlap"]
                         << " overlap; with " << c["darts"]["darts"].size() << " darts after "
                         << c["darts"]["drapes"] << " drapes: " << c["nodes"]["conflict"]
                         << " conflict, " << c["nodes"]["overlap"] << " overlap, coverage "
                         << c["coverage"]);
  CHECK(c["darts"]["auto"] == true);
  CHECK(c["darts"]["drapes"].get<int>() <= 3);
  CHECK(c["nodes"]["conflict"].get<int>() < p["nodes"]["conflict"].get<int>());
  CHECK(c["nodes"]["overlap"].get<int>() < p["nodes"]["overlap"].get<int>());
  const bool laid = c["nodes"]["conflict"] == 0 && c["nodes"]["shear_limit"] == 0;
  CHECK(c["darts"]["laid"] == laid);
  bool warned = false;
  for (const json& w : c["warnings"]) warned = warned || w["code"] == "darts_not_enough";
  CHECK(warned == !laid);
}
