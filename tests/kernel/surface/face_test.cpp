#include "surface/face.hpp"
#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

using namespace plyfit;
using plyfit::test::Rng;

namespace {

std::vector<Vec2> circle_poly(const Vec2& c, double r, int n, bool cw) {
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n * (cw ? -1 : 1);
    p.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
  }
  return p;
}
}  // namespace

TEST_CASE("surface: a face's loops and size are validated, errors by their codes") {
  FaceData good;
  good.surface = plane_patch(Vec3::Zero(), Vec3(10, 0, 0), Vec3(0, 10, 0));
  good.loops.push_back({{Vec2(0.1, 0.1), Vec2(0.9, 0.1), Vec2(0.9, 0.9), Vec2(0.1, 0.9)}});
  good.loops.push_back({{Vec2(0.4, 0.4), Vec2(0.4, 0.6), Vec2(0.6, 0.6), Vec2(0.6, 0.4)}});
  REQUIRE(Face::create(good).ok());
  using V = std::vector<MessageValue>;
  auto refused = [](const FaceData& fd) {
    auto f = Face::create(fd);
    REQUIRE_FALSE(f.ok());
    return f.error();
  };
  FaceData bad = good;
  bad.loops[1].points.resize(2);
  Error e = refused(bad);
  CHECK(e.code == ErrorCode::kTrimLoopTooFewPoints);
  CHECK(e.values == V{std::int64_t{1}});
  bad = good;
  bad.loops[0].points[2].x() = NAN;
  e = refused(bad);
  CHECK(e.code == ErrorCode::kTrimLoopNotFinite);
  CHECK(e.values == V{std::int64_t{0}});
  bad = good;
  bad.loops[1].edges = {-1, -1};
  e = refused(bad);
  CHECK(e.code == ErrorCode::kTrimLoopEdgeTags);
  CHECK(e.values == V{std::int64_t{1}, std::int64_t{2}, std::int64_t{4}});
  // A repeated closing point is dropped with its tag: 5 points and tags make 4 segments.
  bad = good;
  bad.loops[0].points.push_back(bad.loops[0].points.front());
  bad.loops[0].edges = {-1, -1, -1, -1, -1};
  CHECK(Face::create(bad).ok());
  // A loop around no point of the domain leaves no point on the face.
  bad = good;
  bad.loops = {{{Vec2(2, 2), Vec2(3, 2), Vec2(3, 3)}}};
  CHECK(refused(bad).code == ErrorCode::kFaceEmpty);
  bad = good;
  bad.loops.clear();
  bad.surface = plane_patch(Vec3(1, 2, 3), Vec3::Zero(), Vec3::Zero());
  CHECK(refused(bad).code == ErrorCode::kFaceZeroSize);
  bad = good;
  bad.surface.knots_v = {0, 0.5, 0.5, 1};  // the surface's own error: an empty domain in v
  CHECK(refused(bad).code == ErrorCode::kEmptyDomain);
}

TEST_CASE("kernel: contains() is even-odd over the trim loops") {
  FaceData fd;
  fd.surface = plane_patch(Vec3::Zero(), Vec3(10, 0, 0), Vec3(0, 10, 0));
  // Outer loop (0.1..0.9)^2 and a square hole (0.4..0.6)^2, in uv of the unit domain.
  fd.loops.push_back({{Vec2(0.1, 0.1), Vec2(0.9, 0.1), Vec2(0.9, 0.9), Vec2(0.1, 0.9)}});
  fd.loops.push_back({{Vec2(0.4, 0.4), Vec2(0.4, 0.6), Vec2(0.6, 0.6), Vec2(0.6, 0.4)}});
  auto f = Face::create(fd);
  REQUIRE(f.ok());
  CHECK(f->trimmed());
  Rng rng(1);
  for (int k = 0; k < 5000; ++k) {
    const Vec2 uv(rng.uniform(-0.2, 1.2), rng.uniform(-0.2, 1.2));
    const bool in_outer = uv.x() > 0.1 && uv.x() < 0.9 && uv.y() > 0.1 && uv.y() < 0.9;
    const bool in_hole = uv.x() > 0.4 && uv.x() < 0.6 && uv.y() > 0.4 && uv.y() < 0.6;
    CHECK(f->contains(uv) == (in_outer && !in_hole));
  }
  // At the height of loop vertices the half-open rule counts each crossing once.
  for (double v : {0.4, 0.6}) {
    CHECK(f->contains(Vec2(0.2, v)));
    CHECK(f->contains(Vec2(0.8, v)));
    CHECK_FALSE(f->contains(Vec2(0.05, v)));
  }
  // Area of the trimmed region: 100 * (0.64 - 0.04).
  CHECK(f->area() == Approx(60.0).epsilon(2e-2));
}

TEST_CASE("kernel: a circular hole with many vertices") {
  FaceData fd;
  fd.surface = plane_patch(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0));
  fd.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}});
  fd.loops.push_back({circle_poly(Vec2(0.5, 0.5), 0.25, 4000, true)});
  auto f = Face::create(fd);
  REQUIRE(f.ok());
  Rng rng(2);
  for (int k = 0; k < 20000; ++k) {
    const Vec2 uv(rng.uniform(0.01, 0.99), rng.uniform(0.01, 0.99));
    const double r = (uv - Vec2(0.5, 0.5)).norm();
    if (std::abs(r - 0.25) < 1e-6) continue;  // the polygon is within 1e-7 of the circle
    CHECK(f->contains(uv) == (r > 0.25));
  }
}

TEST_CASE("kernel: closed seams wrap parameters and differences") {
  FaceData fd;
  fd.surface = cylinder_patch(5.0, 0.0, 2 * kPi, 0.0, 10.0);
  fd.closed_v = true;  // v runs around the axis
  auto f = Face::create(fd);
  REQUIRE(f.ok());
  const auto& d = f->domain();
  const double P = d.width_v();
  CHECK(f->contains(Vec2(0.5 * (d.u0 + d.u1), d.v1 + 0.1 * P)));
  CHECK(f->wrap(Vec2(0.3, d.v0 - 0.25 * P)).y() == Approx(d.v0 + 0.75 * P));
  CHECK(f->delta(Vec2(0.3, d.v1 - 0.01 * P), Vec2(0.3, d.v0 + 0.01 * P)).y() == Approx(0.02 * P));
  // Evaluation across the seam continues the surface.
  const Vec3 a = f->eval1(Vec2(0.5, d.v1 + 0.1 * P)).p;
  const Vec3 b = f->eval1(Vec2(0.5, d.v0 + 0.1 * P)).p;
  CHECK((a - b).norm() < 1e-12 * 5);
}

TEST_CASE("kernel: projection finds the nearest point of the face") {
  const double R = 20.0;
  FaceData fd;
  fd.surface = sphere_octant(R);
  auto f = Face::create(fd);
  REQUIRE(f.ok());
  // The octant's area is 4 pi R^2 / 8.
  CHECK(f->area() == Approx(kPi * R * R / 2).epsilon(1e-9));
  // Points off the sphere inside the octant's cone project radially.
  Rng rng(4);
  for (int k = 0; k < 50; ++k) {
    const Vec3 dir =
        Vec3(rng.uniform(0.05, 1), rng.uniform(0.05, 1), rng.uniform(0.05, 1)).normalized();
    const double r = rng.uniform(0.3 * R, 2 * R);
    const Projection pr = f->project(r * dir);
    REQUIRE(pr.ok);
    CHECK((pr.point - R * dir).norm() < 1e-9 * R);
    CHECK(pr.distance == Approx(std::abs(r - R)).margin(1e-9 * R));
  }
  // The paper's Table 1 (b) start point (R/2, 0, R/2) lies off the sphere: it moves to
  // (R, 0, R) / sqrt(2), on the octant's y = 0 edge.
  const Projection pb = f->project(Vec3(R / 2, 0, R / 2));
  REQUIRE(pb.ok);
  CHECK((pb.point - Vec3(R, 0, R) / std::sqrt(2.0)).norm() < 1e-9 * R);
  // The pole projects to itself.
  const Projection pp = f->project(Vec3(0, 0, R));
  CHECK(pp.distance < 1e-9 * R);
}

TEST_CASE("surface: boundary_area integrates the area element over (u, v) loops") {
  // The sphere octant of radius 20: its whole domain is an eighth of the sphere, 4 pi R^2 / 8;
  // a loop and a hole inside it (opposite orientations, as a polygon boolean gives them) leave
  // the difference of their areas.
  const double R = 20.0, pi = 3.14159265358979323846;
  const NurbsSurfaceData data = sphere_octant(R);
  auto s = NurbsSurface::create(data);
  REQUIRE(s);
  const auto& d = s->domain();
  const std::vector<Vec2> whole = {Vec2(d.u0, d.v0), Vec2(d.u1, d.v0), Vec2(d.u1, d.v1),
                                   Vec2(d.u0, d.v1)};
  CHECK(boundary_area(*s, {whole}) == Approx(0.5 * pi * R * R).epsilon(1e-10));
  // The plate: a 2 x 3 rectangle with a 1 x 1 hole, exact.
  NurbsSurfaceData plate;
  plate.degree_u = plate.degree_v = 1;
  plate.knots_u = plate.knots_v = {0, 0, 10, 10};
  plate.poles = {Vec3(0, 0, 0), Vec3(0, 10, 0), Vec3(10, 0, 0), Vec3(10, 10, 0)};
  plate.count_u = plate.count_v = 2;
  auto p = NurbsSurface::create(plate);
  REQUIRE(p);
  const std::vector<Vec2> outer = {Vec2(1, 1), Vec2(3, 1), Vec2(3, 4), Vec2(1, 4)};
  const std::vector<Vec2> hole = {Vec2(1.5, 2), Vec2(1.5, 3), Vec2(2.5, 3), Vec2(2.5, 2)};
  CHECK(boundary_area(*p, {outer, hole}) == Approx(5.0).epsilon(1e-12));
}

namespace {
// The part of polygon `poly` where coordinate `axis` is on the `below` side of `at`
// (Sutherland-Hodgman against one line).
std::vector<Vec2> clip_half(const std::vector<Vec2>& poly, int axis, double at, bool below) {
  std::vector<Vec2> out;
  const auto in = [&](const Vec2& p) { return below ? p[axis] <= at : p[axis] >= at; };
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2 &a = poly[i], &b = poly[(i + 1) % n];
    if (in(a)) out.push_back(a);
    if (in(a) != in(b)) out.push_back(a + (b - a) * ((at - a[axis]) / (b[axis] - a[axis])));
  }
  return out;
}

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i)
    a += p[i].x() * p[(i + 1) % n].y() - p[(i + 1) % n].x() * p[i].y();
  return 0.5 * std::abs(a);
}
}  // namespace

TEST_CASE("surface: boundary_area is exact across knots where the area element jumps") {
  // A plate of degree 1 whose parametrisation speeds up at the interior knots (C0 there):
  // x = u on [0, 1] then 1 + 4 (u - 1); y = v on [0, 1] then 1 + 3 (v - 1). The area of a
  // (u, v) polygon is the sum over the four knot cells of its part's area times x' y' there:
  // the loop's segments cross the knots, where the integrand of Green's theorem has a kink.
  NurbsSurfaceData plate;
  plate.degree_u = plate.degree_v = 1;
  plate.knots_u = plate.knots_v = {0, 0, 1, 2, 2};
  const double xs[3] = {0, 1, 5}, ys[3] = {0, 1, 4};
  for (double x : xs)
    for (double y : ys) plate.poles.push_back(Vec3(x, y, 0));
  plate.count_u = plate.count_v = 3;
  auto s = NurbsSurface::create(plate);
  REQUIRE(s);
  const std::vector<Vec2> loop = circle_poly(Vec2(1.1, 0.9), 0.5, 40, false);
  double exact = 0.0;
  for (bool left : {true, false})
    for (bool low : {true, false})
      exact += (left ? 1.0 : 4.0) * (low ? 1.0 : 3.0) *
               polygon_area(clip_half(clip_half(loop, 0, 1.0, left), 1, 1.0, low));
  CHECK(boundary_area(*s, {loop}) == Approx(exact).epsilon(1e-12));
}

TEST_CASE("surface: Face::create takes the producer's surface only when made from its data") {
  FaceData data;
  data.surface = plane_patch(Vec3::Zero(), Vec3(10, 0, 0), Vec3(0, 10, 0));
  const Tolerances tol;
  auto built = NurbsSurface::create(data.surface, tol);
  REQUIRE(built.ok());
  const auto shared = std::make_shared<const NurbsSurface>(std::move(built).value());

  FaceData same = data;
  same.built = shared;
  auto a = Face::create(same, tol);
  REQUIRE(a.ok());
  CHECK(&a->surface() == shared.get());
  CHECK(a->data().built.get() == shared.get());  // a face's data hands its surface on

  FaceData changed = data;
  changed.built = shared;
  changed.surface.poles[0].z() = 1.0;  // data edited after the surface was built
  auto b = Face::create(changed, tol);
  REQUIRE(b.ok());
  CHECK(&b->surface() != shared.get());
  CHECK(b->surface().data().poles[0].z() == 1.0);

  Tolerances other = tol;
  other.degenerate_rel *= 10.0;
  auto c = Face::create(same, other);
  REQUIRE(c.ok());
  CHECK(&c->surface() != shared.get());
}
