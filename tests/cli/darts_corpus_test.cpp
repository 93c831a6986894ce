// plyfit drape --darts auto on a closed shell of the corpus (../shared/cad): the deflector.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "corpus.hpp"

using namespace plyfit::test;
using json = nlohmann::json;

TEST_CASE("cli: automatic darts lay the deflector's closed shell: seams part the fronts that met") {
  // The deflector's 18 faces sewn into one closed shell, seed on the outer wall: the cloth
  // wraps round and its fronts meet and disagree (conflict nodes). With --darts auto the scan
  // cuts a seam where they meet: no conflict is left, every link it keeps has its rest length,
  // and each seam is a slit in the flat pattern (docs/decisions/darts.md).
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
  int seams = 0, links_cut = 0;
  for (const json& d : c["darts"]["darts"])
    if (d["seam"] == true) ++seams, links_cut += d["links_cut"].get<int>();
  INFO("without darts: " << p["nodes"]["conflict"] << " conflict, " << p["nodes"]["mapped"]
                         << " mapped; with " << c["darts"]["darts"].size() << " darts (" << seams
                         << " seams, " << links_cut << " links cut) after " << c["darts"]["drapes"]
                         << " drapes: " << c["nodes"]["conflict"] << " conflict, "
                         << c["nodes"]["mapped"] << " mapped, largest link error "
                         << c["residual"]["edge_length_max_rel"] << " d");
  CHECK(c["darts"]["auto"] == true);
  CHECK(c["darts"]["drapes"].get<int>() <= 3);
  CHECK(c["nodes"]["conflict"] == 0);
  CHECK(c["nodes"]["shear_limit"] == 0);  // no lock given: the material's limit is none
  CHECK(c["darts"]["laid"] == true);
  CHECK(seams > 0);
  CHECK(links_cut > 0);
  // The links the drape keeps (those no seam cut) join their nodes at their rest length.
  CHECK(c["residual"]["edge_length_max_rel"].get<double>() < 1e-6);
  for (const json& w : c["warnings"]) CHECK(w["code"] != "darts_not_enough");
}
