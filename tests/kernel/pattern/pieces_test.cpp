#include "pattern/pieces.hpp"
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "pattern/outline_cleanup.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/outline_checks.hpp"
#include "support/problems.hpp"
#include "support/shells.hpp"
#include "support/surfaces.hpp"

#include <cmath>

using namespace plyfit;
using detail::ClothCorner;

namespace {

// A unit square of cloth: corners at height z on the mold, at ply offset (x0, 0).
std::vector<ClothCorner> square(double x0, double z, bool nodes = true) {
  std::vector<ClothCorner> c;
  for (const Vec2& p : {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)})
    c.push_back({Vec3(p.x(), p.y(), z), Vec2(x0 + p.x(), p.y()), nodes});
  return c;
}

// A barrel (radius 100 at the ends, 108 in the middle rows of poles, 300 long) of eight
// bicubic Bezier skins of 45 degrees each, sewn into a tube: the mold of
// samples/molds/hard/tube-8-skins.step (scripts/make-hard-molds), u round the axis, v along it.
Shell barrel_tube() {
  ShellData sd;
  const double k = 4.0 / 3.0 * std::tan(kPi / 16.0);  // a cubic's handles for a 45 degree arc
  for (int s = 0; s < 8; ++s) {
    const double a0 = s * kPi / 4.0, a1 = (s + 1) * kPi / 4.0;
    const double c0 = std::cos(a0), s0 = std::sin(a0), c1 = std::cos(a1), s1 = std::sin(a1);
    NurbsSurfaceData b = support::bezier_patch(3);
    for (int iv = 0; iv < 4; ++iv) {
      const double r = 100.0 * (iv == 1 || iv == 2 ? 1.08 : 1.0), z = 100.0 * iv;
      b.pole(0, iv) = Vec3(r * c0, r * s0, z);
      b.pole(1, iv) = Vec3(r * (c0 - k * s0), r * (s0 + k * c0), z);
      b.pole(2, iv) = Vec3(r * (c1 + k * s1), r * (s1 - k * c1), z);
      b.pole(3, iv) = Vec3(r * c1, r * s1, z);
    }
    FaceData fd;
    TrimLoop loop;
    loop.points = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    // Sides: v = 0 (an end circle), u = 1 (edge s, shared with skin s + 1), v = 1, u = 0.
    loop.edges = {TrimLoop::kFreeEdge, s, TrimLoop::kFreeEdge, (s + 7) % 8};
    fd.surface = std::move(b);
    fd.loops.push_back(std::move(loop));
    fd.name = "skin-" + std::to_string(s);
    sd.faces.push_back(std::move(fd));
  }
  sd.edge_count = 8;
  auto sh = Shell::create(std::move(sd));
  REQUIRE(sh.ok());
  return std::move(sh).value();
}

int outer_loops(const std::vector<OutlineLoop>& loops, double max_area = INFINITY) {
  int n = 0;
  for (const auto& l : loops) n += !l.hole && l.area <= max_area;
  return n;
}

// The largest distance on the ply from a vertex of `loops` to the nearest mapped node.
double farthest_from_cloth(const std::vector<OutlineLoop>& loops, const DrapeResult& r) {
  std::vector<Vec2> mapped;
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) mapped.push_back(n.ply);
  double farthest = 0.0;
  for (const auto& l : loops)
    for (const Vec2& p : l.points) {
      double near = INFINITY;
      for (const Vec2& q : mapped) near = std::min(near, (p - q).norm());
      farthest = std::max(farthest, near);
    }
  return farthest;
}

}  // namespace

TEST_CASE(
    "pieces: a polygon with a node on the cloth of a larger piece far on the ply is laid "
    "twice") {
  // Piece 0: polygon 0, a unit square at z = 0. Piece 1: polygon 1 a hair above it (0.1, under
  // the radius 0.5) but 10 away on the ply; polygon 2 as high but at the ply's square (the
  // same cloth, as where two pieces share a vertex); polygon 3 far above (2); polygon 4 just
  // above, its corners not nodes (crossings: the rule tests nodes only).
  const std::vector<std::vector<ClothCorner>> polys = {
      square(0, 0), square(10, 0.1), square(1, 0.1), square(20, 2.0), square(30, 0.1, false)};
  const auto corners = [&](int p, std::vector<ClothCorner>& out) {
    out = polys[static_cast<std::size_t>(p)];
  };
  const auto twice =
      detail::polygons_laid_twice({{0}, {1, 2, 3, 4}}, polys.size(), corners, 0.5, 2.0);
  CHECK(twice == std::vector<bool>{false, true, false, false, false});
  // Which of two pieces is laid twice is decided by their order (larger first), not by
  // which lies above.
  CHECK(detail::polygons_laid_twice({{1}, {0}}, polys.size(), corners, 0.5, 2.0) ==
        std::vector<bool>{true, false, false, false, false});
  // A piece on no cloth (polygon 3) is left out when the cloth round it stops at the seam
  // (border 1) and only there or at the face's edge (0); not where a shear limit stops it
  // too (-1), nor where the seam is not round it at all.
  const std::vector<std::vector<int>> two = {{0}, {3, 4}};
  auto with = [&](int b3, int b4) {
    return detail::polygons_laid_twice(two, polys.size(), corners, 0.5, 2.0,
                                       [&](int p) { return p == 3 ? b3 : b4; });
  };
  CHECK(with(1, 0) == std::vector<bool>{false, false, false, true, true});
  CHECK(with(1, 1) == std::vector<bool>{false, false, false, true, true});
  CHECK(with(1, -1) == std::vector<bool>(polys.size(), false));
  CHECK(with(0, 0) == std::vector<bool>(polys.size(), false));
  // One piece: nothing to test against.
  CHECK(detail::polygons_laid_twice({{0, 1}}, polys.size(), corners, 0.5, 2.0) ==
        std::vector<bool>(polys.size(), false));
}

TEST_CASE("flat pattern: a tube of 8 skins wrapped whole is cut in one piece (no single cells)") {
  // The drape of samples/molds/hard/tube-8-skins.step at the corpus campaign's settings
  // (spacing sqrt(tube area) / 40, from skin 0's middle, base path round the barrel): the
  // threads that come round onto the cloth past the drape's overlap test make pieces of
  // their own, single cells among them, which a cutter would cut.
  const Shell tube = barrel_tube();
  const double d = 11.0748;
  const double a = kPi / 8.0, r = 100.0 * (1.0 + 0.08 * 0.75);  // skin 0 at (u, v) = (0.5, 0.5)
  const Vec3 start(r * std::cos(a), r * std::sin(a), 150.0), z(0, 0, 1);
  auto res = drape(tube, support::problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                          start, z, {z, -z}));
  REQUIRE(res.ok());
  REQUIRE(res->metrics.nodes.overlap > 0);  // the cloth came round onto itself
  const FlatPattern fp = flat_pattern(tube, *res);
  REQUIRE(!fp.outline.empty());
  // The case: the exact outline is in pieces, and cleaning it alone leaves single cells.
  CHECK(outer_loops(fp.outline) > 1);
  CHECK(outer_loops(outline_cleanup(fp.outline, {fp.min_width}).loops, 1.5 * d * d) > 0);
  // The cut outline: one piece, simple and spike-free, the exact outline's largest piece
  // (which no cloth lies on) less what the clean-up took.
  CHECK(fp.cells_laid_twice > 0);
  CHECK(outer_loops(fp.cut) == 1);
  const auto defects = support::outline_defects(fp.cut, d);
  INFO(support::describe(defects));
  CHECK(defects.empty());
  CHECK(farthest_from_cloth(fp.cut, *res) <= std::sqrt(2.0) * d);
  const double largest = fp.outline.front().area;
  CHECK(std::abs(fp.cut_area - (largest - fp.cut_removed_area + fp.cut_added_area)) <=
        1e-9 * largest);
  CHECK(std::abs(fp.cut_area - (fp.area - fp.laid_twice_area - fp.cut_removed_area +
                                fp.cut_added_area)) <= 1e-9 * largest);
}

TEST_CASE("flat pattern: a sphere of 8 faces wrapped whole: no piece beyond the seam") {
  // samples/molds/sphere-8.step (builtin sphere-8, radius 20) draped whole from face 0's
  // suggested start (plyfit info), d = 1: the cloth comes round onto itself and the drape
  // stops it there (overlap) and where fronts meet that cannot be joined (conflict). Between
  // those stops some cloth escaped the overlap test: single cells and small pieces of their
  // own, cut off from the rest by the seam all round. They are no cloth to cut; a piece cut
  // off by another stop (a lock) too stays.
  auto sh = support::make_builtin_shell("sphere-8");
  REQUIRE(sh.ok());
  const double d = 1.0;
  const Vec3 bn(-std::sqrt(0.5), std::sqrt(0.5), 0);
  auto res = drape(*sh, support::problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                         Vec3(10, 10, -std::sqrt(200.0)), bn, {bn, -bn}));
  REQUIRE(res.ok());
  REQUIRE(res->metrics.nodes.overlap > 0);  // the cloth came round onto itself
  const FlatPattern fp = flat_pattern(*sh, *res);
  REQUIRE(!fp.outline.empty());
  // The case: the exact outline has single cells, which cleaning it alone keeps.
  CHECK(outer_loops(outline_cleanup(fp.outline, {fp.min_width}).loops, 1.5 * d * d) > 0);
  // The cut outline: no loop of a cell, no spike, every vertex within a cell's diagonal of a
  // mapped node; one piece (the base path's slit is a hole in it).
  CHECK(outer_loops(fp.cut, 1.5 * d * d) == 0);
  CHECK(outer_loops(fp.cut) == 1);
  const auto defects = support::outline_defects(fp.cut, d);
  INFO(support::describe(defects));
  CHECK(defects.empty());
  CHECK(farthest_from_cloth(fp.cut, *res) <= std::sqrt(2.0) * d);
}
