// Poles of a drape surface and the location of points near them (see poles.hpp).
#include "surface/poles.hpp"

#include "geometry/numeric.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// Samples and golden-section refinements when searching a collapsed edge for a direction.
constexpr int kEdgeSamples = 64;
constexpr int kEdgeRefinements = 30;
// A domain edge is collapsed (a pole) when its ends and middle lie within this fraction of the
// surface size of one another in 3D (Face::boundary()'s test of collapsed edges).
constexpr double kCollapsedEdgeRel = 1e-9;
// Gauss-Newton iterations that locate a point near a pole on the face.
constexpr int kPoleLocateIterations = 30;
// The Gauss-Newton normal matrix is regularised by this fraction of its diagonal (and a tiny
// absolute floor) so that a derivative vanishing at the pole leaves it invertible.
constexpr double kNormalRegRel = 1e-10;

}  // namespace

FanFit fan_fit(const DrapeSurface& surface, const Pole& e, const Vec3& dir) {
  const double dn = dir.norm();
  auto score = [&](double t) {
    const SurfaceEval1 eq = surface.eval1(e.on_edge(t));
    const Vec3& g = e.u_fixed ? eq.du : eq.dv;
    const double gn = g.norm();
    return (eq.ok && gn > 0.0 && dn > 0.0) ? e.inward * g.dot(dir) / (gn * dn) : -2.0;
  };
  const double lo = e.lo, hi = e.hi;
  double best_t = lo, best = -3.0;
  for (int k = 0; k <= kEdgeSamples; ++k) {
    const double t = lo + (hi - lo) * k / kEdgeSamples;
    const double sc = score(t);
    if (sc > best) {
      best = sc;
      best_t = t;
    }
  }
  // Golden-section refinement in the bracket around the best sample.
  double a = std::max(lo, best_t - (hi - lo) / kEdgeSamples);
  double b = std::min(hi, best_t + (hi - lo) / kEdgeSamples);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = score(x1), f2 = score(x2);
  for (int k = 0; k < kEdgeRefinements; ++k) {
    if (f1 > f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = score(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = score(x2);
    }
  }
  FanFit out;
  out.t = (f1 > best || f2 > best) ? (f1 > f2 ? x1 : x2) : best_t;
  out.cos = std::max({best, f1, f2});
  return out;
}

std::vector<Pole> find_poles(const DrapeSurface& s) {
  std::vector<Pole> out;
  const double tol = kCollapsedEdgeRel * s.size();
  for (std::int32_t f = 0; f < s.face_count(); ++f) {
    const SurfaceLocation chart(Vec2::Zero(), f);
    const ParamDomain& d = s.domain(chart);
    for (int k = 0; k < 4; ++k) {
      Pole p;
      p.u_fixed = k < 2;
      const bool end = k % 2 == 1;
      const double fixed = p.u_fixed ? (end ? d.u1 : d.u0) : (end ? d.v1 : d.v0);
      p.lo = p.u_fixed ? d.v0 : d.u0;
      p.hi = p.u_fixed ? d.v1 : d.u1;
      p.inward = end ? -1.0 : 1.0;
      const double mid = 0.5 * (p.lo + p.hi);
      p.at = chart.with_uv(p.u_fixed ? Vec2(fixed, mid) : Vec2(mid, fixed));
      const SurfaceEval1 a = s.eval1(p.on_edge(p.lo)), m = s.eval1(p.at),
                         b = s.eval1(p.on_edge(p.hi));
      if (!a.ok || !m.ok || !b.ok || (a.p - m.p).norm() + (b.p - m.p).norm() > tol) continue;
      p.point = m.p;
      out.push_back(p);
    }
  }
  return out;
}

std::optional<SurfaceLocation> locate_through_pole(const DrapeSurface& s, const Pole& e,
                                                   const Vec3& p, const Tolerances& tol) {
  // At the pole itself (to rounding) any point of the edge is p.
  const Vec3 w = p - e.point;
  if (w.norm() <= tol.roundoff_rel * (e.point.cwiseAbs().maxCoeff() + s.size())) return e.at;
  const FanFit fit = fan_fit(s, e, w);
  if (fit.cos <= kMinFanCos) return std::nullopt;
  SurfaceLocation at = e.on_edge(fit.t);
  SurfaceEval1 ev = s.eval1(at);
  const double gn = (e.u_fixed ? ev.du : ev.dv).norm();
  if (!ev.ok || !(gn > 0.0)) return std::nullopt;
  const double step = e.inward * (p - e.point).norm() / gn;
  at = at.with_uv(at.uv + (e.u_fixed ? Vec2(step, 0.0) : Vec2(0.0, step)));
  const ParamDomain& d = s.domain(at);
  auto clamp_in = [&](const Vec2& uv) {
    return s.wrap(at.with_uv(uv.cwiseMax(Vec2(d.u0, d.v0)).cwiseMin(Vec2(d.u1, d.v1))));
  };
  at = clamp_in(at.uv);
  ev = s.eval1(at);
  for (int it = 0; it < kPoleLocateIterations && ev.ok; ++it) {
    const Vec3 r = ev.p - p;
    const double rn = r.norm();
    if (rn == 0.0) break;
    Vec2 dx = -regularised_solve(metric(ev), metric_rhs(ev, r), kNormalRegRel);
    if (!dx.allFinite()) break;
    bool taken = false;
    for (int h = 0; h <= tol.line_search_max_halvings; ++h, dx *= 0.5) {
      const SurfaceLocation cand = clamp_in(at.uv + dx);
      const SurfaceEval1 ec = s.eval1(cand);
      if (ec.ok && (ec.p - p).norm() < rn) {
        at = cand;
        ev = ec;
        taken = true;
        break;
      }
    }
    if (!taken) break;
  }
  return at;
}

}  // namespace plyfit::detail
