#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/polygon2d.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"
#include "support/outline_checks.hpp"
#include "support/problems.hpp"

#include <cmath>

using namespace plyfit;

namespace {

// On a plane both sides of a dart drape as the uncut ply (cut lines within 1e-9 d of each
// other): the outline keeps its area to that, relative.
constexpr double kFlatRel = 1e-9;
// The V is taken out by a polygon boolean (Boost.Geometry), which rounds the points it makes to
// about 1e-6 of the region's extent: areas agree to that times the length of the V's edges
// (a few units here), relative to the ply's area.
constexpr double kBooleanRel = 1e-6;

DrapeResult ok(Result<DrapeResult> r) {
  INFO((r.ok() ? std::string() : exporters::describe(r.error())));
  REQUIRE(r.ok());
  return std::move(r).value();
}

// The region between a dart's cut lines (the left line to the tip, the right one back).
Region2 v_of(const DartResult& d) {
  std::vector<Vec2> v(d.line_left.begin(), d.line_left.end());
  v.insert(v.end(), d.line_right.rbegin(), d.line_right.rend());
  return {v};
}

Region2 region_of(const std::vector<OutlineLoop>& loops) {
  Region2 r;
  for (const auto& l : loops) r.push_back(l.points);
  return r;
}

bool inside(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  bool in = false;
  for (const auto& l : loops) in = in != inside_polygon(l.points, p);
  return in;
}

}  // namespace

TEST_CASE("dart notch: a straight dart on a plane leaves the outline as without it") {
  const MoldSurface f = support::builtin_surface("plane");  // [0, 100]^2, z = 0
  const double d = 2.0;
  DrapeProblem pb =
      support::problem(d, Vec2(0.3, 0.7), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, Vec3(50, 50, 0),
                       Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  const FlatPattern plain = flat_pattern(f, ok(drape(f, pb)));
  pb.darts = {{Vec3(20.3, 0, 0), Vec3(60.3, 35.1, 0)}};  // from the edge y = 0 into the ply
  const DrapeResult r = ok(drape(f, pb));
  REQUIRE(r.darts.size() == 1);
  CHECK(r.darts[0].nodes_cut_out == 0);
  const FlatPattern fp = flat_pattern(f, r);
  CHECK(fp.area == Approx(plain.area).epsilon(kFlatRel));
  CHECK(fp.cut_area == Approx(plain.cut_area).epsilon(kFlatRel));
  CHECK(fp.outline.size() == plain.outline.size());
  CHECK(support::outline_defects(fp.outline, d).empty());
  CHECK(support::outline_defects(fp.cut, d).empty());
}

TEST_CASE("dart notch: beside a dart on a hemisphere the outline ends at the cut lines") {
  // The hemisphere sample (R = 1, d = 0.05, base path over the pole, both sweeps) with a dart
  // on the meridian at azimuth 45 deg from the rim to 40 deg from the pole.
  const double R = 1.0, d = 0.05;
  const MoldSurface f = support::builtin_surface("hemisphere", {{"R", R}});
  DrapeProblem pb = support::pole_problem(R, d);
  pb.darts = {support::meridian_dart(R)};
  const DrapeResult r = ok(drape(f, pb));
  REQUIRE(r.darts.size() == 1);
  const DartResult& dart = r.darts[0];
  REQUIRE(dart.nodes_cut_out > 0);
  REQUIRE(dart.removed_area > 0.0);
  const FlatPattern fp = flat_pattern(f, r);
  REQUIRE(fp.outline.size() == 1);
  // The exact outline crosses itself nowhere; it turns back only at the V's tip, as sharp as
  // the cut lines meet (the cut outline closes what is narrower than its minimum width).
  for (const auto& x : support::outline_defects(fp.outline, d)) {
    INFO(support::describe({x}));
    CHECK(x.kind == support::OutlineDefect::kSpike);
    CHECK((x.at - dart.line_left.back()).norm() < d);
  }
  INFO(support::describe(support::outline_defects(fp.cut, d)));
  CHECK(support::outline_defects(fp.cut, d).empty());
  CHECK(fp.cut.size() == 1);

  // Within a disc about the start well inside the rim, every cell is cloth (mapped, or cut
  // out by the dart and so counted whole): the outline there is the disc less the V between
  // the cut lines, and no other cloth is lost beside it.
  const double rw = 1.3 * R;
  std::vector<Vec2> disc;
  for (int k = 0; k < 256; ++k)
    disc.push_back(rw * Vec2(std::cos(k * 2 * kPi / 256), std::sin(k * 2 * kPi / 256)));
  const double v_in = region_area(intersect_regions(v_of(dart), {disc}));
  const double in = region_area(intersect_regions(region_of(fp.outline), {disc}));
  INFO("disc " << region_area({disc}) << ", V in it " << v_in << " (V " << dart.removed_area
               << "), outline in it " << in << "; outline " << fp.area << ", cut " << fp.cut_area);
  CHECK(v_in > 0.5 * dart.removed_area);
  CHECK(in == Approx(region_area({disc}) - v_in).epsilon(kBooleanRel));

  // No cloth in the V, up to the rim: the middle of each pair of cut-line points, and the
  // mouth beyond the lines' first points, lie outside the outline.
  for (std::size_t i = 0; i + 1 < dart.line_left.size(); ++i) {
    const Vec2 m = 0.25 * (dart.line_left[i] + dart.line_left[i + 1] + dart.line_right[i] +
                           dart.line_right[i + 1]);
    if ((dart.line_left[i] - dart.line_right[i]).norm() > d) CHECK_FALSE(inside(fp.outline, m));
  }
  const Vec2 mouth = 0.5 * (dart.line_left[0] + dart.line_right[0]);
  const Vec2 out = (mouth - 0.5 * (dart.line_left[1] + dart.line_right[1])).normalized();
  CHECK_FALSE(inside(fp.outline, mouth + d * out));
}
