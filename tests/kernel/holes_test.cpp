// A base path that crosses a hole in the face (issue 13 item 2): the sweeps on either side of
// the path must join beyond the hole, so that the flat pattern is the plate less the hole.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/face.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <catch2/catch.hpp>

#include "support/problems.hpp"

#include <cmath>
#include <string>

using namespace plyfit;
using plyfit::support::problem;

namespace {

constexpr double kPi = 3.14159265358979323846;

Face plate_with_hole() {
  auto fd = builtin_mold(
      "plate", {{"W", 100.0}, {"H", 60.0}, {"hole_r", 10.0}, {"hole_x", 50.0}, {"hole_y", 30.0}});
  REQUIRE(fd.ok());
  auto f = Face::create(std::move(fd).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

}  // namespace

// Hidden ([.]): open, issue 13 item 2. Solving the path line beyond the hole from the sweep
// that reaches it first passes this test, but on a curved face (the dish sample) that sweep's
// cloth crosses the line and meets the other sweep's coming round the hole, sheared past the
// fold angle: a shear-limit node there stopped a quadrant (3059 -> 2635 nodes mapped). Run it
// with: plyfit_kernel_tests "[issue13]".
TEST_CASE("drape: a base path across a hole is joined beyond it by the two sweeps",
          "[.][issue13]") {
  const Face f = plate_with_hole();
  // Spacings that put nodes on the path line inside and beyond the hole, with and without a
  // node on the hole's rim.
  for (double d : {2.0, 1.7, 2.5}) {
    INFO("d = " << d);
    auto rr = drape(f, problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                               Vec3(20, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
    REQUIRE(rr.ok());
    const DrapeResult& r = rr.value();
    CHECK(r.metrics.nodes.failed == 0);
    CHECK_FALSE(r.partial);
    // Every node strictly inside the plate and off the hole's rim is mapped (on a plane the
    // ply lies on the face: ply point p is at (20, 30) + p), so no slit is left between the
    // two sweeps.
    const Ply& ply = *r.ply;
    const int ni = static_cast<int>(std::ceil(100 / d)), nj = static_cast<int>(std::ceil(60 / d));
    int missing = 0, inside = 0;
    for (int i = -ni; i <= ni; ++i) {
      for (int j = -nj; j <= nj; ++j) {
        const Vec2 p = ply.pos(i, j) + Vec2(20, 30);
        constexpr double kRim = 1e-9;  // nodes this close to a boundary may fall either way
        if (!(p.x() > kRim && p.x() < 100 - kRim && p.y() > kRim && p.y() < 60 - kRim) ||
            (p - Vec2(50, 30)).norm() < 10 + kRim)
          continue;
        ++inside;
        const auto k = r.index.find(NodeId::regular(i, j));
        if (k >= 0 && r.nodes[static_cast<std::size_t>(k)].mapped()) continue;
        UNSCOPED_INFO(
            "inside, not mapped: ("
            << i << ", " << j << ") "
            << (k >= 0 ? to_string(r.nodes[static_cast<std::size_t>(k)].status) : "never reached"));
        ++missing;
      }
    }
    CHECK(inside > 500);
    CHECK(missing == 0);
    // The flat pattern: the plate less the hole (a plane: the ply is the face itself, up to
    // the hole's polygonal trim, whose area differs from pi r^2 by O(r h^2)); one outer loop
    // and one hole loop.
    const FlatPattern fp = flat_pattern(f, r);
    int outer = 0, holes = 0;
    for (const OutlineLoop& l : fp.outline) (l.hole ? holes : outer) += 1;
    CHECK(outer == 1);
    CHECK(holes == 1);
    CHECK(fp.area == Approx(6000.0 - kPi * 100.0).epsilon(2e-3));
  }
}
