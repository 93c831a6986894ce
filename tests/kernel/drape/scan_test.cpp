// The frontier scan (kernel/src/drape/scan): where the cloth reaches on a face.
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/mold.hpp>
#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include "support/problems.hpp"

using namespace plyfit;
using plyfit::support::problem;

TEST_CASE("scan: the cloth crosses the base path's line beyond the path's end, round a notch") {
  // A U in the plane z = 0: the square [0, 100]^2 less the notch [30, 70] x [30, 100]. The
  // base path along y = 61 starts on the left arm and stops at the notch; the right arm
  // above y = 61 lies on the path's line beyond its end, reached only by cloth that comes
  // round the U's bottom from below and crosses the line there.
  FaceData fd;
  fd.surface = plane_patch(Vec3(0, 0, 0), Vec3(100, 0, 0), Vec3(0, 100, 0));
  fd.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0.7, 1), Vec2(0.7, 0.3),
                       Vec2(0.3, 0.3), Vec2(0.3, 1), Vec2(0, 1)}});
  auto u = MoldSurface::from_face(fd);
  REQUIRE(u);
  const DrapeProblem pb = problem(2.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                  Vec3(15, 61, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  auto r = drape(*u, pb, DrapeOptions{});
  REQUIRE(r);
  CHECK_FALSE(r->partial);
  // On a plane the cloth maps rigidly: the whole U, 100^2 - 40 x 70 = 7200 mm^2, is one
  // piece of that area.
  const FlatPattern fp = flat_pattern(*u, *r, FlatPatternOptions{});
  CHECK(fp.outline.size() == 1);
  CHECK(fp.area == Approx(7200).epsilon(1e-9));
  const DrapeNode* arm = r->find(NodeId::regular(35, 15));  // (85, 91): the right arm's top
  REQUIRE(arm != nullptr);
  CHECK(arm->mapped());
}
