#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/nurbs.hpp>
#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace plyfit;
using plyfit::test::kRoundoffRel;
using plyfit::test::Rng;

namespace {

// Random knot vector for `count` poles of `degree`: random spacing, repeated interior knots,
// clamped or not.
std::vector<double> random_knots(Rng& rng, int count, int degree, bool clamped) {
  std::vector<double> k;
  const int total = count + degree + 1;
  double x = rng.uniform(-2.0, 2.0);
  if (clamped) {
    k.assign(degree + 1, x);
    while (static_cast<int>(k.size()) < count) {
      x += rng.uniform(0.05, 1.5);
      const int mult = std::min(rng.integer(1, degree), count - static_cast<int>(k.size()));
      k.insert(k.end(), mult, x);
    }
    x += rng.uniform(0.05, 1.5);
    k.insert(k.end(), degree + 1, x);
  } else {
    while (static_cast<int>(k.size()) < total) {
      x += rng.uniform(0.05, 1.5);
      k.push_back(x);
    }
  }
  return k;
}

// Greville abscissae: with poles there, a B-spline reproduces linear functions exactly.
std::vector<double> greville(const std::vector<double>& k, int count, int degree) {
  std::vector<double> g(count);
  for (int i = 0; i < count; ++i) {
    double s = 0.0;
    for (int j = 1; j <= degree; ++j) s += k[i + j];
    g[i] = s / degree;
  }
  return g;
}

}  // namespace

// The error of NurbsSurface::create(bad): its code and values.
Error surface_error(const NurbsSurfaceData& bad) {
  auto r = NurbsSurface::create(bad);
  REQUIRE_FALSE(r.ok());
  return r.error();
}

TEST_CASE("geometry: validation rejects malformed surfaces, naming the problem by its code") {
  NurbsSurfaceData good = plane_patch(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
  REQUIRE(NurbsSurface::create(good).ok());
  using V = std::vector<MessageValue>;

  auto bad = good;
  bad.knots_u.pop_back();
  Error e = surface_error(bad);
  CHECK(e.code == ErrorCode::kKnotCount);
  CHECK(e.values == V{std::string("u"), std::int64_t{3}, std::int64_t{4}});

  bad = good;
  bad.knots_v = {0, 1, 0.5, 1};
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kKnotsDecrease);
  CHECK(e.values == V{std::string("v"), std::int64_t{2}});

  bad = good;
  bad.knots_u = {0, 0, 0, 1};  // multiplicity 3 > degree + 1 = 2
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kKnotMultiplicity);
  CHECK(e.values == V{std::string("u"), std::int64_t{2}});

  bad = good;
  bad.knots_u[1] = INFINITY;
  CHECK(surface_error(bad).code == ErrorCode::kKnotNotFinite);

  bad = good;
  bad.poles[2].y() = std::numeric_limits<double>::quiet_NaN();
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kPoleNotFinite);
  CHECK(e.values == V{std::int64_t{2}});

  bad = good;
  bad.weights = {1, 1, -0.5, 1};
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kWeightNotPositive);
  CHECK(e.values == V{std::int64_t{2}});

  bad = good;
  bad.weights = {1, 1, 1};
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kWeightCount);
  CHECK(e.values == V{std::int64_t{3}, std::int64_t{4}});

  bad = good;
  bad.poles.pop_back();
  CHECK(surface_error(bad).code == ErrorCode::kPoleCount);

  bad = good;
  bad.degree_u = 26;
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kDegreeRange);
  CHECK(e.values == V{std::string("u"), std::int64_t{26}, std::int64_t{25}});

  bad = good;
  bad.count_v = 1;
  bad.poles.resize(2);
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kTooFewPoles);
  CHECK(e.values == V{std::string("v"), std::int64_t{2}, std::int64_t{1}});

  bad = good;
  bad.knots_u = {0, 1, 1, 2};  // domain [1, 1] is empty
  e = surface_error(bad);
  CHECK(e.code == ErrorCode::kEmptyDomain);
  CHECK(e.values == V{std::string("u")});
}

TEST_CASE("geometry: the errors' texts name the direction, the index and the counts") {
  auto text = [](ErrorCode c, std::vector<MessageValue> v) {
    return exporters::describe(Error{c, {}, std::move(v)});
  };
  CHECK(text(ErrorCode::kKnotCount, {std::string("u"), std::int64_t{3}, std::int64_t{4}}) ==
        "knot count in u is 3, must be poles + degree + 1 = 4");
  CHECK(text(ErrorCode::kDegreeRange, {std::string("v"), std::int64_t{26}, std::int64_t{25}}) ==
        "degree in v is 26, must be 1..25");
  CHECK(text(ErrorCode::kTooFewPoles, {std::string("curve"), std::int64_t{3}, std::int64_t{2}}) ==
        "need at least degree + 1 = 3 poles in curve, got 2");
  CHECK(text(ErrorCode::kPoleCount, {std::int64_t{3}, std::int64_t{2}, std::int64_t{2}}) ==
        "pole count is 3, must be 2 x 2");
  CHECK(text(ErrorCode::kWeightNotPositive, {std::int64_t{2}}) ==
        "weight 2 is not a positive finite number");
  CHECK(text(ErrorCode::kInterpolationPointsCoincide, {std::int64_t{1}, std::int64_t{2}}) ==
        "interpolation points 1 and 2 coincide");
}

TEST_CASE("kernel: linear precision for any degree and knot vector, clamped or not") {
  // Poles at the Greville abscissae (x_i, y_j, x_i * y_j) reproduce S(u, v) = (u, v, u v)
  // exactly, with Su = (1, 0, v), Sv = (0, 1, u), Suu = Svv = 0, Suv = (0, 0, 1). This
  // checks the basis functions and their derivatives for every degree, knot multiplicity and
  // unclamped vectors, and the extension past the domain (the same polynomial).
  Rng rng(7);
  for (int trial = 0; trial < 60; ++trial) {
    const int p = trial < 50 ? rng.integer(1, 7) : rng.integer(12, 25);
    const int q = trial < 50 ? rng.integer(1, 7) : rng.integer(1, 4);
    const int nu = p + 1 + rng.integer(0, 6), nv = q + 1 + rng.integer(0, 6);
    NurbsSurfaceData d;
    d.degree_u = p;
    d.degree_v = q;
    d.count_u = nu;
    d.count_v = nv;
    d.knots_u = random_knots(rng, nu, p, trial % 3 != 0);
    d.knots_v = random_knots(rng, nv, q, trial % 4 != 0);
    const auto gu = greville(d.knots_u, nu, p), gv = greville(d.knots_v, nv, q);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) d.poles.emplace_back(gu[i], gv[j], gu[i] * gv[j]);
    auto s = NurbsSurface::create(d);
    REQUIRE(s.ok());
    const auto& dom = s->domain();
    const double scale =
        1.0 + std::max({std::abs(dom.u0), std::abs(dom.u1), std::abs(dom.v0), std::abs(dom.v1)});
    const double tol = 1e-11 * scale * scale;  // degree-25 bases lose a few digits
    for (int k = 0; k < 50; ++k) {
      // Up to 10% beyond the domain for degrees <= 7. Extrapolating a degree-25 polynomial
      // that far amplifies rounding by (distance / span)^degree, so high degrees are checked
      // inside the domain only (the drape extends surfaces by a fraction of one step).
      const double ext = (p <= 7 && q <= 7) ? 0.1 : 0.0;
      const double u = rng.uniform(dom.u0 - ext * dom.width_u(), dom.u1 + ext * dom.width_u());
      const double v = rng.uniform(dom.v0 - ext * dom.width_v(), dom.v1 + ext * dom.width_v());
      const SurfaceEval2 e = s->eval2(u, v);
      INFO("trial " << trial << " degrees " << p << "x" << q << " uv " << u << "," << v
                    << " inside " << dom.contains(u, v));
      REQUIRE(e.ok);
      CHECK((e.p - Vec3(u, v, u * v)).norm() < tol);
      CHECK((e.du - Vec3(1, 0, v)).norm() < tol);
      CHECK((e.dv - Vec3(0, 1, u)).norm() < tol);
      CHECK(e.duu.norm() < tol);
      CHECK((e.duv - Vec3(0, 0, 1)).norm() < tol);
      CHECK(e.dvv.norm() < tol);
      const SurfaceEval1 e1 = s->eval1(u, v);
      CHECK((e1.p - e.p).norm() < tol);
      CHECK((e1.du - e.du).norm() < tol);
      CHECK((e1.dv - e.dv).norm() < tol);
      CHECK((s->point(u, v) - e.p).norm() < tol);
    }
  }
}

TEST_CASE("kernel: rational derivatives satisfy the sphere identities exactly") {
  // On |S|^2 = R^2: S.Su = S.Sv = 0 and Su.Su + S.Suu = Su.Sv + S.Suv = Sv.Sv + S.Svv = 0.
  // These hold only if the quotient rule is right to second order.
  const double R = 20.0;
  auto s = NurbsSurface::create(sphere_patch(R, -1.2, 1.5, 0.3, 5.9));
  REQUIRE(s.ok());
  REQUIRE(s->rational());
  Rng rng(3);
  const auto& d = s->domain();
  for (int k = 0; k < 2000; ++k) {
    const double u = rng.uniform(d.u0, d.u1), v = rng.uniform(d.v0, d.v1);
    const SurfaceEval2 e = s->eval2(u, v);
    const double sp = e.du.norm() + e.dv.norm();
    CHECK(std::abs(e.p.norm() - R) < kRoundoffRel * R);
    CHECK(std::abs(e.p.dot(e.du)) < kRoundoffRel * R * sp);
    CHECK(std::abs(e.p.dot(e.dv)) < kRoundoffRel * R * sp);
    const double sc = R * (e.duu.norm() + e.duv.norm() + e.dvv.norm()) + sp * sp;
    CHECK(std::abs(e.du.dot(e.du) + e.p.dot(e.duu)) < kRoundoffRel * sc);
    CHECK(std::abs(e.du.dot(e.dv) + e.p.dot(e.duv)) < kRoundoffRel * sc);
    CHECK(std::abs(e.dv.dot(e.dv) + e.p.dot(e.dvv)) < kRoundoffRel * sc);
  }
}

TEST_CASE("kernel: the normal at a pole is the limit, flagged degenerate, never NaN") {
  const double R = 20.0;
  auto s = NurbsSurface::create(sphere_octant(R));
  REQUIRE(s.ok());
  const auto& d = s->domain();
  // u = d.u0 is the pole (0, 0, R) for every v.
  for (double v : {d.v0, 0.5 * (d.v0 + d.v1), d.v1}) {
    const SurfaceEval1 e = s->eval1(d.u0, v);
    CHECK((e.p - Vec3(0, 0, R)).norm() < kRoundoffRel * R);
    const SurfaceNormal n = s->normal(d.u0, v);
    CHECK(n.ok);
    CHECK(n.degenerate);
    CHECK(n.n.allFinite());
    CHECK((n.n - Vec3::UnitZ()).norm() < 1e-12);
  }
  // Away from the pole: not degenerate, radial and outward.
  const SurfaceNormal n = s->normal(0.4, 0.7);
  CHECK_FALSE(n.degenerate);
  CHECK((n.n - s->point(0.4, 0.7) / R).norm() < 1e-12);
  // A hemisphere's pole is in the interior of the v range, still a limit.
  auto h = NurbsSurface::create(sphere_patch(1.0, 0.0, kPi / 2, 0.0, 2 * kPi));
  REQUIRE(h.ok());
  const SurfaceNormal hn = h->normal(h->domain().u0, 2.0);
  CHECK(hn.degenerate);
  CHECK((hn.n - Vec3::UnitZ()).norm() < 1e-12);
}

TEST_CASE("kernel: an extended rational surface reports where it is undefined, no NaN") {
  // Middle weight 3 (a hyperbolic arc in u): the weight of the extended end spans,
  // 1 + 4 t (1 - t), reaches zero past the domain.
  NurbsSurfaceData d;
  d.degree_u = 2;
  d.degree_v = 1;
  d.count_u = 3;
  d.count_v = 2;
  d.knots_u = {0, 0, 0, 1, 1, 1};
  d.knots_v = {0, 0, 1, 1};
  d.poles = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 1),
             Vec3(1, 1, 1), Vec3(2, 0, 0), Vec3(2, 1, 0)};
  d.weights = {1, 1, 3, 3, 1, 1};
  auto s = NurbsSurface::create(d);
  REQUIRE(s.ok());
  int undefined = 0;
  for (double u = -5.0; u <= 6.0; u += 0.001) {
    const SurfaceEval2 e = s->eval2(u, 0.5);
    const SurfaceEval1 e1 = s->eval1(u, 0.5);
    CHECK(e.p.allFinite());
    CHECK(e.du.allFinite());
    CHECK(e.duu.allFinite());
    CHECK(e1.p.allFinite());
    CHECK(s->point(u, 0.5).allFinite());
    CHECK(s->normal(u, 0.5).n.allFinite());
    if (!e.ok) ++undefined;
    if (u >= 0.0 && u <= 1.0) CHECK(e.ok);
  }
  CHECK(undefined > 0);
}

TEST_CASE("kernel: rounding covers the spacing of the parameters' doubles, and no more") {
  // A 4 mm cylinder strip of radius 33 whose axial parameter runs over [1e5, 1e5 + 1] (a CAD
  // export's parameter from a distant origin): the doubles near u = 1e5 are 1.46e-11 apart,
  // so the surface is known only at points 4 x 1.46e-11 mm apart along the axis. rounding()
  // must cover half that spacing; the same strip on [0, 1] has only the sums' rounding.
  const double far = 1e5, width = 72.0 / 33;
  NurbsSurfaceData strip = cylinder_patch(33, 0.0, width, 0.0, 4.0);  // u axial, v around
  auto near = NurbsSurface::create(strip);
  for (double& k : strip.knots_u) k += far;
  auto at_far = NurbsSurface::create(strip);
  REQUIRE(near.ok());
  REQUIRE(at_far.ok());
  const double spacing = std::nextafter(far + 1.0, 2 * far) - (far + 1.0);  // 1.46e-11
  const double speed = at_far->eval1(far + 0.5, 0.5).du.norm();             // |Su| = 4 mm
  CHECK(std::abs(speed - 4.0) < 1e-9);
  CHECK(at_far->rounding() >= 0.5 * spacing * speed);
  // Not absurd: within a few hundred ulps of the parameter's spacing and of the strip's size.
  const double size = at_far->control_bbox().diagonal();
  const double eps = std::numeric_limits<double>::epsilon();
  CHECK(at_far->rounding() < 100 * spacing + 100 * eps * size);
  // On [0, 1] the spacing near the parameters is below the sums' rounding: a few ulps of the
  // size.
  CHECK(near->rounding() < 100 * eps * size);
  CHECK(near->rounding() > 0.0);
}

TEST_CASE("kernel: eval1_along_u gives eval1's values bit for bit, any degree, rational or not") {
  // Rows of points along u at one v, as the area integration asks: several points per knot
  // span, spans in any order, points on knots and past the domain. The fixed degrees (with a
  // Bezier table) share the sums along v; the others evaluate point by point.
  Rng rng(11);
  const std::pair<int, int> degrees[] = {{1, 1}, {1, 3}, {2, 2}, {3, 2}, {3, 3},
                                         {4, 4}, {5, 5}, {4, 2}, {6, 3}, {9, 12}};
  for (int trial = 0; trial < 40; ++trial) {
    const auto [p, q] = degrees[trial % std::size(degrees)];
    NurbsSurfaceData d;
    d.degree_u = p;
    d.degree_v = q;
    d.count_u = p + 1 + rng.integer(0, 6);
    d.count_v = q + 1 + rng.integer(0, 6);
    d.knots_u = random_knots(rng, d.count_u, p, trial % 3 != 0);
    d.knots_v = random_knots(rng, d.count_v, q, trial % 5 != 0);
    for (int k = 0; k < d.count_u * d.count_v; ++k) {
      d.poles.emplace_back(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50));
      if (trial % 2 == 1) d.weights.push_back(rng.uniform(0.3, 3.0));
    }
    auto s = NurbsSurface::create(d);
    REQUIRE(s.ok());
    const auto& dom = s->domain();
    std::vector<double> us;
    for (std::size_t k = 0; k < d.knots_u.size(); ++k) us.push_back(d.knots_u[k]);
    for (int k = 0; k < 40; ++k)
      us.push_back(rng.uniform(dom.u0 - 0.05 * dom.width_u(), dom.u1 + 0.05 * dom.width_u()));
    for (int row = 0; row < 6; ++row) {
      const double v = row == 0 ? dom.v0 : row == 1 ? dom.v1 : rng.uniform(dom.v0, dom.v1);
      std::vector<SurfaceEval1> got(us.size());
      s->eval1_along_u(v, us.data(), us.size(), got.data());
      for (std::size_t k = 0; k < us.size(); ++k) {
        const SurfaceEval1 want = s->eval1(us[k], v);
        INFO("trial " << trial << " degrees " << p << "x" << q << " uv " << us[k] << "," << v);
        CHECK(got[k].ok == want.ok);
        CHECK(got[k].p == want.p);
        CHECK(got[k].du == want.du);
        CHECK(got[k].dv == want.dv);
      }
    }
  }
}

TEST_CASE("kernel: made_from is true for the data and tolerances a surface was built from") {
  NurbsSurfaceData d = plane_patch(Vec3::Zero(), Vec3(10, 0, 0), Vec3(0, 10, 0));
  const Tolerances tol;
  auto s = NurbsSurface::create(d, tol);
  REQUIRE(s.ok());
  CHECK(s->made_from(d, tol));
  auto moved = d;
  moved.poles[1].z() += 1e-9;
  CHECK_FALSE(s->made_from(moved, tol));
  auto weighted = d;
  weighted.weights.assign(weighted.poles.size(), 1.0);  // the same surface, but rational
  CHECK_FALSE(s->made_from(weighted, tol));
  auto knots = d;
  knots.knots_u.back() = 2.0;
  CHECK_FALSE(s->made_from(knots, tol));
  Tolerances other = tol;
  other.degenerate_rel *= 2.0;
  CHECK_FALSE(s->made_from(d, other));
  other = tol;
  other.extension_min_weight_rel *= 2.0;
  CHECK_FALSE(s->made_from(d, other));
}
