// Nodes at or near a pole (a collapsed edge of a face's parameter domain): the solvers and the
// drape on the hemisphere, the sphere octant, a cone apex, bicubic domes with a collapsed u or
// v edge at either end, and the sphere as a shell of 8 faces. Configurations are built
// independently of the solvers (bisection along surface curves).
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "drape/solvers/solvers.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/faces.hpp"
#include "support/problems.hpp"
#include "support/shells.hpp"
#include "support/solver_cases.hpp"
#include "support/surfaces.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

using namespace plyfit;
using plyfit::support::make_face;
using plyfit::support::point_at_distance;
using plyfit::support::problem;

namespace {

// Constraint accuracy the solvers promise at convergence, relative to d.
constexpr double kConstraintRel = 1e-10;
// Three points of an edge closer than this (relative to the face size) are one point.
constexpr double kCollapsedRel = 1e-12;
// Distances of the unknown node from the pole, relative to d: at it, within rounding, and on.
constexpr double kPoleDistances[] = {0.0, 1e-15, 1e-12, 1e-7, 1e-4, 1e-2, 0.2, 0.7};

Face builtin(const std::string& name, std::map<std::string, double> p = {}) {
  auto fd = builtin_mold(name, p);
  REQUIRE(fd.ok());
  return make_face(std::move(fd).value());
}

// A collapsed edge of the face's domain: parameter `fixed_u` (u fixed at `at`, v free) or
// v fixed; `inward` the sign of the fixed parameter's step into the domain.
struct PoleEdge {
  bool fixed_u = true;
  double at = 0.0, lo = 0.0, hi = 1.0, inward = 1.0;
  Vec3 point = Vec3::Zero();
  Vec2 uv(double t) const { return fixed_u ? Vec2(at, t) : Vec2(t, at); }
};

std::vector<PoleEdge> pole_edges(const Face& f) {
  std::vector<PoleEdge> out;
  const auto& d = f.domain();
  for (int fu = 0; fu < 2; ++fu) {
    for (int end = 0; end < 2; ++end) {
      PoleEdge e;
      e.fixed_u = fu == 1;
      e.at = e.fixed_u ? (end ? d.u1 : d.u0) : (end ? d.v1 : d.v0);
      e.lo = e.fixed_u ? d.v0 : d.u0;
      e.hi = e.fixed_u ? d.v1 : d.u1;
      e.inward = end ? -1.0 : 1.0;
      const Vec3 a = f.eval1(e.uv(e.lo)).p, m = f.eval1(e.uv(0.5 * (e.lo + e.hi))).p,
                 b = f.eval1(e.uv(e.hi)).p;
      if ((a - m).norm() + (b - m).norm() > kCollapsedRel * f.size()) continue;
      e.point = m;
      out.push_back(e);
    }
  }
  return out;
}

struct PoleCounts {
  int built = 0, converged = 0;
};

// Two-sphere and plane-sphere solves for nodes q at the distances kPoleDistances from each
// pole of f, at several places of its fan, from neighbours a and b one spacing d away.
PoleCounts check_pole_solves(const Face& f, double d) {
  PoleCounts n;
  SolverSettings st;
  st.spacing = d;
  const std::vector<PoleEdge> edges = pole_edges(f);
  REQUIRE(!edges.empty());
  const Vec2 sp = f.speeds();
  for (const PoleEdge& e : edges) {
    for (double rel : kPoleDistances) {
      for (double frac : {0.13, 0.5, 0.91}) {
        const double t = e.lo + frac * (e.hi - e.lo);
        Vec2 uq = e.uv(t);
        if (rel > 0.0) {
          const Vec2 in = e.fixed_u ? Vec2(e.inward, 0.0) : Vec2(0.0, e.inward);
          if (!point_at_distance(f, e.uv(t), in, rel * d, uq)) continue;
        }
        const Vec3 q = f.eval1(uq).p;
        for (double ta : {-1.0, -0.3, 0.4}) {
          for (double gap : {0.8, 1.6}) {
            // Directions in the scaled (normal to the edge, along it) parameter frame.
            auto uvdir = [&](double ang) {
              const double across = e.inward * std::cos(ang), along = std::sin(ang);
              return e.fixed_u ? Vec2(across / sp.x(), along / sp.y())
                               : Vec2(along / sp.x(), across / sp.y());
            };
            Vec2 ua, ub;
            if (!point_at_distance(f, uq, uvdir(ta), d, ua) ||
                !point_at_distance(f, uq, uvdir(ta + gap), d, ub))
              continue;
            const Vec3 a = f.eval1(ua).p, b = f.eval1(ub).p;
            const Vec3 nq = f.normal(uq).n;
            const double s = nq.dot((b - a).cross(q - a));
            if (std::abs(s) < 0.05 * d * d) continue;  // q nearly on the line ab: ill-posed
            const double side = s > 0 ? 1.0 : -1.0;
            std::vector<std::optional<Vec2>> guesses = {std::nullopt, 0.5 * (ua + ub)};
            // A guess at the right distance from the pole, a third of the fan off.
            const Vec2 off =
                e.fixed_u ? Vec2(0.0, (e.hi - e.lo) / 3) : Vec2((e.hi - e.lo) / 3, 0.0);
            Vec2 bad = uq + off;
            if ((e.fixed_u ? bad.y() : bad.x()) > e.hi) bad -= 2 * off;
            guesses.push_back(bad);
            for (const auto& g : guesses) {
              ++n.built;
              const SolveResult r = solve_two_spheres(f, {a, ua, d, b, ub, d, side, g}, st);
              INFO("pole at " << e.point.transpose() << ", q " << rel << " d from it at fan "
                              << frac << ", a at " << ta << ", gap " << gap << ", guess "
                              << (g ? 1 : 0) << ": " << to_string(r.status) << " " << r.reason
                              << " after " << r.iterations << " iterations at "
                              << r.at.uv.transpose());
              CHECK(r.status == SolveStatus::kConverged);
              if (r.status != SolveStatus::kConverged) continue;
              ++n.converged;
              CHECK((r.point - q).norm() < kConstraintRel * d);
              CHECK(f.contains(r.at.uv));
              CHECK((f.eval1(r.at.uv).p - r.point).norm() < kConstraintRel * d);
            }
            // The plane through a with its normal and q - a holds q at distance d.
            const SolveResult p = solve_plane_sphere(f, {a, ua, d, q - a}, st);
            INFO("plane-sphere: " << to_string(p.status) << " " << p.reason);
            CHECK(p.status == SolveStatus::kConverged);
            if (p.status == SolveStatus::kConverged) {
              CHECK((p.point - q).norm() < kConstraintRel * d);
              CHECK(f.contains(p.at.uv));
            }
          }
        }
      }
    }
  }
  return n;
}

}  // namespace

TEST_CASE("solvers: a node at or within rounding of a pole is found, on the face") {
  SECTION("the hemisphere (closed around its axis, rational)") {
    const PoleCounts n = check_pole_solves(builtin("hemisphere", {{"R", 1.0}}), 0.0375);
    CHECK(n.built > 200);
    CHECK(n.converged == n.built);
  }
  SECTION("the sphere octant (a pole in a corner)") {
    const PoleCounts n = check_pole_solves(make_face(sphere_octant(20.0)), 1.0);
    CHECK(n.built > 200);
    CHECK(n.converged == n.built);
  }
  SECTION("a cone's apex (no tangent plane)") {
    const PoleCounts n = check_pole_solves(builtin("cone", {{"r1", 0.0}}), 1.0);
    CHECK(n.built > 200);
    CHECK(n.converged == n.built);
  }
  SECTION("bicubic domes with a collapsed u or v edge at either end") {
    for (int k = 0; k < 4; ++k) {
      INFO("transpose " << (k & 1) << ", at the end " << (k >> 1));
      const PoleCounts n =
          check_pole_solves(make_face(support::quarter_dome(10.0, 5.0, k & 1, k >> 1)), 0.5);
      CHECK(n.built > 200);
      CHECK(n.converged == n.built);
    }
  }
}

namespace {

DrapeResult run(const DrapeSurface& s, const DrapeProblem& pb) {
  auto r = drape(s, pb);
  INFO((r.ok() ? std::string() : exporters::describe(r.error())));
  REQUIRE(r.ok());
  return std::move(r).value();
}

// Nodes within `radius` of the start on the ply that are not mapped, overlapping nodes apart
// if `overlap_ok` (a base plane that cuts a closed surface in a closed curve comes round to
// the start).
int unmapped_near_start(const DrapeResult& r, double radius, bool overlap_ok) {
  const Vec2 s = r.ply->spec().start;
  int missing = 0;
  for (const DrapeNode& n : r.nodes) {
    if ((n.ply - s).norm() >= radius || n.mapped()) continue;
    if (overlap_ok && n.status == NodeStatus::kOverlap) continue;
    UNSCOPED_INFO("node (" << n.id.i << ", " << n.id.j << ") " << to_string(n.status) << " at "
                           << n.point.transpose());
    ++missing;
  }
  return missing;
}

}  // namespace

TEST_CASE("drape: nodes landing on or next to a pole are mapped") {
  SECTION("the unit hemisphere: node (1, 1) lands 5e-5 from the pole") {
    const Face f = builtin("hemisphere", {{"R", 1.0}});
    const double d = 0.0375;
    const DrapeResult r =
        run(f, problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, Vec3(-d, -d, 1),
                       Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
    CHECK(r.metrics.nodes.failed == 0);
    CHECK(r.metrics.nodes.conflict == 0);
    CHECK_FALSE(r.partial);
    CHECK(unmapped_near_start(r, 10 * d, false) == 0);
    CHECK(r.metrics.edge_length_max_rel < kConstraintRel);
  }
  SECTION("the hemisphere and the sphere as 8 faces, starts about the pole") {
    const double R = 20.0, d = 1.0;
    const Face hemi = builtin("hemisphere", {{"R", R}});
    auto sh = support::make_builtin_shell("sphere-8", {{"R", R}});
    REQUIRE(sh.ok());
    const Shell& sphere = sh.value();
    // Starts off the pole by (a, b) d, base planes at several azimuths: some node lands within
    // a hair of the pole in each.
    for (const Vec2& ab : {Vec2(-0.987, -0.971), Vec2(1.013, -0.638), Vec2(-0.654, -0.971),
                           Vec2(1.013, 0.029), Vec2(0.346, 1.029), Vec2(-0.32, 0.696)}) {
      for (double az : {0.0, 17.0, 90.0, 133.0, 200.0, 300.0}) {
        const double phi = az * kDegToRad;
        const Vec3 bn(-std::sin(phi), std::cos(phi), 0);
        const Vec3 s3(ab.x() * d, ab.y() * d, std::sqrt(R * R - ab.squaredNorm() * d * d));
        const DrapeProblem pb =
            problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, s3, bn, {bn, Vec3(-bn)});
        INFO("start " << ab.transpose() << " d, base plane at " << az << " degrees");
        const DrapeResult h = run(hemi, pb);
        CHECK(h.metrics.nodes.failed == 0);
        CHECK(h.metrics.nodes.conflict == 0);
        CHECK(unmapped_near_start(h, 8 * d, false) == 0);
        CHECK(h.metrics.edge_length_max_rel < kConstraintRel);
        // The sphere has no boundary: no node is outside it. Its base path goes all round.
        const DrapeResult s = run(sphere, pb);
        CHECK(s.metrics.nodes.outside == 0);
        CHECK(unmapped_near_start(s, 8 * d, true) == 0);
      }
    }
  }
}
