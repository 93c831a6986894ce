#include <plyfit/kernel/polygon2d.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plyfit;

namespace {

std::vector<Vec2> points(const std::vector<ClipVertex>& loop) {
  std::vector<Vec2> p;
  for (const ClipVertex& v : loop) p.push_back(v.p);
  return p;
}

double total_area(const std::vector<std::vector<ClipVertex>>& loops) {
  double a = 0;
  for (const auto& l : loops) a += signed_area(points(l));
  return a;
}

}  // namespace

TEST_CASE("polygon2d: a square with a hole clipped to a slab keeps its vertices and the hole") {
  // The square [0, 4]^2 (counter-clockwise) with the hole [1, 3]^2 (clockwise), in the slab
  // 0.5 <= x <= 2: the strips [0.5, 1] x [0, 4] and [1, 2] x ([0, 1] u [3, 4]), area 2 + 2.
  const Region2 r = {{Vec2(0, 0), Vec2(4, 0), Vec2(4, 4), Vec2(0, 4)},
                     {Vec2(1, 1), Vec2(1, 3), Vec2(3, 3), Vec2(3, 1)}};
  const auto out = clip_to_slab(r, 0.5, 2.0);
  REQUIRE(out.size() == 1);  // one loop round the C shape
  CHECK(total_area(out) == 4.0);
  for (const auto& l : out)
    for (const ClipVertex& v : l) {
      CHECK(v.p.x() >= 0.5);
      CHECK(v.p.x() <= 2.0);
      // Each vertex is on its input edge, at t along it.
      const auto& loop = r[v.loop];
      const Vec2 on = loop[v.edge] + v.t * (loop[(v.edge + 1) % loop.size()] - loop[v.edge]);
      CHECK((on - v.p).norm() == Approx(0.0).margin(1e-15));
    }
  // The hole's corners (1, 1) and (1, 3) are kept exactly.
  int kept = 0;
  for (const ClipVertex& v : out[0])
    if (v.p == Vec2(1, 1) || v.p == Vec2(1, 3)) ++kept;
  CHECK(kept == 2);
}

TEST_CASE("polygon2d: a slab across a U's arms gives a loop per arm") {
  // A U: [0, 3]^2 less the notch [1, 2] x [1, 3]. The slab 1.5 <= x <= 3 holds half the
  // base and the right arm: one loop of area 1.5 + 2.
  const Region2 u = {{Vec2(0, 0), Vec2(3, 0), Vec2(3, 3), Vec2(2, 3), Vec2(2, 1), Vec2(1, 1),
                      Vec2(1, 3), Vec2(0, 3)}};
  CHECK(total_area(clip_to_slab(u, 1.5, 3.0)) == Approx(1.5 + 2.0).epsilon(1e-15));
  // The U on its side (arms along x): a slab across both arms gives two loops.
  const Region2 c = {{Vec2(0, 0), Vec2(3, 0), Vec2(3, 1), Vec2(1, 1), Vec2(1, 2), Vec2(3, 2),
                      Vec2(3, 3), Vec2(0, 3)}};
  const auto arms = clip_to_slab(c, 2.0, 2.5);
  REQUIRE(arms.size() == 2);
  for (const auto& l : arms) CHECK(signed_area(points(l)) == Approx(0.5).epsilon(1e-15));
  // Infinite bounds keep the region as it is.
  const auto whole = clip_to_slab(c, -INFINITY, INFINITY);
  REQUIRE(whole.size() == 1);
  CHECK(whole[0].size() == c[0].size());
  CHECK(total_area(whole) == signed_area(c[0]));
  // A slab beside the region leaves nothing.
  CHECK(clip_to_slab(c, 4.0, 5.0).empty());
}

TEST_CASE("polygon2d: a region less another: a hole, a bite, and nothing when they do not meet") {
  const std::vector<Vec2> square{Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10)};
  const std::vector<Vec2> inner{Vec2(2, 2), Vec2(4, 2), Vec2(4, 5), Vec2(2, 5)};
  // A square inside: a hole of 6 (loops whose even-odd area is 100 - 6).
  const auto holed = subtract_regions({square}, {inner});
  REQUIRE(holed);
  CHECK(holed->size() == 2);
  CHECK(region_area(*holed) == Approx(94.0).epsilon(1e-14));
  // A triangle over the right edge: the part inside bitten off, a trapezoid 2 wide between
  // heights 4 (x = 8) and 2 (x = 10).
  const std::vector<Vec2> tri{Vec2(8, 3), Vec2(12, 5), Vec2(8, 7)};
  const auto bitten = subtract_regions({square}, {tri});
  REQUIRE(bitten);
  CHECK(region_area(*bitten) == Approx(100.0 - 6.0).epsilon(1e-14));
  // A square inside the hole of an even-odd region (the square with the inner hole) does not
  // meet it, nor does one far away: none (the region stays whole).
  const std::vector<Vec2> in_hole{Vec2(2.5, 2.5), Vec2(3.5, 2.5), Vec2(3.5, 3.5), Vec2(2.5, 3.5)};
  CHECK_FALSE(subtract_regions({square, inner}, {in_hole}));
  const std::vector<Vec2> far{Vec2(20, 0), Vec2(21, 0), Vec2(21, 1)};
  CHECK_FALSE(subtract_regions({square}, {far}));
}

TEST_CASE("polygon2d: many regions united: overlaps counted once, a ring's hole kept") {
  auto square = [](double x, double y, double a) {
    return std::vector<Vec2>{Vec2(x, y), Vec2(x + a, y), Vec2(x + a, y + a), Vec2(x, y + a)};
  };
  // Five unit squares in a row, each overlapping the next by a half: 3 units long, 1 high.
  std::vector<Region2> row;
  for (int k = 0; k < 5; ++k) row.push_back({square(0.5 * k, 0, 1)});
  CHECK(region_area(unite_all(row)) == Approx(3.0).epsilon(1e-14));
  // A frame (a square with a square hole) and a square inside the hole not touching it: the
  // hole's remaining ring stays a hole; and no regions at all: an empty region.
  const Region2 frame{square(0, 0, 10), square(2, 2, 6)};
  const Region2 island{square(4, 4, 2)};
  CHECK(region_area(unite_all({frame, island})) == Approx(100.0 - 36.0 + 4.0).epsilon(1e-14));
  CHECK(unite_all({}).empty());
}
