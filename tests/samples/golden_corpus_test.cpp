// The sample scenes on the real CAD files of the corpus (../shared/cad) against their goldens
// (golden_check.hpp).

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "samples/golden_check.hpp"

using namespace plyfit::test;

TEST_CASE("samples: every sample scene on a corpus file matches its golden report figures") {
  const auto scenes = scenes_of(true);
  REQUIRE(scenes.size() >= 4);
  check_goldens(scenes);
}
