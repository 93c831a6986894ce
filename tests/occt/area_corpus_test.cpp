// Face areas (importers/src/face_measure.cpp) on the shared CAD files: the integration along u
// against the one along v (another path of quadratures for the same integral) to the accuracy
// asked, at the listing's 1e-6 and a described face's 1e-9. Closed forms: area_test.cpp.

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "face_measure.hpp"  // occt/src
#include "occt/occt_reference.hpp"

#include <algorithm>
#include "surface/face.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

// The accuracies the importer asks for (occt_mold.cpp): the listing, and a described face.
constexpr double kListingRel = 1e-6;
constexpr double kDescribedRel = 1e-9;

}  // namespace

TEST_CASE(
    "importers: face areas integrated along u and along v agree to the accuracy asked (shared "
    "CAD files)") {
  for (const std::string name :
       {"BUC50025.igs", "PRO20359-L1.igs", "occ22470.igs", "surf114.igs", "example_45_faces.iges",
        "bug27693_cornetta-step.stp", "trj7_c2-td-203.stp", "trj8_c2-db-214.stp"}) {
    const Reference ref = read_reference(shared_cad(name), is_iges(name));
    int unconverged = 0;
    double worst = 0.0;
    for (int i = 0; i < ref.count(); ++i) {
      INFO(name << " face " << i);
      for (const double rel : {kListingRel, kDescribedRel}) {
        const auto along_u = importers::occt::measure_face(ref.face(i), rel, false, false);
        const auto along_v = importers::occt::measure_face(ref.face(i), rel, false, true);
        INFO("asked " << rel << ": " << along_u.area << " +- " << along_u.error << " along u, "
                      << along_v.area << " +- " << along_v.error << " along v");
        // Each is asked for `rel` and, when it says it converged, is within `rel` (its error
        // estimate is an estimate: on these files it falls short of the actual error by up to
        // 10 times, still far below `rel`); when it says it did not, within its estimate.
        const double claim_u =
            std::max(rel * along_u.area, along_u.converged ? 0.0 : along_u.error);
        const double claim_v =
            std::max(rel * along_v.area, along_v.converged ? 0.0 : along_v.error);
        CHECK(std::abs(along_u.area - along_v.area) <=
              (along_u.converged && along_v.converged ? rel * along_u.area : claim_u + claim_v));
        unconverged += !along_u.converged + !along_v.converged;
        if (!along_u.converged || !along_v.converged) WARN("short of " << rel);
        worst = std::max(worst, std::abs(along_u.area - along_v.area) / along_u.area);
      }
    }
    WARN(name << ": largest |u - v| " << worst << " of the area; " << unconverged
              << " integrations short of their accuracy");
    // Every integration converges but surf114's face 3 along v at 1e-9 (5e-8 reached: its
    // bands in v, the surface's u, meet the edges where |S_u| vanishes). With the inner rule's
    // columns in equal parts, three surf114 faces fell short at 1e-9 along u as well; the
    // importer integrates along u.
    CHECK(unconverged <= (name == "surf114.igs" ? 1 : 0));
  }
}
