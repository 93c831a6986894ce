// plyfit info FILE --face N on real faces of the CAD corpus (../shared/cad): the point lies
// inside the trims, and the flags start a drape there.

#include <plyfit/importers/importers.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/info_face_checks.hpp"
#include "corpus.hpp"
#include "support/face_of.hpp"

#include <utility>
#include <vector>

using namespace plyfit;
using namespace plyfit::test;
using nlohmann::json;

TEST_CASE("cli: plyfit info --face finds a point inside the trims of real faces") {
  Scratch tmp("info_face_cad");
  for (const auto& [name, face] :
       std::vector<std::pair<std::string, int>>{{"PRO20359-L1.igs", 0},
                                                {"surf114.igs", 3},
                                                {"trj7_c2-td-203.stp", 2},
                                                {"example_45_faces.iges", 7},
                                                {"bug27693_cornetta-step.stp", 20}}) {
    const std::string file = shared_cad(name);
    INFO(name << " face " << face);
    const CliRun r =
        plyfit_run("info '" + file + "' --face " + std::to_string(face) + " --json", tmp);
    INFO(r.err);
    REQUIRE(r.code == 0);
    const json j = json::parse(r.out);
    auto f = importers::load_face(file, face);
    REQUIRE(f.ok());
    const Vec2 uv(j["uv"][0].get<double>(), j["uv"][1].get<double>());
    CHECK(test::face_of(*f).contains(uv));
    CHECK((f->eval1(uv).p - vec(j["point"])).norm() <= 1e-9 * f->size());
    CHECK((f->normal(uv).n - vec(j["normal"])).norm() <= 1e-9);
    drape_from(file, j["flags"].get<std::string>(), tmp);
  }
}
