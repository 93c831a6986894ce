#include "drape/solvers/solvers.hpp"
#include <plyfit/kernel/builtin_molds.hpp>
#include "geometry/analytic_surfaces.hpp"
#include "surface/face.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/shells.hpp"
#include "support/solver_cases.hpp"
#include "support/surfaces.hpp"
#include "test_util.hpp"

#include <cmath>

using namespace plyfit;
using plyfit::support::point_at_distance;
using plyfit::test::Rng;

namespace {

// Constraint accuracy the solvers promise at convergence, relative to d (issue 3).
constexpr double kConstraintRel = 1e-10;

Face make_face(NurbsSurfaceData d, std::vector<TrimLoop> loops = {}) {
  FaceData fd;
  fd.surface = std::move(d);
  fd.loops = std::move(loops);
  auto f = Face::create(std::move(fd));
  REQUIRE(f.ok());
  return std::move(f).value();
}

// Independent checks of a returned point: on the surface at its (u, v), and the distance
// constraints.
void check_on_surface(const Face& f, const SolveResult& r) {
  CHECK((f.eval1(r.at.uv).p - r.point).norm() <= 1e-12 * f.size());
  CHECK(r.point.allFinite());
}
double sphere_error(const Vec3& p, const Vec3& c, double rho) {
  return std::abs((p - c).norm() - rho);
}

}  // namespace

TEST_CASE("solvers: exact answers on a plane") {
  const Face f = make_face(plane_patch(Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0)));
  SolverSettings st;
  st.spacing = 1.0;
  const Projection o = f.project(Vec3(0, 0, 0));
  SECTION("base path") {
    const SolveResult r =
        solve_base_path(f, {o.point, o.at.uv, Vec3(0, 1, 0), Vec3(1, 0, 0), 1.0}, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK((r.point - Vec3(1, 0, 0)).norm() < kConstraintRel);
    check_on_surface(f, r);
  }
  SECTION("two spheres, both branches") {
    const Vec3 a(1, 0, 0), b(0, 1, 0);
    const Vec2 ua = f.project(a).at.uv, ub = f.project(b).at.uv;
    TwoSphereStep s{a, ua, 1.0, b, ub, 1.0, -1.0, std::nullopt};
    SolveResult r = solve_two_spheres(f, s, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK((r.point - Vec3(1, 1, 0)).norm() < kConstraintRel);
    CHECK(r.thread_angle == Approx(kPi / 2).margin(1e-12));
    s.side = 1.0;
    r = solve_two_spheres(f, s, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK(r.point.norm() < kConstraintRel);
    // A guess on the folded branch is corrected by the restart.
    s.side = -1.0;
    s.guess = f.project(Vec3(0.1, 0.1, 0)).at.uv;
    r = solve_two_spheres(f, s, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK((r.point - Vec3(1, 1, 0)).norm() < kConstraintRel);
  }
  SECTION("plane and sphere at any angle") {
    for (double deg : {0.0, 30.0, 45.0, 135.0, 270.0}) {
      const double t = deg * kDegToRad;
      const Vec3 dir(std::cos(t), std::sin(t), 0);
      const SolveResult r = solve_plane_sphere(f, {o.point, o.at.uv, 2.0, dir}, st);
      REQUIRE(r.status == SolveStatus::kConverged);
      CHECK((r.point - 2.0 * dir).norm() < 2 * kConstraintRel);
    }
  }
}

TEST_CASE("solvers: the sphere octant's pole (paper cases (a) and (c) start there)") {
  const double R = 20.0, d = 1.0;
  const Face f = make_face(sphere_octant(R));
  SolverSettings st;
  st.spacing = d;
  // Any v at u = u0 is the pole; take one whose meridian is far from the path.
  const Vec2 pole_uv(f.domain().u0, f.domain().v1);
  const Vec3 pole = f.eval1(pole_uv).p;
  REQUIRE((pole - Vec3(0, 0, R)).norm() < 1e-12 * R);
  const double phi = 2 * std::asin(d / (2 * R));  // chord d on a great circle
  SECTION("base path along y = 0 from the pole") {
    Vec3 x0 = pole, fwd(1, 0, 0);
    Vec2 uv0 = pole_uv;
    for (int k = 1; k <= 30; ++k) {
      const SolveResult r = solve_base_path(f, {x0, uv0, Vec3(0, 1, 0), fwd, d}, st);
      REQUIRE(r.status == SolveStatus::kConverged);
      const Vec3 expect(R * std::sin(k * phi), 0, R * std::cos(k * phi));
      CHECK((r.point - expect).norm() < 10 * k * kConstraintRel * d);
      CHECK(std::abs(r.point.y()) < kConstraintRel * d);
      CHECK(sphere_error(r.point, x0, d) < kConstraintRel * d);
      check_on_surface(f, r);
      fwd = r.point - x0;
      x0 = r.point;
      uv0 = r.at.uv;
    }
  }
  SECTION("plane and sphere from the pole at 30 degrees") {
    const double t = kPi / 6;
    const Vec3 dir(std::cos(t), std::sin(t), 0);
    const SolveResult r = solve_plane_sphere(f, {pole, pole_uv, d, dir}, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    const Vec3 expect(R * std::sin(phi) * std::cos(t), R * std::sin(phi) * std::sin(t),
                      R * std::cos(phi));
    CHECK((r.point - expect).norm() < 10 * kConstraintRel * d);
  }
  SECTION("two spheres next to the pole") {
    // a and b one chord from the pole along the meridians at 0 and 90 degrees; the node
    // between them lies one chord from both, off the pole.
    const Vec3 a(R * std::sin(phi), 0, R * std::cos(phi)),
        b(0, R * std::sin(phi), R * std::cos(phi));
    const SolveResult r = solve_two_spheres(
        f, {a, f.project(a).at.uv, d, b, f.project(b).at.uv, d, -1.0, std::nullopt}, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK(sphere_error(r.point, a, d) < kConstraintRel * d);
    CHECK(sphere_error(r.point, b, d) < kConstraintRel * d);
    CHECK(r.point.x() > a.x() * 0.5);  // the side away from the pole
    // The other branch is the pole itself.
    const SolveResult q = solve_two_spheres(
        f, {a, f.project(a).at.uv, d, b, f.project(b).at.uv, d, 1.0, std::nullopt}, st);
    REQUIRE(q.status == SolveStatus::kConverged);
    CHECK((q.point - pole).norm() < 10 * kConstraintRel * d);
    CHECK(q.point.allFinite());
  }
}

TEST_CASE("solvers: near the shear limit, converge or say so, never a wrong point") {
  const Face f = make_face(plane_patch(Vec3(-10, -10, 0), Vec3(20, 0, 0), Vec3(0, 20, 0)));
  SolverSettings st;
  st.spacing = 1.0;
  const Vec3 a(0, 0, 0);
  for (double gap : {1e-1, 1e-3, 1e-6, 1e-9, 1e-12, 0.0, -1e-9, -1e-3}) {
    // |a - b| = 2 (1 - gap): the spheres meet in a circle of radius ~ sqrt(2 gap).
    const Vec3 b(2 * (1 - gap), 0, 0);
    TwoSphereStep s{a, f.project(a).at.uv, 1.0, b, f.project(b).at.uv, 1.0, 1.0, std::nullopt};
    st.gamma_min = 0.0;
    const SolveResult r = solve_two_spheres(f, s, st);
    INFO("gap " << gap << " status " << to_string(r.status) << " " << r.reason);
    if (r.status == SolveStatus::kConverged) {
      CHECK(sphere_error(r.point, a, 1.0) < kConstraintRel);
      CHECK(sphere_error(r.point, b, 1.0) < kConstraintRel);
      CHECK(r.point.y() >= 0.0);  // requested side (n = +z, side +1)
    } else {
      CHECK(r.status == SolveStatus::kFailed);
    }
    if (gap < 0) CHECK(r.status == SolveStatus::kFailed);
    // With a lock angle the thread angle near pi is caught as the shear limit.
    st.gamma_min = 10.0 * kDegToRad;
    const SolveResult q = solve_two_spheres(f, s, st);
    if (gap <= 1e-3) CHECK(q.status != SolveStatus::kConverged);
    if (gap == 1e-3) CHECK(q.status == SolveStatus::kShearLimit);  // 174.9 degrees
    // Spheres apart: the thread angle would pass 180 degrees, beyond any lock.
    if (gap < 0) CHECK(q.status == SolveStatus::kShearLimit);
    if (gap == 1e-1) CHECK(q.status == SolveStatus::kConverged);  // angle ~ 2 asin(0.9) = 128 deg
  }
}

TEST_CASE("solvers: a step across a C0 crease") {
  // A roof: two planes z = 1 + x/2 (x < 0) and z = 1 - x/2 (x > 0) meeting in a crease at
  // x = 0, as one degree-2 B-spline with a double knot (C0).
  const NurbsSurfaceData d = support::roof(1);
  const Face f = make_face(d);
  SolverSettings st;
  st.spacing = 1.0;
  const Vec3 x0(-0.2, 0, 0.9);
  const Vec2 uv0 = f.project(x0).at.uv;
  // Exact: x1 > 0 with (x1 + 0.2)^2 + (0.1 - x1 / 2)^2 = 1.
  const double A = 1.25, B = 0.4 - 0.1, C = 0.04 + 0.01 - 1.0;
  const double x1 = (-B + std::sqrt(B * B - 4 * A * C)) / (2 * A);
  const Vec3 expect(x1, 0, 1 - x1 / 2);
  const SolveResult r = solve_base_path(f, {x0, uv0, Vec3(0, 1, 0), Vec3(1, 0, 0), 1.0}, st);
  REQUIRE(r.status == SolveStatus::kConverged);
  CHECK((r.point - expect).norm() < 10 * kConstraintRel);
  const SolveResult q = solve_plane_sphere(f, {x0, uv0, 1.0, Vec3(1, 0, 0.5)}, st);
  REQUIRE(q.status == SolveStatus::kConverged);
  CHECK((q.point - expect).norm() < 10 * kConstraintRel);
  // Two spheres whose solution lies across the crease.
  const Vec3 a(x1, -0.6, 1 - x1 / 2);
  const Vec3 b(-0.2, 0.5, 0.9);
  const double ra = (expect - a).norm(), rb = (expect - b).norm();
  const Vec3 n_guess(0.3, 0, 1);  // side from the truth
  const double side = n_guess.dot((b - a).cross(expect - a)) > 0 ? 1.0 : -1.0;
  const SolveResult t = solve_two_spheres(
      f, {a, f.project(a).at.uv, ra, b, f.project(b).at.uv, rb, side, std::nullopt}, st);
  REQUIRE(t.status == SolveStatus::kConverged);
  CHECK((t.point - expect).norm() < 1e-9);
}

TEST_CASE("solvers: strongly non-uniform parametrisation and extreme weights") {
  // A flat patch z = 0 whose parametrisation is wildly non-uniform: knot spans differing by
  // 1000x and product weights from 0.01 to 100. Geometry is a plane, so answers are exact.
  const Face f = make_face(support::wild_plane(true, true));
  SolverSettings st;
  st.spacing = 0.5;
  Rng rng(9);
  int converged = 0, total = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 x0(rng.uniform(-7, 7), rng.uniform(-7, 7), 0);
    const Projection p0 = f.project(x0);
    REQUIRE(p0.distance < 1e-9);
    const double t = rng.uniform(0, 2 * kPi);
    const Vec3 dir(std::cos(t), std::sin(t), 0);
    const SolveResult r = solve_plane_sphere(f, {x0, p0.at.uv, 0.5, dir}, st);
    ++total;
    if (r.status == SolveStatus::kConverged) {
      ++converged;
      CHECK((r.point - (x0 + 0.5 * dir)).norm() < kConstraintRel * 0.5);
    }
    const SolveResult b =
        solve_base_path(f, {x0, p0.at.uv, Vec3(-dir.y(), dir.x(), 0), dir, 0.5}, st);
    ++total;
    if (b.status == SolveStatus::kConverged) {
      ++converged;
      CHECK((b.point - (x0 + 0.5 * dir)).norm() < kConstraintRel * 0.5);
    }
  }
  CHECK(converged == total);
  // Two spheres: configurations built by bisection along surface curves (independent).
  int ok2 = 0, built = 0;
  for (int k = 0; k < 300; ++k) {
    const Projection pp = f.project(Vec3(rng.uniform(-7, 7), rng.uniform(-7, 7), 0));
    const SurfaceEval1 ep = f.eval1(pp.at.uv);
    auto uvdir = [&](double t) {
      return Vec2(std::cos(t) / ep.du.norm(), std::sin(t) / ep.dv.norm());
    };
    const double t1 = rng.uniform(0, 2 * kPi), t2 = t1 + rng.uniform(0.6, 2.5);
    Vec2 ua, ub;
    if (!point_at_distance(f, pp.at.uv, uvdir(t1), 0.5, ua) ||
        !point_at_distance(f, pp.at.uv, uvdir(t2), 0.5, ub))
      continue;
    ++built;
    const Vec3 a = f.eval1(ua).p, b = f.eval1(ub).p;
    const double side = (b - a).cross(pp.point - a).z() > 0 ? 1.0 : -1.0;  // n = +z
    const SolveResult r = solve_two_spheres(f, {a, ua, 0.5, b, ub, 0.5, side, std::nullopt}, st);
    UNSCOPED_INFO("two-sphere " << to_string(r.status) << " " << r.reason << " it " << r.iterations
                                << " p " << pp.point.transpose() << " uv " << pp.at.uv.transpose());
    if (r.status != SolveStatus::kConverged) continue;
    ++ok2;
    CHECK((r.point - pp.point).norm() < 1e-9);
  }
  CHECK(built > 250);
  CHECK(ok2 == built);
}

TEST_CASE("solvers: the same problem at scales 1e-3, 1 and 1e4 gives the scaled answer") {
  SolveResult ref;
  for (double scale : {1.0, 1e-3, 1e4}) {
    NurbsSurfaceData d = wave_surface(100.0, 8.0, 70.0, 10);
    for (auto& p : d.poles) p *= scale;
    const Face f = make_face(d);
    SolverSettings st;
    st.spacing = 2.0 * scale;
    const Vec3 a = f.eval1(Vec2(0.5, 0.5)).p, b = f.eval1(Vec2(0.52, 0.48)).p;
    const SolveResult r = solve_two_spheres(
        f, {a, Vec2(0.5, 0.5), 2.0 * scale, b, Vec2(0.52, 0.48), 2.0 * scale, 1.0, std::nullopt},
        st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK(sphere_error(r.point, a, 2.0 * scale) < kConstraintRel * 2.0 * scale);
    if (scale == 1.0) {
      ref = r;
    } else {
      CHECK((r.point / scale - ref.point).norm() < 1e-9);
      CHECK(r.iterations == ref.iterations);
      CHECK(r.evaluations == ref.evaluations);
    }
  }
}

TEST_CASE("solvers: curvature radius equal to d, and a saddle") {
  SECTION("sphere of radius d") {
    const double R = 1.0, d = 1.0;
    const Face f = make_face(sphere_patch(R, -1.4, 1.5, 0.0, 5.0));
    SolverSettings st;
    st.spacing = d;
    const Vec3 x0(R, 0, 0);
    const Projection p0 = f.project(x0);
    // Chord 1 on a great circle of radius 1: 60 degrees.
    const SolveResult r =
        solve_base_path(f, {p0.point, p0.at.uv, Vec3(0, 1, 0), Vec3(0, 0, 1), d}, st);
    REQUIRE(r.status == SolveStatus::kConverged);
    CHECK((r.point - Vec3(std::cos(kPi / 3), 0, std::sin(kPi / 3))).norm() < 10 * kConstraintRel);
    const SolveResult q = solve_plane_sphere(f, {p0.point, p0.at.uv, d, Vec3(0, 1, 1)}, st);
    REQUIRE(q.status == SolveStatus::kConverged);
    CHECK(sphere_error(q.point, x0, d) < kConstraintRel);
    CHECK(std::abs(q.point.norm() - R) < 1e-12);
  }
  SECTION("saddle (negative Gaussian curvature)") {
    const Face f = make_face(saddle_patch(20.0, 5.0));
    SolverSettings st;
    st.spacing = 1.0;
    Rng rng(21);
    int ok = 0;
    for (int k = 0; k < 200; ++k) {
      const Vec2 uvp(rng.uniform(0.25, 0.75), rng.uniform(0.25, 0.75));
      const double t1 = rng.uniform(0, 2 * kPi), t2 = t1 + rng.uniform(0.6, 2.5);
      Vec2 ua, ub;
      REQUIRE(point_at_distance(f, uvp, Vec2(std::cos(t1), std::sin(t1)), 1.0, ua));
      REQUIRE(point_at_distance(f, uvp, Vec2(std::cos(t2), std::sin(t2)), 1.0, ub));
      const Vec3 p = f.eval1(uvp).p, a = f.eval1(ua).p, b = f.eval1(ub).p;
      const double side = f.normal(uvp).n.dot((b - a).cross(p - a)) > 0 ? 1.0 : -1.0;
      const SolveResult r = solve_two_spheres(f, {a, ua, 1.0, b, ub, 1.0, side, std::nullopt}, st);
      if (r.status != SolveStatus::kConverged) continue;
      ++ok;
      CHECK((r.point - p).norm() < 1e-8);
    }
    CHECK(ok == 200);
  }
}

TEST_CASE("solvers: steps from the middle of a large face converge at its rounding level") {
  // The origin of a 40 mm saddle is evaluated to a few ulps of 40 mm (the size of the control
  // net summed over), not of its own zero coordinates: with d = 0.2 the residual cannot reach
  // 1e-14 d there, and the stop must allow for it.
  const Face f = make_face(saddle_patch(40.0, 20.0));
  SolverSettings st;
  st.spacing = 0.2;
  const Projection p0 = f.project(Vec3(0, 0, 0));
  REQUIRE(p0.distance < 1e-12);
  int converged = 0, total = 0;
  for (int k = 0; k < 72; ++k) {
    const double t = 2 * kPi * k / 72;
    const Vec3 dir(std::cos(t), std::sin(t), 0), bn(-std::sin(t), std::cos(t), 0);
    const SolveResult r = solve_base_path(f, {p0.point, p0.at.uv, bn, dir, st.spacing}, st);
    ++total;
    INFO("direction " << k << ": " << to_string(r.status) << " " << r.reason << " residual "
                      << r.residual);
    CHECK(r.status == SolveStatus::kConverged);
    if (r.status != SolveStatus::kConverged) continue;
    ++converged;
    CHECK(sphere_error(r.point, p0.point, st.spacing) < kConstraintRel * st.spacing);
    CHECK(std::abs(bn.dot(r.point - p0.point)) < kConstraintRel * st.spacing);
    check_on_surface(f, r);
  }
  CHECK(converged == total);
}

TEST_CASE("solvers: a step past the domain edge or into a trim hole leaves the face promptly") {
  const Face f = make_face(plane_patch(Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0)));
  SolverSettings st;
  st.spacing = 1.0;
  const Vec3 x0(9.5, 5, 0);
  const Vec2 uv0 = f.project(x0).at.uv;
  // Half a step past the edge: converged on the extended surface, reported outside.
  SolveResult r = solve_base_path(f, {x0, uv0, Vec3(0, 1, 0), Vec3(1, 0, 0), 1.0}, st);
  CHECK(r.status == SolveStatus::kLeftFace);
  CHECK(r.extended);
  CHECK((r.point - Vec3(10.5, 5, 0)).norm() < kConstraintRel);
  // Many steps past the edge: stopped within a few iterations, no far excursion.
  st.spacing = 8.0;
  r = solve_base_path(f, {x0, uv0, Vec3(0, 1, 0), Vec3(1, 0, 0), 8.0}, st);
  CHECK(r.status == SolveStatus::kLeftFace);
  CHECK(r.iterations <= 3);
  CHECK(r.at.uv.x() <= f.domain().u1 + st.tol.extension_steps * 1.0);
  // A circular hole of radius 1 at (5, 5): a step into it.
  std::vector<Vec2> hole;
  for (int k = 0; k < 720; ++k) {
    const double t = -2 * kPi * k / 720;
    hole.emplace_back(0.5 + 0.1 * std::cos(t), 0.5 + 0.1 * std::sin(t));
  }
  const Face g =
      make_face(plane_patch(Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, 10, 0)),
                {TrimLoop{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}}, TrimLoop{hole}});
  st.spacing = 1.0;
  const Vec3 y0(3.5, 5, 0);
  const SolveResult h = solve_plane_sphere(g, {y0, g.project(y0).at.uv, 1.0, Vec3(1, 0, 0)}, st);
  CHECK(h.status == SolveStatus::kLeftFace);
  CHECK(h.extended);
  CHECK((h.point - Vec3(4.5, 5, 0)).norm() < kConstraintRel);
}

TEST_CASE("solvers: random valid configurations are recovered, never folded", "[slow]") {
  // Configurations built independently of the solvers (tests/support/solver_cases.hpp): a
  // cell corner c and its neighbours a, b at the rest length, found by bisection along
  // surface curves; the node p across line ab is what solver 2 must find.
  struct Case {
    const char* name;
    NurbsSurfaceData data;
    double d;
  };
  std::vector<Case> cases;
  {
    // Random bicubic bumps over [0, 100]^2.
    Rng rng(31);
    NurbsSurfaceData s;
    s.degree_u = s.degree_v = 3;
    s.count_u = s.count_v = 9;
    std::vector<double> k = {0, 0, 0, 0, 0.2, 0.35, 0.5, 0.7, 0.85, 1, 1, 1, 1};
    s.knots_u = s.knots_v = k;
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j < 9; ++j) s.poles.emplace_back(12.5 * i, 12.5 * j, rng.uniform(-12, 12));
    cases.push_back({"bicubic", s, 1.0});
  }
  cases.push_back({"rational torus", torus_patch(30.0, 10.0, -2.5, 2.5, 0.0, 4.0), 1.0});
  for (const auto& c : cases) {
    const Face f = make_face(c.data);
    SolverSettings st;
    st.spacing = c.d;
    const auto configs = support::make_solver_cases(f, c.d, 4000, 77);
    const int trials = static_cast<int>(configs.size());
    int ok2 = 0, ok1 = 0, ok3 = 0, it2 = 0;
    for (const auto& k : configs) {
      // Half the cases start from the drape's parallelogram guess, half from none (the
      // solver's planar guess).
      const bool with_guess = (&k - configs.data()) % 2 == 0;
      const SolveResult r2 =
          solve_two_spheres(f,
                            {k.a, k.ua, c.d, k.b, k.ub, c.d, k.side,
                             with_guess ? std::optional<Vec2>(k.guess) : std::nullopt},
                            st);
      if (r2.status == SolveStatus::kConverged) {
        const double sd = f.normal(r2.at.uv).n.dot((k.b - k.a).cross(r2.point - k.a));
        REQUIRE(sd * k.side > 0);  // never the folded branch
        CHECK(sphere_error(r2.point, k.a, c.d) < kConstraintRel * c.d);
        CHECK(sphere_error(r2.point, k.b, c.d) < kConstraintRel * c.d);
        check_on_surface(f, r2);
        ++ok2;
        it2 += r2.iterations;
      }
      // Solver 3 from c towards a: the plane through c containing n and (a - c).
      const SolveResult r3 = solve_plane_sphere(f, {k.c, k.uc, c.d, k.a - k.c}, st);
      if (r3.status == SolveStatus::kConverged) {
        const Vec3 m = f.normal(k.uc).n.cross(k.a - k.c).normalized();
        CHECK(std::abs(m.dot(r3.point - k.c)) < kConstraintRel * c.d);
        CHECK(sphere_error(r3.point, k.c, c.d) < kConstraintRel * c.d);
        CHECK((r3.point - k.c).dot(k.a - k.c) > 0);
        check_on_surface(f, r3);
        ++ok3;
      }
      // Solver 1: the tilted base plane through c.
      const SolveResult r1 = solve_base_path(f, {k.c, k.uc, k.plane_normal, k.travel, c.d}, st);
      if (r1.status == SolveStatus::kConverged) {
        CHECK(std::abs(k.plane_normal.dot(r1.point - k.c)) < kConstraintRel * c.d);
        CHECK(sphere_error(r1.point, k.c, c.d) < kConstraintRel * c.d);
        CHECK((r1.point - k.c).dot(k.travel) > 0);
        check_on_surface(f, r1);
        ++ok1;
      }
    }
    INFO(c.name << ": trials " << trials << " solver2 " << ok2 << " solver1 " << ok1 << " solver3 "
                << ok3 << " mean iterations (2) " << double(it2) / ok2);
    REQUIRE(trials > 3000);
    CHECK(ok2 >= 0.999 * trials);
    CHECK(ok1 >= 0.999 * trials);
    CHECK(ok3 >= 0.999 * trials);
  }
}

TEST_CASE("solvers: a cell sheared nearly flat across two faces of sphere-8 is solved unfolded") {
  // A node of a fuzz drape on builtin:sphere-8 (R = 20, d = 2.33766) near the south pole,
  // its weft neighbour a and warp neighbour b on two octant faces and the cell sheared by
  // 80 degrees: both solutions of the two spheres lie 0.19 sideways of the chord a-b but
  // 0.14 below it (the sphere's sag), and the old side test (the full perpendicular to a-b)
  // took the unfolded one for the folded one: "only the folded branch was found".
  const double R = 20.0, d = 2.33766;
  auto made = support::make_builtin_shell("sphere-8", {{"R", R}});
  REQUIRE(made.ok());
  const Shell& sh = *made;
  const Vec3 a = Vec3(-5.15837763509, -0.952660671787, -19.2998336215).normalized() * R;
  const Vec3 b = Vec3(-2.79642230406, 3.05670182342, -19.5662105749).normalized() * R;
  // Both solutions in closed form: |p| = R, |p - a| = |p - b| = d.
  const auto [s1, s2] = support::sphere_points_at(a, b, R, d);
  // The cell's fourth corner is the solution on the side +1 about the outward normal; the
  // node is the other one.
  auto side = [&](const Vec3& p) { return (p / R).dot((b - a).cross(p - a)); };
  const Vec3 corner = side(s1) > 0 ? s1 : s2, want = side(s1) > 0 ? s2 : s1;
  const double gamma = std::acos((a - want).normalized().dot((b - want).normalized()));
  REQUIRE(gamma > 169.0 * kDegToRad);  // sheared by more than 79 degrees
  TwoSphereStep st;
  st.a = a;
  st.b = b;
  st.a_at = sh.project(a).at;
  st.b_at = sh.project(b).at;
  REQUIRE(st.a_at.face != st.b_at.face);
  st.ra = st.rb = d;
  st.side = -1.0;
  st.corner = corner;
  SolverSettings set;
  set.spacing = d;
  set.gamma_min = set.tol.fold_angle;
  const SolveResult r = solve_two_spheres(sh, st, set);
  INFO("status " << to_string(r.status) << ": " << r.reason);
  REQUIRE(r.status == SolveStatus::kConverged);
  CHECK((r.point - want).norm() < kConstraintRel * d * 100);
  CHECK(sphere_error(r.point, a, d) < kConstraintRel * d);
  CHECK(sphere_error(r.point, b, d) < kConstraintRel * d);
}

TEST_CASE("solvers: links that would pass below a curved face are the shear limit, not a failure") {
  // Unit sphere; a and b on the equator 60 degrees apart (|a - b| = 1). The points at equal
  // distance r from both lie on the meridian plane y = 0, (cos phi, 0, sin phi), at distance
  // sqrt(2 - sqrt(3) cos phi) >= sqrt(2 - sqrt(3)) = 0.5176 from them: for r below that no
  // point of the sphere fits both links, although the spheres about a and b meet (2 r > 1).
  const Face f = make_face(sphere_patch(1.0, -kPi / 4, kPi / 4, -kPi / 3, kPi / 3));
  const Vec3 a(std::cos(kPi / 6), -0.5, 0), b(std::cos(kPi / 6), 0.5, 0);
  SolverSettings st;
  st.spacing = 0.5;
  auto step = [&](double r) {
    return TwoSphereStep{a, f.project(a).at, r, b, f.project(b).at, r, 1.0, std::nullopt};
  };
  SECTION("a solution exists: found, on the meridian") {
    const double r = 0.55;
    st.gamma_min = st.tol.fold_angle;
    const SolveResult q = solve_two_spheres(f, step(r), st);
    REQUIRE(q.status == SolveStatus::kConverged);
    const double cos_phi = (2 - r * r) / std::sqrt(3.0);
    CHECK(std::abs(q.point.y()) < kConstraintRel);
    CHECK(std::abs(std::abs(q.point.z()) - std::sqrt(1 - cos_phi * cos_phi)) < kConstraintRel);
    CHECK(sphere_error(q.point, a, r) < kConstraintRel);
    CHECK(sphere_error(q.point, b, r) < kConstraintRel);
  }
  SECTION("no solution: the shear limit for a weft and a warp link, with its thread angle") {
    const double r = 0.505;
    st.gamma_min = st.tol.fold_angle;  // no lock angle: only the fold angle, 1 degree
    const SolveResult q = solve_two_spheres(f, step(r), st);
    INFO(to_string(q.status) << " " << q.reason);
    CHECK(q.status == SolveStatus::kShearLimit);
    CHECK(q.no_point);
    // The thread angle of the three lengths: cos = (2 r^2 - 1) / (2 r^2), 163.9 degrees.
    CHECK(std::abs(q.thread_angle - std::acos((2 * r * r - 1) / (2 * r * r))) < 1e-12);
  }
  SECTION("no solution: two links of one thread fail, saying that no point fits") {
    st.gamma_min = 0.0;
    const SolveResult q = solve_two_spheres(f, step(0.505), st);
    CHECK(q.status == SolveStatus::kFailed);
    CHECK(q.no_point);
  }
}

TEST_CASE("solvers: steps from an edge where S_u vanishes but the edge is no pole") {
  // The square [0, 10]^2 in z = 0 with x = 10 u^k (k = 2, 3): S_u = 0 all along the edge u = 0,
  // which is 10 long (S_v does not vanish there). From its middle, a step across the edge into
  // the face lands at the exact point; a step out of the face leaves it.
  for (const int k : {2, 3}) {
    NurbsSurfaceData d;
    d.degree_u = k;
    d.count_u = k + 1;
    d.degree_v = 1;
    d.count_v = 2;
    d.knots_u.assign(static_cast<std::size_t>(k + 1), 0.0);
    d.knots_u.resize(static_cast<std::size_t>(2 * k + 2), 1.0);
    d.knots_v = {0, 0, 1, 1};
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j < 2; ++j) d.poles.emplace_back(i == k ? 10.0 : 0.0, 10.0 * j, 0.0);
    const Face f = make_face(d);
    const Vec3 x0(0, 5, 0);
    const SurfaceLocation at0(Vec2(0, 0.5));
    REQUIRE((f.eval1(at0).p - x0).norm() < 1e-14);
    REQUIRE(f.eval1(at0).du.norm() == 0.0);
    SolverSettings st;
    st.spacing = 1.0;
    INFO("x = 10 u^" << k);
    SECTION("base path") {
      const SolveResult in = solve_base_path(f, {x0, at0, Vec3(0, 1, 0), Vec3(1, 0, 0), 1.0}, st);
      INFO(to_string(in.status) << " " << in.reason);
      REQUIRE(in.status == SolveStatus::kConverged);
      CHECK((in.point - Vec3(1, 5, 0)).norm() < kConstraintRel);
      check_on_surface(f, in);
      const SolveResult out = solve_base_path(f, {x0, at0, Vec3(0, 1, 0), Vec3(-1, 0, 0), 1.0}, st);
      INFO(to_string(out.status) << " " << out.reason);
      CHECK(out.status == SolveStatus::kLeftFace);
    }
    SECTION("plane-sphere, across the edge and obliquely") {
      for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0.6, 0.8, 0), Vec3(0.6, -0.8, 0)}) {
        const SolveResult in = solve_plane_sphere(f, {x0, at0, 1.0, dir}, st);
        INFO(dir.transpose() << ": " << to_string(in.status) << " " << in.reason);
        REQUIRE(in.status == SolveStatus::kConverged);
        CHECK((in.point - (x0 + dir)).norm() < kConstraintRel);
        check_on_surface(f, in);
      }
      const SolveResult out = solve_plane_sphere(f, {x0, at0, 1.0, Vec3(-0.6, 0.8, 0)}, st);
      CHECK(out.status == SolveStatus::kLeftFace);
    }
  }
}

TEST_CASE("solvers: a step longer than the face's plane section ends the path, not a failure") {
  // Unit hemisphere z >= 0; P at latitude 45 degrees on the meridian y = 0, and a base plane
  // through P with its normal m at latitude 25 degrees: it cuts the sphere in a circle of
  // radius sin 20 degrees about (cos 20) m, all on the face, whose points lie at most its
  // diameter 2 sin 20 = 0.684 from P. A base-path step of 1.0 has no place on the face (the
  // section closes within the step: the path ends there; it does not leave the face); one of
  // 0.3 has (a point of that circle).
  const Face f = make_face(sphere_patch(1.0, 0.0, kPi / 2, -kPi, kPi));
  const double c45 = std::cos(kPi / 4);
  const Vec3 p(c45, 0, c45), m(std::cos(25 * kDegToRad), 0, std::sin(25 * kDegToRad));
  const Projection at = f.project(p);
  REQUIRE((at.point - p).norm() < 1e-12);
  SolverSettings st;
  st.spacing = 1.0;
  for (const double rho : {0.3, 1.0}) {
    const SolveResult r = solve_base_path(f, {p, at.at, m, Vec3(0, 1, 0), rho}, st);
    INFO("rho " << rho << ": " << to_string(r.status) << " " << r.reason);
    if (rho < 2 * std::sin(20 * kDegToRad)) {
      REQUIRE(r.status == SolveStatus::kConverged);
      CHECK(std::abs((r.point - p).dot(m)) < kConstraintRel);
      CHECK(sphere_error(r.point, p, rho) < kConstraintRel);
      CHECK(std::abs(r.point.norm() - 1) < kConstraintRel);
      CHECK(r.point.y() > 0);
    } else {
      CHECK(r.status == SolveStatus::kFailed);
      CHECK(r.section_ends);
    }
  }
}

TEST_CASE("solvers: a base plane nearly tangent to a sphere: its small section circle") {
  // A plane through x0 = (R, 0, 0) whose normal lies theta from the sphere's normal there cuts
  // the sphere in a circle of radius rs = R sin(theta) about c = R cos(theta) pn (Meusnier).
  // Going forward along the section from x0, its point at arc angle phi lies at the chord
  // 2 rs sin(phi / 2) from x0: a step of rho <= 2 rs lands at phi = 2 asin(rho / (2 rs)),
  // past a quarter turn when rho > sqrt(2) rs (behind x0 along the section's tangent); a
  // step longer than the circle's diameter has no point at all: the path ends there.
  const double R = 1.0;
  const Face f = make_face(sphere_patch(R, -1.2, 1.2, -1.5, 1.5));
  SolverSettings st;
  st.spacing = 0.1;
  const Vec3 x0(R, 0, 0);
  const Projection p0 = f.project(x0);
  REQUIRE(p0.distance < 1e-12);
  for (const double theta_deg : {1.0, 4.0, 10.0, 25.0}) {
    const double theta = theta_deg * kDegToRad;
    const Vec3 pn(std::cos(theta), 0, std::sin(theta));
    const Vec3 fwd(0, 1, 0);  // the section's tangent at x0 is along y
    const double rs = R * std::sin(theta);
    const Vec3 c = R * std::cos(theta) * pn;
    for (const double ratio : {0.5, 0.9, 0.99, 1.01, 1.3}) {
      const double rho = ratio * 2.0 * rs;
      INFO("theta " << theta_deg << " deg, rho / diameter " << ratio);
      const SolveResult r = solve_base_path(f, {x0, p0.at, pn, fwd, rho}, st);
      if (ratio > 1.0) {
        CHECK(r.status == SolveStatus::kFailed);
        CHECK(r.section_ends);
        continue;
      }
      REQUIRE(r.status == SolveStatus::kConverged);
      const double phi = 2.0 * std::asin(ratio);
      const Vec3 exact = c + std::cos(phi) * (x0 - c) + std::sin(phi) * rs * fwd;
      CHECK((r.point - exact).norm() < 1e-9 * rho);
      CHECK(!r.section_ends);
    }
  }
}

TEST_CASE("solvers: a march-only plane-sphere step keeps the march's verdict, no trace") {
  // Unit hemisphere z >= 0, from P at latitude 45 degrees along the parallel (y): the plane
  // through the normal cuts the great circle cos(s) P + sin(s) y, on the face for |s| <= 90
  // degrees (chord sqrt 2 from P). A step of rho < sqrt 2 lands at the same point either way
  // (the march solves it, the trace is never asked); one of 1.9 leaves the face either way;
  // one longer than the circle's diameter has no point: the full solve traces the section
  // (to where it leaves the face), the march-only one stops unconverged at fewer evaluations.
  const Face f = make_face(sphere_patch(1.0, 0.0, kPi / 2, -kPi, kPi));
  const double c45 = std::cos(kPi / 4);
  const Vec3 p(c45, 0, c45);
  const Projection at = f.project(p);
  REQUIRE((at.point - p).norm() < 1e-12);
  SolverSettings st;
  st.spacing = 0.1;
  for (const double rho : {0.3, 1.0, 1.4, 1.9, 2.5}) {
    INFO("rho " << rho);
    PlaneSphereStep step{p, at.at, rho, Vec3(0, 1, 0)};
    const SolveResult full = solve_plane_sphere(f, step, st);
    step.march_only = true;
    const SolveResult march = solve_plane_sphere(f, step, st);
    INFO(to_string(full.status) << " " << full.reason << " / " << to_string(march.status) << " "
                                << march.reason << "; evaluations " << full.evaluations << " / "
                                << march.evaluations);
    if (rho < std::sqrt(2.0)) {
      REQUIRE(full.status == SolveStatus::kConverged);
      REQUIRE(march.status == SolveStatus::kConverged);
      CHECK(march.point == full.point);
      CHECK(sphere_error(march.point, p, rho) < kConstraintRel);
      CHECK(std::abs(march.point.norm() - 1) < kConstraintRel);
    } else if (rho < 2.0) {
      CHECK(full.status == SolveStatus::kLeftFace);
      CHECK(march.status == SolveStatus::kLeftFace);
    } else {
      CHECK(full.status != SolveStatus::kConverged);
      CHECK(march.status != SolveStatus::kConverged);
      CHECK(march.evaluations < full.evaluations);
    }
  }
}
