// Ply boundaries (bound_mold) against closed forms: circles and a hole on the plate, a circle
// of the development across the flange, fillet and wall, a cap on the sphere; and every error.
#include <plyfit/kernel/boundary.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include <catch2/catch.hpp>

#include "support/boundary_curves.hpp"
#include "support/builtin_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

using namespace plyfit;
using plyfit::support::builtin_surface;

namespace {
constexpr double kPiT = 3.14159265358979323846;
constexpr double kDeg = kPiT / 180.0;

// The circle of radius r about c in the plane z = c.z, n points, as a closed curve.
BoundaryCurve circle(const Vec3& c, double r, int n = 720) {
  BoundaryCurve b;
  b.name = "circle";
  b.closed = true;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPiT * i / n;
    b.points.push_back(c + Vec3(r * std::cos(t), r * std::sin(t), 0));
  }
  return b;
}

// The area of the regular n-gon inscribed in a circle of radius r: what the boundary's points
// enclose (the curve between them is straight).
double ngon_area(double r, int n) {
  return 0.5 * n * r * r * std::sin(2 * kPiT / n);
}

PlySpec cloth(double d) {
  PlySpec s;
  s.d_weft = s.d_warp = d;
  return s;
}

// Drapes `bounded` from the seed at the ply angle and returns its flat pattern.
FlatPattern drape_flat(const BoundedMold& bounded, const Vec3& seed, double deg, double d,
                       DrapeResult* out = nullptr) {
  PlyDefinition def;
  def.seed = seed;
  def.angle = deg * kDeg;
  auto pb = ply_problem(bounded.surface, def, cloth(d));
  REQUIRE(pb);
  auto r = drape(bounded.surface, *pb, DrapeOptions{});
  REQUIRE(r);
  if (out) *out = *r;
  return flat_pattern(bounded.surface, *r);
}
}  // namespace

TEST_CASE("bound mold: a circle of radius 20 on the plate is the outline at every ply angle") {
  const MoldSurface plate = builtin_surface("plate");  // 100 x 60 in z = 0
  PlyBoundary b;
  b.curves = {circle(Vec3(50, 30, 0), 20.0)};
  auto bm = bound_mold(plate, b, Vec3(50, 30, 0));
  REQUIRE(bm);
  const double exact = 400.0 * kPiT;
  CHECK(bm->area == Approx(exact).epsilon(1e-3));
  // The face's area quadrature converges to first order at trims, within its evaluation cap.
  CHECK(bm->area == Approx(ngon_area(20.0, 720)).epsilon(1e-5));
  REQUIRE(bm->loops.size() == 1);
  CHECK(bm->loops[0].length == Approx(40.0 * kPiT).epsilon(1e-4));
  for (double deg : {0.0, 45.0, 90.0, -45.0}) {
    CAPTURE(deg);
    const FlatPattern flat = drape_flat(*bm, Vec3(50, 30, 0), deg, 1.0);
    CHECK(flat.area == Approx(exact).epsilon(1e-3));
    // The outline is the circle: every vertex 20 from the seed (the ply's origin).
    double worst = 0.0;
    for (const auto& loop : flat.outline)
      for (const Vec2& p : loop.points) worst = std::max(worst, std::abs(p.norm() - 20.0));
    CHECK(worst < 0.01);
  }
}

TEST_CASE("bound mold: an inner loop is a cut-out") {
  const MoldSurface plate = builtin_surface("plate");
  PlyBoundary b;
  BoundaryCurve rect;
  rect.name = "rectangle";
  rect.closed = true;
  rect.points = {Vec3(20, 10, 0), Vec3(80, 10, 0), Vec3(80, 50, 0), Vec3(20, 50, 0)};
  b.curves = {rect, circle(Vec3(35, 30, 0), 8.0)};
  auto bm = bound_mold(plate, b, Vec3(60, 30, 0));
  REQUIRE(bm);
  const double exact = 60.0 * 40.0 - ngon_area(8.0, 720);
  CHECK(bm->area == Approx(exact).epsilon(1e-4));
  const FlatPattern flat = drape_flat(*bm, Vec3(60, 30, 0), 30.0, 1.0);
  CHECK(flat.area == Approx(exact).epsilon(1e-3));
  // The seed in the hole is outside.
  auto in_hole = bound_mold(plate, b, Vec3(35, 30, 0));
  REQUIRE_FALSE(in_hole);
  CHECK(in_hole.error().code == ErrorCode::kBoundarySeedOutside);
}

TEST_CASE("bound mold: open curves chain into a loop; the offset grows and shrinks it") {
  const MoldSurface plate = builtin_surface("plate");
  const BoundaryCurve full = circle(Vec3(50, 30, 0), 20.0);
  BoundaryCurve a, c;
  a.name = "upper";
  c.name = "lower";
  a.points.assign(full.points.begin(), full.points.begin() + 361);
  c.points.assign(full.points.begin() + 360, full.points.end());
  c.points.push_back(full.points.front());
  std::reverse(c.points.begin(), c.points.end());  // chained reversed
  PlyBoundary b;
  b.curves = {a, c};
  auto bm = bound_mold(plate, b, Vec3(50, 30, 0));
  REQUIRE(bm);
  CHECK(bm->area == Approx(ngon_area(20.0, 720)).epsilon(1e-5));
  REQUIRE(bm->loops.size() == 1);
  CHECK(bm->loops[0].curves.size() == 2);
  for (double offset : {3.0, -3.0}) {
    CAPTURE(offset);
    b.offset = offset;
    auto grown = bound_mold(plate, b, Vec3(50, 30, 0));
    REQUIRE(grown);
    CHECK(grown->area == Approx(kPiT * (20 + offset) * (20 + offset)).epsilon(1e-3));
  }
}

TEST_CASE("bound mold: a circle of the development across flange, fillet and wall") {
  // Flange z = 0 for x in [-40, 0], fillet of radius 10 about x = 0, z = -10, wall x = 10;
  // 0 <= y <= 60. Arc length s from the fillet's top: the development is the (s, y) plane.
  auto data = builtin_shell("flange-fillet-wall", {});
  REQUIRE(data);
  auto shell = MoldSurface::from_shell(*data);
  REQUIRE(shell);
  const double quarter = 0.5 * kPiT * 10.0;  // the fillet's arc
  const auto on_mold = plyfit::support::flange_fillet_wall_at;
  // Radius 25 about the fillet's middle: s from -17 to 33, through all three faces.
  const double s0 = 0.5 * quarter, y0 = 30.0, R = 25.0;
  const BoundaryCurve c = plyfit::support::circle_curve(on_mold, s0, y0, R, 1440);
  PlyBoundary b;
  b.curves = {c};
  const Vec3 seed = on_mold(s0, y0);
  auto bm = bound_mold(*shell, b, seed);
  REQUIRE(bm);
  CHECK(bm->faces.size() == 3);
  // Developable: the region's area on the mold is the development's circle's.
  const double exact = kPiT * R * R;
  CHECK(bm->area == Approx(exact).epsilon(1e-3));
  DrapeResult res;
  const FlatPattern flat = drape_flat(*bm, seed, 0.0, 1.0, &res);
  CHECK(flat.area == Approx(exact).epsilon(1e-3));
  double worst = 0.0;
  for (const auto& loop : flat.outline)
    for (const Vec2& p : loop.points) worst = std::max(worst, std::abs(p.norm() - R));
  CHECK(worst < 0.05);
}

TEST_CASE("bound mold: a cap on the sphere has the cap's area") {
  const double R = 20.0, a = 20.0 * kDeg;
  const MoldSurface octant = builtin_surface("sphere-octant", {{"R", R}});
  // The cap of angular radius a about the octant's middle direction.
  const Vec3 axis = Vec3(1, 1, 1).normalized();
  const Vec3 e1 = Vec3(1, -1, 0).normalized(), e2 = axis.cross(e1);
  BoundaryCurve c;
  c.name = "cap";
  c.closed = true;
  const int n = 1440;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPiT * i / n;
    c.points.push_back(R *
                       (std::cos(a) * axis + std::sin(a) * (std::cos(t) * e1 + std::sin(t) * e2)));
  }
  PlyBoundary b;
  b.curves = {c};
  auto bm = bound_mold(octant, b, R * axis);
  REQUIRE(bm);
  const double cap = 2 * kPiT * R * R * (1 - std::cos(a));
  CHECK(bm->area == Approx(cap).epsilon(5e-3));
  DrapeResult res;
  const FlatPattern flat = drape_flat(*bm, R * axis, 0.0, 0.25, &res);
  CHECK_FALSE(flat.outline.empty());
  // Every node the drape laid lies in the cap.
  double widest = 0.0;
  for (const auto& node : res.nodes)
    if (node.mapped())
      widest =
          std::max(widest, std::acos(std::clamp(node.point.normalized().dot(axis), -1.0, 1.0)));
  CHECK(widest <= a + 1e-6);
  CHECK(widest >= a - 0.25 / R);
}

// The cap of angular radius a about the unit direction `axis` of the sphere of radius R.
BoundaryCurve cap_curve(double R, double a, const Vec3& axis, int n = 1440) {
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  BoundaryCurve c;
  c.name = "cap";
  c.closed = true;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPiT * i / n;
    c.points.push_back(R *
                       (std::cos(a) * axis + std::sin(a) * (std::cos(t) * e1 + std::sin(t) * e2)));
  }
  return c;
}

TEST_CASE("bound mold: caps across the sphere's eight faces, about a corner and about a pole") {
  // Four faces meet at the corner (R, 0, 0) on the equator and at the pole (0, 0, R): a cap
  // about either crosses four faces, runs along their shared edges to the corner or the pole,
  // and the region is whole on each (no corner or pole cut off, every shared edge kept).
  const double R = 20.0, a = 30.0 * kDeg;
  auto data = builtin_shell("sphere-8", {{"R", R}});
  REQUIRE(data);
  auto shell = MoldSurface::from_shell(*data);
  REQUIRE(shell);
  const double cap = 2 * kPiT * R * R * (1 - std::cos(a));
  // The pole is a collapsed edge of all four faces: the seed is set just beside it.
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 0, 1)}) {
    CAPTURE(axis.transpose());
    PlyBoundary b;
    b.curves = {cap_curve(R, a, axis)};
    const Vec3 seed = R * (axis + Vec3(0.01, 0.02, 0)).normalized();
    auto bm = bound_mold(*shell, b, seed);
    REQUIRE(bm);
    CHECK(bm->faces.size() == 4);
    CHECK(bm->area == Approx(cap).epsilon(1e-3));
    DrapeResult res;
    const FlatPattern flat = drape_flat(*bm, seed, 0.0, 0.5, &res);
    CHECK_FALSE(res.partial);
    // Sheared cells cover less of the mold than of the ply (d^2 cos(shear)): the flat area
    // lies between the cap's and the cap's over the cosine of the largest shear.
    CHECK(flat.area >= cap * (1 - 1e-3));
    CHECK(flat.area <= cap / std::cos(res.metrics.shear_max));
  }
}

// The rectangle [x0, x1] x [y0, y1] in the plane z = 0 as one closed curve, counter-clockwise
// (or clockwise) seen from +Z.
BoundaryCurve rectangle(double x0, double y0, double x1, double y1, bool ccw) {
  BoundaryCurve b;
  b.name = "rectangle";
  b.closed = true;
  b.points = {Vec3(x0, y0, 0), Vec3(x1, y0, 0), Vec3(x1, y1, 0), Vec3(x0, y1, 0)};
  if (!ccw) std::reverse(b.points.begin(), b.points.end());
  return b;
}

TEST_CASE("bound mold: an offset rectangle keeps square corners, either way round") {
  // Shrinking a rectangle by 5 gives the rectangle 10 narrower each way (each point moved
  // across the loop overshoots at the convex corners: the swallowtails are cut out). On the
  // plate's own border, one side of the loop is off the mold: the side that is on it is
  // the region, whichever way the loop runs. Growing the border clips the loop to the mold.
  const MoldSurface plate = builtin_surface("plate");
  // From (50, 30) at d = 1 the net's nodes lie on the rectangles' sides and corners: a
  // corner of the boundary on a node is kept (the walk along the boundary passes through the
  // cell's own corner); from (50.3, 30.4) they lie off them.
  for (const Vec3& seed : {Vec3(50, 30, 0), Vec3(50.3, 30.4, 0)})
    for (bool ccw : {true, false}) {
      CAPTURE(seed.transpose(), ccw);
      struct Case {
        BoundaryCurve curve;
        double offset, area;
      };
      for (const Case& c : {Case{rectangle(20, 10, 80, 50, ccw), 0.0, 60.0 * 40.0},
                            Case{rectangle(20, 10, 80, 50, ccw), -5.0, 50.0 * 30.0},
                            Case{rectangle(0, 0, 100, 60, ccw), -5.0, 90.0 * 50.0},
                            Case{rectangle(0, 0, 100, 60, ccw), 5.0, 100.0 * 60.0}}) {
        CAPTURE(c.offset, c.area);
        PlyBoundary b;
        b.curves = {c.curve};
        b.offset = c.offset;
        auto bm = bound_mold(plate, b, seed);
        REQUIRE(bm);
        CHECK(bm->area == Approx(c.area).epsilon(1e-9));
        CHECK(drape_flat(*bm, seed, 0.0, 1.0).area == Approx(c.area).epsilon(1e-9));
      }
    }
}

TEST_CASE("bound mold: bad boundaries are errors naming the curve") {
  const MoldSurface plate = builtin_surface("plate");
  const Vec3 seed(50, 30, 0);
  // The error of bounding the plate by `curves` from `at` (it must be one).
  const auto bound_error = [&](std::vector<BoundaryCurve> curves, const Vec3& at) {
    PlyBoundary b;
    b.curves = std::move(curves);
    auto r = bound_mold(plate, b, at);
    REQUIRE_FALSE(r);
    return r.error();
  };
  SECTION("no curve") {
    CHECK(bound_error({}, seed).code == ErrorCode::kBoundaryEmpty);
  }
  SECTION("too few points") {
    BoundaryCurve c;
    c.closed = true;
    c.points = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
    CHECK(bound_error({c}, seed).code == ErrorCode::kBoundaryCurvePoints);
  }
  SECTION("a gap larger than the tolerance") {
    const BoundaryCurve full = circle(Vec3(50, 30, 0), 20.0);
    BoundaryCurve half;
    half.name = "half";
    half.points.assign(full.points.begin(), full.points.begin() + 361);
    const Error e = bound_error({half}, seed);
    CHECK(e.code == ErrorCode::kBoundaryGap);
    CHECK(std::get<double>(e.values.at(2)) == Approx(40.0));
  }
  SECTION("a curve off the mold") {
    const Error e = bound_error({circle(Vec3(50, 30, 2), 20.0)}, seed);
    CHECK(e.code == ErrorCode::kBoundaryOffMold);
    CHECK(std::get<double>(e.values.at(1)) == Approx(2.0));
  }
  SECTION("a seed outside") {
    CHECK(bound_error({circle(Vec3(50, 30, 0), 20.0)}, Vec3(5, 5, 0)).code ==
          ErrorCode::kBoundarySeedOutside);
  }
}
