// The cut outline (kernel/src/pattern/outline_cleanup.hpp): features
// narrower than the minimum width w are cut off or closed, nothing else moves. Analytic
// polygons first, then drapes on the built-in molds.

#include "pattern/outline_cleanup.hpp"
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/polygon2d.hpp>
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/outline_checks.hpp"
#include "support/problems.hpp"
#include "support/shells.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

using namespace plyfit;

namespace {

// Areas below are closed forms of exact polygons: they agree to rounding of coordinates of
// size ~10 (a few ulps times the number of vertices).
constexpr double kAreaTol = 1e-12;

OutlineLoop loop(std::vector<Vec2> p, bool hole = false) {
  OutlineLoop l;
  l.points = std::move(p);
  l.hole = hole;
  return l;
}

// A length x width rectangle from the origin, turned by `deg` degrees, counter-clockwise with
// `per_side` points per side (collinear to rounding).
std::vector<Vec2> turned_rectangle(double length, double width, double deg, int per_side) {
  const double c = std::cos(deg * kDegToRad), s = std::sin(deg * kDegToRad);
  const Vec2 u(c, s), v(-s, c);
  const Vec2 corner[4] = {Vec2::Zero(), Vec2(length * u), Vec2(length * u + width * v),
                          Vec2(width * v)};
  std::vector<Vec2> p;
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < per_side; ++k)
      p.push_back(corner[side] +
                  (static_cast<double>(k) / per_side) * (corner[(side + 1) % 4] - corner[side]));
  return p;
}

// The square [0, 10]^2, counter-clockwise from (0, 0), with `top` inserted in its top edge
// (which runs from (10, 10) to (0, 10)).
OutlineLoop square_with(const std::vector<Vec2>& top) {
  std::vector<Vec2> p{Vec2(0, 0), Vec2(10, 0), Vec2(10, 10)};
  p.insert(p.end(), top.begin(), top.end());
  p.push_back(Vec2(0, 10));
  return loop(p);
}

bool has_vertex(const OutlineLoop& l, const Vec2& v) {
  return std::find(l.points.begin(), l.points.end(), v) != l.points.end();
}

// A regular polygon of n vertices about c, counter-clockwise (clockwise for a hole).
std::vector<Vec2> circle(Vec2 c, double r, int n, bool cw) {
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * kPi * k / n * (cw ? -1.0 : 1.0);
    p.push_back(c + r * Vec2(std::cos(t), std::sin(t)));
  }
  return p;
}

}  // namespace

TEST_CASE("outline cleanup: a thin outward wedge is cut where its width reaches w") {
  // A wedge of full angle 2a = 6 degrees on the square's top edge, tip 5 above it. The width
  // at a point of one side is its distance to the other side, r sin 2a at r from the tip; it
  // reaches w at r = w / sin 2a, and the chord runs square to the other side, whose foot is
  // r cos 2a from the tip: the triangle cut off has area w^2 / (2 tan 2a), with w the width
  // the chord is placed at (min_width (1 + kCutChordMargin)).
  const double a = 3.0 * kDegToRad, L = 5.0, w = 0.5, b = L * std::tan(a);
  const double wc = w * (1.0 + kCutChordMargin);
  const OutlineLoop sq = square_with({Vec2(5 + b, 10), Vec2(5, 10 + L), Vec2(5 - b, 10)});
  // The exact outline has the spike the checks see (d = 2w).
  REQUIRE_FALSE(support::outline_defects({sq}, 2 * w).empty());
  const auto res = outline_cleanup({sq}, {w});
  REQUIRE(res.loops.size() == 1);
  const OutlineLoop& c = res.loops[0];
  INFO(support::describe(support::outline_defects(res.loops, 2 * w)));
  CHECK(support::outline_defects(res.loops, 2 * w).empty());
  CHECK(res.slivers == 1);
  CHECK(res.added_area == 0.0);
  CHECK(std::abs(res.removed_area - wc * wc / (2.0 * std::tan(2 * a))) < kAreaTol);
  CHECK(std::abs(c.area - (100.0 + L * b - res.removed_area)) < kAreaTol);
  // The square and the wedge's base stay; the tip goes; two chord ends come in, w apart.
  for (const Vec2& v :
       {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10), Vec2(5 + b, 10), Vec2(5 - b, 10)})
    CHECK(has_vertex(c, v));
  CHECK_FALSE(has_vertex(c, Vec2(5, 10 + L)));
  CHECK(c.points.size() == 8);
  CHECK_FALSE(c.hole);
  CHECK(signed_area(c.points) > 0.0);
}

TEST_CASE("outline cleanup: an inward slit and a thin notch are closed across the mouth") {
  const double w = 0.5;
  SECTION("a slit 0.1 wide and 5 deep: closed whole, its area added") {
    const OutlineLoop sq =
        square_with({Vec2(5.05, 10), Vec2(5.05, 5), Vec2(4.95, 5), Vec2(4.95, 10)});
    REQUIRE_FALSE(support::outline_defects({sq}, 2 * w).empty());
    const auto res = outline_cleanup({sq}, {w});
    REQUIRE(res.loops.size() == 1);
    CHECK(support::outline_defects(res.loops, 2 * w).empty());
    CHECK(res.slivers == 1);
    CHECK(res.removed_area == 0.0);
    // The slit's rectangle 0.1 x 5 (its corners' coordinates are not exact in binary).
    CHECK(std::abs(res.added_area - 0.1 * 5.0) < 1e-9);
    CHECK(std::abs(res.loops[0].area - 100.0) < 1e-9);
    for (const Vec2& v : {Vec2(5.05, 5), Vec2(4.95, 5)}) CHECK_FALSE(has_vertex(res.loops[0], v));
  }
  SECTION("a notch of 6 degrees: the wedge of gap beyond width w is closed") {
    const double a = 3.0 * kDegToRad, L = 5.0, b = L * std::tan(a);
    const double wc = w * (1.0 + kCutChordMargin);  // the width the chord is placed at
    const OutlineLoop sq = square_with({Vec2(5 + b, 10), Vec2(5, 10 - L), Vec2(5 - b, 10)});
    REQUIRE_FALSE(support::outline_defects({sq}, 2 * w).empty());
    const auto res = outline_cleanup({sq}, {w});
    REQUIRE(res.loops.size() == 1);
    CHECK(support::outline_defects(res.loops, 2 * w).empty());
    CHECK(res.removed_area == 0.0);
    CHECK(std::abs(res.added_area - wc * wc / (2.0 * std::tan(2 * a))) < kAreaTol);
    CHECK(std::abs(res.loops[0].area - (100.0 - L * b + res.added_area)) < kAreaTol);
  }
}

TEST_CASE("outline cleanup: a rectangle, a disk with a hole of radius 3w, a slow curve stay") {
  const double w = 0.5;
  std::vector<OutlineLoop> in{loop({Vec2(0, 0), Vec2(20, 0), Vec2(20, 3), Vec2(0, 3)}),
                              loop(circle(Vec2(50, 0), 10.0, 96, false)),
                              loop(circle(Vec2(50, 0), 3 * w, 48, true), true)};
  // A slow curve: a sine-wave top edge, amplitude 1, wavelength 8, 200 vertices.
  std::vector<Vec2> wave{Vec2(0, 20), Vec2(40, 20)};
  for (int k = 200; k >= 0; --k)
    wave.push_back(Vec2(0.2 * k, 30 + std::sin(2 * kPi * 0.2 * k / 8.0)));
  in.push_back(loop(wave));
  const auto res = outline_cleanup(in, {w});
  REQUIRE(res.loops.size() == in.size());
  for (std::size_t k = 0; k < in.size(); ++k) {
    CHECK(res.loops[k].points == in[k].points);
    CHECK(res.loops[k].hole == in[k].hole);
  }
  CHECK(res.slivers == 0);
  CHECK(res.removed_area == 0.0);
  CHECK(res.added_area == 0.0);
}

TEST_CASE("outline cleanup: a turned rectangle with many points per side stays") {
  // 100 x 80 turned by 43 degrees, 40 points per side (collinear to rounding).
  const std::vector<Vec2> p = turned_rectangle(100, 80, 43, 40);
  const auto res = outline_cleanup({loop(p)}, {0.5});
  REQUIRE(res.loops.size() == 1);
  CHECK(res.loops[0].points == p);
  CHECK(res.slivers == 0);
}

TEST_CASE("outline cleanup: loops narrower than w everywhere are dropped") {
  const double w = 0.5;
  const OutlineLoop sq = square_with({});
  // A triangle 0.3 across, and a bow-tie of area 0.03 (two lobes of 0.015).
  const OutlineLoop tri = loop({Vec2(20, 0), Vec2(20.3, 0), Vec2(20.1, 0.2)});
  const OutlineLoop bow = loop({Vec2(30, 0), Vec2(30.3, 0.1), Vec2(30.3, 0), Vec2(30, 0.1)});
  const auto res = outline_cleanup({tri, sq, bow}, {w});
  REQUIRE(res.loops.size() == 1);
  CHECK(res.loops[0].points == sq.points);
  CHECK(res.loops_dropped == 2);
  CHECK(res.slivers == 2);
  CHECK(std::abs(res.removed_area - 0.5 * 0.3 * 0.2) < 1e-12);
  // The bow-tie's signed area is 0 (its lobes cancel): nothing counted for it.
  CHECK(res.added_area == 0.0);
  // A 0.4 x 0.4 square goes at w = 0.5 and stays at w = 0.35.
  const OutlineLoop small = loop({Vec2(0, 0), Vec2(0.4, 0), Vec2(0.4, 0.4), Vec2(0, 0.4)});
  CHECK(outline_cleanup({small}, {0.5}).loops.empty());
  CHECK(outline_cleanup({small}, {0.35}).loops.size() == 1);
}

TEST_CASE("outline cleanup: a long strip of many points goes or stays by its width alone") {
  // 100 x 0.4 turned by 29 degrees, 400 points per side: the width test samples long loops
  // first (every 16th point); the answer must be the full hull's on both sides of the width.
  const std::vector<Vec2> p = turned_rectangle(100, 0.4, 29, 400);
  const auto gone = outline_cleanup({loop(p)}, {0.5});
  CHECK(gone.loops.empty());
  CHECK(gone.loops_dropped == 1);
  CHECK(std::abs(gone.removed_area - 40.0) < 1e-9);
  const auto kept = outline_cleanup({loop(p)}, {0.35});
  REQUIRE(kept.loops.size() == 1);
  CHECK(kept.loops[0].points == p);
  CHECK(kept.slivers == 0);
}

TEST_CASE("outline cleanup: w = 0 leaves every outline as it is") {
  const double a = 3.0 * kDegToRad, L = 5.0, b = L * std::tan(a);
  const std::vector<OutlineLoop> in{
      square_with({Vec2(5 + b, 10), Vec2(5, 10 + L), Vec2(5 - b, 10)}),
      loop({Vec2(20, 0), Vec2(20.3, 0), Vec2(20.1, 0.2)})};
  const auto res = outline_cleanup(in, {0.0});
  REQUIRE(res.loops.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) CHECK(res.loops[k].points == in[k].points);
  CHECK(res.slivers == 0);
}

namespace {

Face builtin(const std::string& name) {
  auto f = Face::create(builtin_mold(name, {}).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

// The cut outline of a drape: simple and spike-free by the plain geometric check (no
// drape-aware excuse), its loops oriented (outer counter-clockwise, holes clockwise), and
// its area the exact one's less the cloth laid twice and what was removed, plus what was
// added.
void check_cut(const FlatPattern& fp, double d) {
  const auto defects = support::outline_defects(fp.cut, d);
  INFO(support::describe(defects));
  CHECK(defects.empty());
  for (const OutlineLoop& l : fp.cut) {
    CHECK(l.points.size() >= 3);
    CHECK((signed_area(l.points) > 0.0) == !l.hole);
  }
  CHECK(std::abs(fp.cut_area - (fp.area - fp.laid_twice_area - fp.cut_removed_area +
                                fp.cut_added_area)) <= 1e-9 * std::max(1.0, std::abs(fp.area)));
  // Only narrow features go: each is narrower than w along its length, so its area is below
  // w times half the outline it takes away (a strip: w L against 2 L of outline; a dropped
  // loop: its hull width times its diameter); in all, below w times the exact perimeter.
  CHECK(fp.cut_removed_area + fp.cut_added_area <= fp.min_width * fp.perimeter);
}

// The random drapes of tests/kernel/outline_quality_test.cpp (same seeds and draws); the
// number drapes made, and the slivers removed in all.
struct Tally {
  int checked = 0, slivers = 0, exact_spiky = 0;
};
void random_cuts(const DrapeSurface& s, const std::string& name, unsigned seed, int count,
                 Tally& t) {
  std::mt19937 g(seed);
  for (int k = 0; k < count; ++k) {
    const support::RandomDrape rd = support::random_drape(s, name, k, g);
    const auto r = drape(s, rd.problem, rd.options);
    if (!r.ok()) continue;
    const FlatPattern fp = flat_pattern(s, *r);
    INFO(rd.what);
    check_cut(fp, rd.d);
    ++t.checked;
    t.slivers += fp.slivers;
    t.exact_spiky += !support::outline_defects(fp.outline, rd.d).empty();
  }
}

}  // namespace

TEST_CASE("outline cleanup: a drape's strip narrower than w is cut off (hemisphere)") {
  // tests/kernel/outline_quality_test.cpp's first narrow shape: a strip of cloth 0.18 d
  // wide between the face's edge and a row stopped by overlap; its exact outline turns back
  // within d / 2 (a spike no cutter can follow).
  const Face f = builtin("hemisphere");
  const double d = 0.10973817914653033;
  const auto r = drape(
      f, support::problem(d, Vec2(0, 0), Vec2(0.99834856016847195, -0.057446953004828792),
                          {Vec2(0.057446953004828792, 0.99834856016847195)},
                          Vec3(0.23447179449406841, 0.13044943651281971, 0.54521187752363209),
                          Vec3(-0.99580287622940966, -0.064639367141352835, 0.064794937370141345),
                          {Vec3(-0.43134763568172607, -0.55503042602519637, 0.71125272820430974)}));
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(f, *r);
  REQUIRE_FALSE(support::outline_defects(fp.outline, d).empty());
  CHECK(fp.min_width == 0.5 * d);
  check_cut(fp, d);
  CHECK(fp.slivers >= 1);
  CHECK(fp.cut_removed_area > 0.0);
  // What goes is narrow: less than w times the exact outline's perimeter.
  CHECK(fp.cut_removed_area + fp.cut_added_area < 0.5 * d * fp.perimeter);
  // Off, the cut outline is the exact one, less its pieces beyond the seam (the two cut off
  // between the face's edge and the nodes stopped by overlap: pieces.hpp), loop for loop.
  FlatPatternOptions off;
  off.min_width = 0.0;
  const FlatPattern fo = flat_pattern(f, *r, off);
  for (const auto& c : fo.cut)
    CHECK(std::any_of(fo.outline.begin(), fo.outline.end(),
                      [&](const OutlineLoop& l) { return l.points == c.points; }));
  CHECK(fo.cut.size() < fo.outline.size());
  CHECK(fo.cut_area == Approx(fo.area - fo.laid_twice_area).epsilon(1e-12));
  CHECK(fo.slivers == 0);
}

TEST_CASE("outline cleanup: a wide pattern whose hull has points collinear to rounding stays") {
  // Random drape 0 on the plane (seed 6 of the drapes below): the outline's convex hull has
  // a run of points along the base path, collinear to rounding, where the distance from the
  // first hull edge dips by 1e-15; the rotating calipers stopped there and took the
  // 100 x 80 pattern for one 2e-14 wide, and the clean-up dropped it whole.
  const Face f = builtin("plane");
  const double d = 6.4274606472429019;
  const auto r = drape(
      f, support::problem(d, Vec2(0, 0), Vec2(-0.68504804119089324, 0.72849789379278251),
                          {Vec2(0.72849789379278251, 0.68504804119089324)},
                          Vec3(67.899043056116071, 38.376254628710257, 0),
                          Vec3(-0.8805831463862257, -0.45741355188933158, 0.12387963855501359),
                          {Vec3(-0.84717622892816025, 0.41809783251337729, 0.32785155114270426)}));
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(f, *r);
  REQUIRE(fp.outline.size() == 1);
  REQUIRE(fp.cut.size() == 1);
  CHECK(fp.cut[0].points == fp.outline[0].points);
  CHECK(fp.slivers == 0);
  CHECK(fp.cut_area == fp.area);
}

TEST_CASE("outline cleanup: cut outlines are simple and spike-free on every built-in mold") {
  Tally t;
  unsigned seed = 1;
  int molds = 0;
  for (const BuiltinInfo& info : builtin_molds()) {
    random_cuts(builtin(info.name), info.name, seed++, 12, t);
    ++molds;
  }
  CHECK(t.checked >= 6 * molds);
  // The check can fail: some exact outlines of these drapes have spikes.
  CHECK(t.exact_spiky > 0);
  CHECK(t.slivers >= t.exact_spiky);
}

TEST_CASE("outline cleanup: cut outlines are simple and spike-free on every built-in shell") {
  Tally t;
  unsigned seed = 100;
  for (const BuiltinInfo& info : builtin_shells()) {
    auto sh = support::make_builtin_shell(info.name);
    REQUIRE(sh.ok());
    random_cuts(*sh, info.name, seed++, 12, t);
  }
  CHECK(t.checked >= 6 * static_cast<int>(builtin_shells().size()));
}

TEST_CASE("outline cleanup: cut outlines on 40 more random drapes per mold (the blade too)",
          "[slow]") {
  Tally t;
  unsigned seed = 1000;
  for (const BuiltinInfo& info : builtin_molds())
    random_cuts(builtin(info.name), info.name, seed++, 40, t);
  INFO(t.checked << " drapes, " << t.exact_spiky << " exact outlines with spikes, " << t.slivers
                 << " slivers");
  CHECK(t.exact_spiky > 0);
}

TEST_CASE(
    "outline cleanup: the exact outline's faults and spikes come out of the cut outline clean") {
  // The exact outline's faults found by random drapes (support::fixed_outline_faults: a
  // zigzag next to a pole, a slit where a node sits on the face edge, a tiny loop at a face
  // corner, fixed in the flat pattern) and the spikes once taken for faults
  // (support::explained_outline_spikes: a sliver on the blade, the draped region's own).
  // Whatever the exact outline does there, the cut outline has no spike and no crossing.
  std::vector<support::DrapeCase> cases = support::fixed_outline_faults();
  for (const support::DrapeCase& c : support::explained_outline_spikes()) cases.push_back(c);
  for (const support::DrapeCase& c : cases) {
    INFO(c.what);
    const Face f = builtin(c.mold);
    const auto r = drape(f, c.problem(), c.options());
    REQUIRE(r.ok());
    check_cut(flat_pattern(f, *r), c.d);
  }
}

TEST_CASE("outline cleanup: a chord is no shorter than w to rounding (full cylinder in parts)") {
  // A 15-minute fuzz drape (seed 37): a sliver cut by a chord of w less an ulp as the fuzz
  // measured it (0.25181099999999995 for w = 0.251811), which with the edge before it turned
  // back by 174 degrees within w: the cut outline's own chord made a spike by the checks'
  // definition.
  auto sh = support::make_builtin_shell("cylinder-split", {{"angle", 360.0}, {"parts", 3.0}});
  REQUIRE(sh.ok());
  const double d = 0.503622;
  const auto r =
      drape(*sh, support::problem(d, Vec2(0, 0), Vec2(0.994361, 0.106050),
                                  {Vec2(0.106050, -0.994361)}, Vec3(0.332703, -3.620461, 8.960990),
                                  Vec3(0.260646, 0.268935, -0.927220),
                                  {Vec3(0.728350, 0.683438, -0.049179)}));
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(*sh, *r);
  CHECK(fp.slivers >= 1);
  check_cut(fp, d);
  // The fuzz measures in Python (math.dist, another rounding): the cut outline must pass a
  // check whose w is larger by far more than rounding and far less than anything that
  // matters (a chord placed at exactly w fails it).
  const auto defects = support::outline_defects(fp.cut, d * (1.0 + 1e-12));
  INFO(support::describe(defects));
  CHECK(defects.empty());
}
