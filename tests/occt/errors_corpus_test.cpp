// Expected failures of the importers (error_checks.hpp) on the real CAD files of the corpus:
// renamed, truncated and corrupted copies, bad face indices and the time limit (on the largest
// file, whose transfer takes longest).

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "occt/error_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: renamed, truncated and corrupted copies of real files give clear errors") {
  TempDir dir("corrupt_corpus");
  check_damaged_copies({{shared_cad("trj8_c2-db-214.stp"), shared_cad("PRO20359-L1.igs"), 21}},
                       dir);
}

TEST_CASE("importers: the plyfit binary survives every corrupted copy of real files", "[slow]") {
  TempDir dir("corrupt_bin_corpus");
  binary_survives_corrupted(shared_cad("trj8_c2-db-214.stp"), shared_cad("occ22470.igs"), dir);
}

TEST_CASE("importers: bad face indices and a past time limit on real files are errors") {
  check_bad_index_and_time_limit(shared_cad("trj7_c2-td-203.stp"), 4);
  check_bad_index_and_time_limit(shared_cad("bug27693_cornetta-step.stp"), 110);
}
