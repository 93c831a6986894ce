#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <functional>

using namespace plyfit;
using plyfit::test::kRoundoffRel;
using plyfit::test::Rng;

namespace {

// Samples the surface and checks an implicit equation f(p) = 0 (scaled by `scale`) and that
// the normal agrees with the expected outward direction `out(p)`.
void check_surface(const NurbsSurfaceData& data, const std::function<double(const Vec3&)>& f,
                   const std::function<Vec3(const Vec3&)>& out, double scale) {
  auto s = NurbsSurface::create(data);
  REQUIRE(s.ok());
  Rng rng(5);
  const auto& d = s->domain();
  for (int k = 0; k < 500; ++k) {
    const double u = rng.uniform(d.u0, d.u1), v = rng.uniform(d.v0, d.v1);
    const Vec3 p = s->point(u, v);
    CHECK(std::abs(f(p)) < kRoundoffRel * scale);
    const SurfaceNormal n = s->normal(u, v);
    if (!n.degenerate) {
      CHECK(n.n.dot(out(p).normalized()) > 1.0 - 1e-9);
    }
  }
}

}  // namespace

TEST_CASE("geometry: analytic constructors: plane, exact and outward") {
  const Vec3 o(1, 2, 3), a(4, 0, 0), b(0, 5, 1);
  check_surface(
      plane_patch(o, a, b), [&](const Vec3& p) { return (p - o).dot(a.cross(b).normalized()); },
      [&](const Vec3&) { return a.cross(b); }, 10.0);
}

TEST_CASE("geometry: analytic constructors: cylinder, exact and outward") {
  const double R = 7.0;
  check_surface(
      cylinder_patch(R, 0.2, 4.0, -1.0, 5.0),
      [&](const Vec3& p) { return std::hypot(p.x(), p.y()) - R; },
      [&](const Vec3& p) { return Vec3(p.x(), p.y(), 0); }, R);
}

TEST_CASE("geometry: analytic constructors: cone, exact and outward") {
  // r(z) = r0 + (r1 - r0) (z - z0) / (z1 - z0); outward normal (1, -dr/dz) in (r, z).
  const double r0 = 10, r1 = 4, z0 = 0, z1 = 6;
  const double slope = (r1 - r0) / (z1 - z0);
  check_surface(
      cone_patch(r0, r1, z0, z1, 0.0, 2.0),
      [&](const Vec3& p) { return std::hypot(p.x(), p.y()) - (r0 + slope * (p.z() - z0)); },
      [&](const Vec3& p) {
        const double r = std::hypot(p.x(), p.y());
        return Vec3(p.x() / r, p.y() / r, -slope);
      },
      r0);
}

TEST_CASE("geometry: analytic constructors: sphere octant, exact and outward") {
  const double R = 20.0;
  auto d = sphere_octant(R);
  check_surface(
      d, [&](const Vec3& p) { return p.norm() - R; }, [](const Vec3& p) { return p; }, R);
  auto s = NurbsSurface::create(d);
  REQUIRE(s.ok());
  // The octant: pole (0, 0, R) at u0, and x, y, z >= 0 everywhere.
  CHECK((s->point(s->domain().u0, 0.3) - Vec3(0, 0, R)).norm() < kRoundoffRel * R);
  for (double u = 0; u <= 1.0; u += 0.05)
    for (double v = 0; v <= 1.0; v += 0.05) {
      const Vec3 p = s->point(u, v);
      CHECK(p.minCoeff() > -kRoundoffRel * R);
    }
}

TEST_CASE("geometry: analytic constructors: torus, exact and outward") {
  const double Rm = 10, rm = 3;
  check_surface(
      torus_patch(Rm, rm, -2.0, 2.5, 0.5, 3.0),
      [&](const Vec3& p) { return std::hypot(std::hypot(p.x(), p.y()) - Rm, p.z()) - rm; },
      [&](const Vec3& p) {
        const double r = std::hypot(p.x(), p.y());
        const Vec3 c(p.x() / r * Rm, p.y() / r * Rm, 0);
        return Vec3(p - c);
      },
      Rm);
}

TEST_CASE("geometry: analytic constructors: an elliptic profile revolved, exact and outward") {
  // The profile of the paper's one-third surface: the quarter ellipse from the top (0, b) down
  // to (a, 0), outward normal.
  const double a = 20.0, b = 10.33;
  auto prof = ellipse_arc(a, b, kPi / 2, 0.0);
  check_surface(
      revolve(prof, 0.0, 2 * kPi / 3),
      [&](const Vec3& p) {
        const double r = std::hypot(p.x(), p.y());
        return (r * r / (a * a) + p.z() * p.z() / (b * b) - 1.0) * a;
      },
      [&](const Vec3& p) {
        const double r = std::hypot(p.x(), p.y());
        // gradient of the implicit function in (r, z), rotated back
        return Vec3(p.x() / r * (r / (a * a)), p.y() / r * (r / (a * a)), p.z() / (b * b));
      },
      a);
}

TEST_CASE("geometry: analytic constructors: extrusion, exact and outward") {
  NurbsCurveData3 prof;
  prof.degree = 2;
  prof.knots = {0, 0, 0, 1, 1, 1};
  prof.poles = {Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(2, 0, 0)};
  const Vec3 dir(0, 0, 3);
  auto s = NurbsSurface::create(extrude(prof, dir));
  REQUIRE(s.ok());
  auto c = NurbsCurve3::create(prof);
  REQUIRE(c.ok());
  for (double u = 0; u <= 1; u += 0.1)
    for (double v = 0; v <= 1; v += 0.25)
      CHECK((s->point(u, v) - (c->point(u) + v * dir)).norm() < kRoundoffRel * 4);
}

TEST_CASE("geometry: analytic constructors: saddle, exact and outward") {
  const double rho = 15.0;
  check_surface(
      saddle_patch(10.0, rho),
      [&](const Vec3& p) { return p.z() - (p.x() * p.x() - p.y() * p.y()) / (2 * rho); },
      [&](const Vec3& p) { return Vec3(-p.x() / rho, p.y() / rho, 1.0); }, 10.0);
}

TEST_CASE("geometry: analytic constructors: wave, exact and outward") {
  auto s = NurbsSurface::create(wave_surface(100.0, 5.0, 60.0, 12));
  REQUIRE(s.ok());
  CHECK(s->data().degree_u == 3);
  CHECK_FALSE(s->rational());
  for (double u = 0; u <= 1; u += 0.1)
    for (double v = 0; v <= 1; v += 0.1) {
      CHECK(std::abs(s->point(u, v).z()) <= 5.0);
      CHECK(s->normal(u, v).n.z() > 0.0);
    }
}
