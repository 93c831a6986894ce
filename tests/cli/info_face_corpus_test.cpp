// plyfit info FILE --face N on real faces of the CAD corpus (../shared/cad): the point lies
// inside the trims, and the flags start a drape there.

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/info_face_checks.hpp"
#include "corpus.hpp"

#include <utility>
#include <vector>

using namespace plyfit;
using namespace plyfit::test;

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
    check_face_start(file, face, tmp);
  }
}
