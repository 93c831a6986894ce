#include <plyfit/kernel/nurbs.hpp>
#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace plyfit;
using plyfit::test::kRoundoffRel;
using plyfit::test::Rng;

TEST_CASE("geometry: curve validation names the problem by its code") {
  NurbsCurveData3 d;
  d.degree = 2;
  d.poles = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 0, 0)};
  d.knots = {0, 0, 0, 1, 1, 1};
  REQUIRE(NurbsCurve3::create(d).ok());
  auto code_of = [](const NurbsCurveData3& bad) {
    auto r = NurbsCurve3::create(bad);
    REQUIRE_FALSE(r.ok());
    return r.error();
  };
  auto bad = d;
  bad.knots = {0, 0, 1, 1, 1};
  const Error e = code_of(bad);
  CHECK(e.code == ErrorCode::kKnotCount);
  CHECK(e.values ==
        std::vector<MessageValue>{std::string("curve"), std::int64_t{5}, std::int64_t{6}});
  bad = d;
  bad.weights = {1, 0, 1};
  CHECK(code_of(bad).code == ErrorCode::kCurveWeightNotPositive);
  bad = d;
  bad.weights = {1, 1};
  CHECK(code_of(bad).code == ErrorCode::kCurveWeightCount);
  bad = d;
  bad.poles[1].x() = NAN;
  CHECK(code_of(bad).code == ErrorCode::kCurvePoleNotFinite);
  bad = d;
  bad.knots = {0, 0, 0, 0, 1, 1};
  CHECK(code_of(bad).code == ErrorCode::kKnotMultiplicity);
}

TEST_CASE("geometry: interpolation refuses too few points and coinciding ones") {
  CHECK(polyline_curve({Vec3::Zero()}).error().code == ErrorCode::kPolylineTooFewPoints);
  CHECK(interpolate_cubic({Vec3::Zero()}).error().code == ErrorCode::kInterpolationTooFewPoints);
  const auto r = interpolate_cubic({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)});
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kInterpolationPointsCoincide);
  CHECK(r.error().values == std::vector<MessageValue>{std::int64_t{1}, std::int64_t{2}});
}

TEST_CASE("kernel: circle arcs are exact, with exact derivatives") {
  const double R = 3.5;
  for (auto [a0, a1] : {std::pair{0.0, 1.0}, std::pair{2.0, -1.5}, std::pair{0.0, 2 * kPi}}) {
    auto c = NurbsCurve2::create(circle_arc(R, a0, a1));
    REQUIRE(c.ok());
    CHECK((c->point(c->t0()) - Vec2(R * std::cos(a0), R * std::sin(a0))).norm() < kRoundoffRel * R);
    CHECK((c->point(c->t1()) - Vec2(R * std::cos(a1), R * std::sin(a1))).norm() < kRoundoffRel * R);
    for (int k = 0; k <= 200; ++k) {
      const double t = c->t0() + (c->t1() - c->t0()) * k / 200.0;
      const auto e = c->eval2(t);
      CHECK(std::abs(e.p.norm() - R) < kRoundoffRel * R);
      // |p|^2 = R^2  =>  p.p' = 0 and p'.p' + p.p'' = 0.
      CHECK(std::abs(e.p.dot(e.d1)) < kRoundoffRel * R * e.d1.norm());
      CHECK(std::abs(e.d1.dot(e.d1) + e.p.dot(e.d2)) <
            kRoundoffRel * (e.d1.squaredNorm() + R * e.d2.norm()));
    }
    // Tessellation stays within its chord tolerance (sagitta of each chord).
    const double tol = 1e-4 * R;
    const auto pts = c->tessellate(tol);
    REQUIRE(pts.size() >= 3);
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
      const double chord = (pts[i + 1] - pts[i]).norm();
      const double sagitta = R - std::sqrt(std::max(0.0, R * R - chord * chord / 4));
      CHECK(sagitta <= tol * 1.0001);
    }
  }
}

TEST_CASE("kernel: cubic interpolation passes through its points") {
  Rng rng(11);
  for (int n : {2, 3, 4, 5, 17, 300}) {
    std::vector<Vec3> pts;
    Vec3 p(0, 0, 0);
    for (int i = 0; i < n; ++i) {
      p += Vec3(rng.uniform(0.5, 1.5), rng.uniform(-1, 1), rng.uniform(-1, 1));
      pts.push_back(p);
    }
    auto c = interpolate_cubic(pts);
    REQUIRE(c.ok());
    CHECK(c->data().degree == std::min(3, n - 1));
    // Parameters are chord lengths; check every point by its own parameter.
    double total = 0.0;
    std::vector<double> t(n, 0.0);
    for (int i = 1; i < n; ++i) t[i] = (total += (pts[i] - pts[i - 1]).norm());
    for (int i = 0; i < n; ++i) {
      CHECK((c->point(t[i] / total) - pts[i]).norm() < 1e-10 * total);
    }
  }
  // Collinear, evenly spaced points: the interpolant is the straight line.
  std::vector<Vec3> line;
  for (int i = 0; i < 10; ++i) line.emplace_back(i, 2.0 * i, -i);
  auto c = interpolate_cubic(line);
  REQUIRE(c.ok());
  for (int k = 0; k <= 100; ++k) {
    const Vec3 q = c->point(k / 100.0);
    CHECK((q - Vec3(9, 18, -9) * (k / 100.0)).norm() < 1e-12 * 20);
  }
  REQUIRE_FALSE(interpolate_cubic({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0)}).ok());
  REQUIRE_FALSE(interpolate_cubic({Vec3(0, 0, 0)}).ok());
}
