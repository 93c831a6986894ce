// The surface near a known point as the solvers use it: normals, tangent directions in (u, v)
// (at poles and degenerate edges too), nearest points.
#include "drape/solvers/tangent.hpp"
#include "geometry/numeric.hpp"

#include "drape/solvers/newton.hpp"
#include "surface/poles.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace plyfit {

Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - c);
}

namespace solvers {

namespace {

// A step from a degenerate edge that is no pole (see singular_edge_direction) is told into
// or off the face by the chord to the surface across the edge, of this fraction of the
// step's length, found among parameter steps halved at most kSingularEdgeHalvings times.
constexpr double kProbeRel = 1e-3;
constexpr int kSingularEdgeHalvings = 60;
// A degenerate point lies on a domain edge when within this fraction of the domain's width
// of it (a start projected onto the edge lands within rounding of it, or a hair inside).
constexpr double kEdgeNearRel = 1e-6;

// At a degenerate point on a domain edge across which the derivative vanishes while the one
// along the edge does not (the edge is no pole: a regular surface parametrised as
// S(u0 + s^(1/k), v) near u = u0, k > 1), a step leaves the face unless it has a component
// into the face, along the chord from the point to the surface a short way across the edge
// (its length kProbeRel of the step's). Otherwise it starts from a point across the edge,
// the farthest of the parameter steps width * 2^-j whose chord is at most half the step's
// length, with the direction of the metric there (the first-order model at the edge itself
// cannot move across it). False when the point is not of this kind.
bool singular_edge_direction(const DrapeSurface& surface, const SurfaceLocation& at,
                             const SurfaceEval1& e, const Vec3& n, const Vec3& dt, double reach,
                             UvDirection& out) {
  const Vec2 sp = surface.speeds(at);
  const bool across_u = e.du.norm() * sp.y() < e.dv.norm() * sp.x();  // S_u vanishes
  const ParamDomain& d = surface.domain(at);
  const double lo = across_u ? d.u0 : d.v0, hi = across_u ? d.u1 : d.v1;
  const double x = across_u ? at.uv.x() : at.uv.y(), y = across_u ? at.uv.y() : at.uv.x();
  const double ylo = across_u ? d.v0 : d.u0, yhi = across_u ? d.v1 : d.u1;
  const double px = kEdgeNearRel * (hi - lo), py = kEdgeNearRel * (yhi - ylo);
  const bool on_edge = std::abs(x - lo) <= px || std::abs(x - hi) <= px;
  const bool on_cross_edge = std::abs(y - ylo) <= py || std::abs(y - yhi) <= py;
  if (!on_edge || on_cross_edge) return false;  // a pole, or a corner: see fan_fit
  const Vec2 axis = (std::abs(x - lo) <= px ? 1.0 : -1.0) * (across_u ? Vec2(1, 0) : Vec2(0, 1));
  const Vec3 along = (across_u ? e.dv : e.du).normalized();
  if (!along.allFinite()) return false;
  // The parameter steps width * 2^-j, j = 0, 1, ...: the chords to the surface there.
  const double len = reach > 0.0 ? reach : kProbeRel * surface.size();
  Vec3 probe = Vec3::Zero();
  SurfaceLocation start;
  bool have_start = false;
  const double dt_len = dt.norm();
  for (int j = 0; j < kSingularEdgeHalvings; ++j) {
    const SurfaceLocation q = at.with_uv(at.uv + std::ldexp(hi - lo, -j) * axis);
    const SurfaceEval1 eq = surface.eval1(q);
    if (!eq.ok) continue;
    Vec3 c = eq.p - e.p;
    c -= c.dot(n) * n + c.dot(along) * along;  // the inward part, in the tangent plane
    if (!have_start && c.norm() <= 0.5 * len) {
      start = q;
      have_start = true;
    }
    if (c.norm() <= kProbeRel * len && c.norm() > 0.0) {
      probe = c.normalized();
      break;
    }
  }
  if (!(probe.norm() > 0.0) || !(dt_len > 0.0)) return false;
  const double beta = dt.dot(probe) / dt_len;
  if (beta <= detail::kMinFanCos) {
    out.leaves_face = true;
    return true;
  }
  if (!have_start) return false;
  out.from_at = start;
  out.from_singular_edge = true;
  const SurfaceEval1 ef = surface.eval1(start);
  out.ok = ef.ok && metric_direction(ef, dt, out.dir_uv);
  return true;
}

}  // namespace

Vec3 face_normal(const DrapeSurface& s, const SurfaceLocation& at, const SurfaceEval1& e) {
  if (s.degenerate(at, e)) return s.normal(at).n;
  return s.orientation(at) * e.du.cross(e.dv).normalized();
}

bool metric_direction(const SurfaceEval1& e, const Vec3& dir, Vec2& a) {
  const Eigen::Matrix2d G = detail::metric(e);
  if (!(G(0, 0) > 0.0 || G(1, 1) > 0.0)) return false;
  a = detail::regularised_solve(G, detail::metric_rhs(e, dir), kSingularRel);
  const double len = (e.du * a.x() + e.dv * a.y()).norm();
  if (!(len > 0.0) || !a.allFinite()) return false;
  a /= len;
  return true;
}

UvDirection uv_direction_at(const DrapeSurface& surface, const SurfaceLocation& at,
                            const SurfaceEval1& e, const Vec3& n, const Vec3& dir, double reach) {
  UvDirection out;
  out.from_at = at;
  if (!e.ok) return out;
  const Vec3 dt = dir - dir.dot(n) * n;
  if (!(dt.norm() > 0.0)) return out;
  const Vec2 sp = surface.speeds(at);
  const Vec2& uv = at.uv;
  if (!surface.degenerate(at, e)) {
    out.ok = metric_direction(e, dt, out.dir_uv);
    return out;
  }
  if (singular_edge_direction(surface, at, e, n, dt, reach, out)) return out;
  // A pole: one derivative vanishes along a collapsed edge. Slide along that edge to the
  // parameter whose remaining derivative points best along dir.
  const bool v_collapsed = e.dv.norm() * sp.x() <= e.du.norm() * sp.y();
  const auto& d = surface.domain(at);
  Pole edge;
  edge.at = at;
  edge.u_fixed = v_collapsed;
  edge.lo = v_collapsed ? d.v0 : d.u0;
  edge.hi = v_collapsed ? d.v1 : d.u1;
  // The edge is left towards the interior: at the domain end the derivative flips sign.
  edge.inward = v_collapsed ? ((uv.x() <= 0.5 * (d.u0 + d.u1)) ? 1.0 : -1.0)
                            : ((uv.y() <= 0.5 * (d.v0 + d.v1)) ? 1.0 : -1.0);
  const detail::FanFit fit = detail::fan_fit(surface, edge, dt);
  if (fit.cos <= detail::kMinFanCos) {
    out.leaves_face = true;
    return out;
  }
  out.from_at = edge.on_edge(fit.t);
  const SurfaceEval1 ef = surface.eval1(out.from_at);
  const Vec3 gvec = v_collapsed ? ef.du : ef.dv;
  const double gn = gvec.norm();
  if (!(gn > 0.0)) return out;
  const double sgn = gvec.dot(dt) >= 0.0 ? 1.0 : -1.0;
  out.dir_uv = v_collapsed ? Vec2(sgn / gn, 0.0) : Vec2(0.0, sgn / gn);
  out.ok = true;
  return out;
}

Foot foot_near(const DrapeSurface& s, const SolverSettings& st, const Vec3& q, SurfaceLocation at,
               int& evaluations) {
  Foot out;
  SurfaceEval1 e = s.eval1(at);
  ++evaluations;
  if (!e.ok) return out;
  double phi = (e.p - q).squaredNorm();
  for (int it = 0; it < st.tol.newton_max_iterations; ++it) {
    const Vec3 r = e.p - q;
    Eigen::Matrix2d A;
    A << e.du.dot(e.du), e.du.dot(e.dv), e.du.dot(e.dv), e.dv.dot(e.dv);
    A(0, 0) += kLmDampingRel * A(0, 0);  // Marquardt: poles make A singular
    A(1, 1) += kLmDampingRel * A(1, 1);
    Vec2 step = -A.ldlt().solve(Vec2(e.du.dot(r), e.dv.dot(r)));
    if (!step.allFinite()) break;
    bool accepted = false;
    for (int h = 0; h <= st.tol.line_search_max_halvings; ++h, step *= 0.5) {
      const SurfaceLocation cand = s.locate(at, at.uv + step);
      if (!s.contains(cand)) continue;
      const SurfaceEval1 e2 = s.eval1(cand);
      ++evaluations;
      if (!e2.ok || !((e2.p - q).squaredNorm() < phi)) continue;
      at = cand;
      e = e2;
      phi = (e.p - q).squaredNorm();
      accepted = true;
      break;
    }
    if (!accepted) break;
  }
  out.at = s.wrap(at);
  out.p = e.p;
  out.n = face_normal(s, at, e);
  out.ok = true;
  return out;
}

SurfaceLocation continue_step(const DrapeSurface& s, const SurfaceLocation& a,
                              const SurfaceLocation& b) {
  if (s.same_chart(a, b)) return s.locate(b, b.uv + s.delta(a, b));
  return s.locate(b, b.uv - s.delta(b, a));
}

}  // namespace solvers

UvDirection uv_direction(const DrapeSurface& surface, const SurfaceLocation& at, const Vec3& dir) {
  const SurfaceEval1 e = surface.eval1(at);
  if (!e.ok) return {at, Vec2::Zero(), false};
  return solvers::uv_direction_at(surface, at, e, solvers::face_normal(surface, at, e), dir);
}

}  // namespace plyfit
