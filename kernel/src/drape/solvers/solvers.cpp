#include "drape/solvers/solvers.hpp"

#include "geometry/numeric.hpp"
#include "surface/poles.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace plyfit {

namespace {

// A 2x2 Jacobian is treated as singular when |det| < kSingularRel * |col 0| * |col 1|; the
// step is then a Levenberg-Marquardt step with damping kLmDampingRel * diag(J^T J).
constexpr double kSingularRel = 1e-10;
constexpr double kLmDampingRel = 1e-8;
// Newton steps are capped at this many initial-step lengths in (u, v).
constexpr double kStepCapSteps = 10.0;
// The first-order model of a plane-sphere step is trusted when the surface point at the
// guess lies within kTrustRatio * rho of the intended point; otherwise, and after a failed
// solve, the solver marches along the curve in kMarchSteps sub-steps.
constexpr double kTrustRatio = 0.5;
constexpr int kMarchSteps[] = {4, 16};
// An iterate where a first derivative of the surface vanishes (a pole, or an edge along
// which the derivative across it vanishes: a degenerate parametrisation of a regular
// surface) has a zero Jacobian column, and neither Newton nor Levenberg-Marquardt can move
// it in that parameter. It is moved into the domain by this fraction of the domain's width in
// that parameter, at most kMaxNudges times per solve.
constexpr double kNudgeRel = 1e-6;
constexpr int kMaxNudges = 4;
// A step from a degenerate edge that is no pole (see singular_edge_direction) is told into
// or off the face by the chord to the surface across the edge, of this fraction of the
// step's length, found among parameter steps halved at most kSingularEdgeHalvings times.
constexpr double kProbeRel = 1e-3;
constexpr int kSingularEdgeHalvings = 60;
// A degenerate point lies on a domain edge when within this fraction of the domain's width
// of it (a start projected onto the edge lands within rounding of it, or a hair inside).
constexpr double kEdgeNearRel = 1e-6;
// Sine of the angle between base plane and tangent plane below which the plane is taken
// as tangent to the surface (no intersection curve direction).
constexpr double kTangentPlaneSin = 1e-6;
// A solution off its face is solved again on a face within this fraction of d of it (3D),
// from the point's projection there (DrapeSurface::settle).
constexpr double kSettleReachRel = 0.1;
// The two-sphere fallback across creases samples this many points on each quarter of the
// spheres' circle of intersection (the requested side's half first, then the other half:
// where the normals at a and b disagree, at a pinch of the face, "the requested side" of the
// circle may hold no solution while the other does, on the requested branch) and bisects
// the sign change for at most this many steps;
// a circle smaller than kCircleMinRel of the radii (the spheres just touch) is not tried.
constexpr int kCircleSamples = 8;
constexpr int kCircleIterations = 100;
// A plane-sphere step that no march solves is outside when the plane's and the sphere's
// circle of intersection, sampled at this many points, passes the face at a distance.
constexpr int kSectionSamples = 64;
constexpr double kCircleMinRel = 1e-6;
// A sign change of the signed distance on that circle holds a crossing of the surface only
// where the circle's point found in it lies within this fraction of the circle's radius of
// the face (or within eq. (9)'s tolerance): not where the nearest point is on a face edge.
constexpr double kCircleNearRel = 1e-3;
// A base-path step that neither the direct solve nor the march solves is traced along the
// plane's section of the surface (see trace_section): steps of kTraceStepRel of the link
// at first, halved while the section's tangent turns by more than kTraceTurnMax radians in
// one step or Newton fails, down to kTraceMinStepRel of the link; at most kTraceMaxSteps
// steps. The section ends where the plane comes within kSectionEndSin (the sine of the angle)
// of the surface's tangent plane: a point where the section stops, or crosses itself.
constexpr double kTraceStepRel = 1.0 / 8.0;
constexpr double kTraceMinStepRel = 1.0 / 4096.0;
constexpr double kTraceTurnMax = 0.35;
constexpr int kTraceMaxSteps = 512;
constexpr double kSectionEndSin = 1e-3;
// Two solutions of one plane-sphere step are distinct when they lie further apart than this
// fraction of the radius (the forward and backward ones lie about two radii apart).
constexpr double kDistinctSolutionRel = 0.5;
// A Newton step proposing to leave the domain margin this many times in a row, from an
// iterate already past the domain edge, ends the solve with "left the face".
constexpr int kOutsideStrikes = 2;
// The two-sphere solver tells the sides of the line a-b apart sideways, across the mean of
// the normals at a and b, while that mean (of two unit normals) is at least this long: the
// normals turn by less than about 174 degrees between a and b.
constexpr double kMeanNormalMin = 0.1;

Vec3 face_normal(const DrapeSurface& s, const SurfaceLocation& at, const SurfaceEval1& e) {
  // The limit normal at poles, else the normalised cross product with the face orientation.
  if (s.degenerate(at, e)) return s.normal(at).n;
  return s.orientation(at) * e.du.cross(e.dv).normalized();
}

// Least-squares (u, v) direction a with J a = dir_t, scaled to |J a| = 1.
bool metric_direction(const SurfaceEval1& e, const Vec3& dir, Vec2& a) {
  const Eigen::Matrix2d G = detail::metric(e);
  if (!(G(0, 0) > 0.0 || G(1, 1) > 0.0)) return false;
  a = detail::regularised_solve(G, detail::metric_rhs(e, dir), kSingularRel);
  const double len = (e.du * a.x() + e.dv * a.y()).norm();
  if (!(len > 0.0) || !a.allFinite()) return false;
  a /= len;
  return true;
}

// Parameter-space lengths are measured in "scaled" units, (du * speed_u, dv * speed_v),
// speed = the face's characteristic |dS/du|, |dS/dv|: about model units, and invariant
// to reparametrising u or v by a constant factor.
struct Ctx {
  Ctx(const DrapeSurface& surface, const SolverSettings& settings) : s(surface), st(settings) {}
  const DrapeSurface& s;
  const SolverSettings& st;
  double eps = 0.0;        // residual tolerance (model units)
  SurfaceLocation anchor;  // the known point the step starts from
  double margin = 0.0;     // allowed excursion past the domain, scaled units
  double max_step = 0.0;   // Newton step cap, scaled units
  SolveResult res;
  SurfaceEval1 last;  // evaluation at the last Newton iterate (the solution if converged)
  // Length of a parameter step of face `face`.
  double scaled_norm(const SurfaceLocation& chart, const Vec2& duv) const {
    return duv.cwiseProduct(s.speeds(chart)).norm();
  }
  bool within_margin(const SurfaceLocation& at) const {
    const SurfaceLocation w = s.wrap(at);  // closed directions come back inside
    const Vec2 sp = s.speeds(w);
    return s.domain(w).contains(w.uv.x(), w.uv.y(), margin / sp.x(), margin / sp.y());
  }
};

// A Newton solve that ends unconverged (for `why`) at `at`: failed, or left the face where
// that iterate lies past its face's domain edge (the surface extended past a free edge, where
// the residual has no zero near the face: the cloth leaves the face there).
void stop_unconverged(Ctx& c, const SurfaceLocation& at, const Vec3& p, double r, const char* why) {
  c.res.at = c.s.wrap(at);
  c.res.point = p;
  c.res.residual = r;
  const bool past_edge = !c.s.domain(c.res.at).contains(c.res.at.uv.x(), c.res.at.uv.y());
  c.res.status = past_edge ? SolveStatus::kLeftFace : SolveStatus::kFailed;
  c.res.reason = past_edge ? "iterate" : why;
}

// Newton-Raphson on (u, v) for the residual functor resid(e, f, J) (f in model units).
// Returns true on convergence (|f1| + |f2| < eps); fills ctx.res with the point, counts and,
// on failure, status and reason.
template <class Resid>
bool newton(Ctx& c, SurfaceLocation at, Resid&& resid) {
  const int max_it = c.st.tol.newton_max_iterations;
  SurfaceEval1 e = c.s.eval1(at);
  ++c.res.evaluations;
  // A guess where the surface is undefined or beyond the margin is pulled back towards the
  // known point.
  for (int h = 0; h < c.st.tol.line_search_max_halvings && (!e.ok || !c.within_margin(at)); ++h) {
    at = c.s.locate(c.anchor, c.anchor.uv + 0.5 * c.s.delta(c.anchor, at));
    e = c.s.eval1(at);
    ++c.res.evaluations;
  }
  if (!e.ok) {
    c.res.status = SolveStatus::kLeftFace;
    c.res.reason = "iterate";
    return false;
  }
  Vec2 f;
  Eigen::Matrix2d J;
  resid(e, f, J);
  double r = f.cwiseAbs().sum();
  int outside_strikes = 0, nudges = 0;
  for (int it = 0;; ++it) {
    if (!(r == r) || !f.allFinite()) break;  // defensive: never iterate on NaN
    if (r < c.eps) {
      c.res.at = c.s.wrap(at);
      c.res.point = e.p;
      c.res.residual = r;
      c.res.iterations += it;
      c.last = e;
      return true;
    }
    if (it >= max_it) {
      c.res.iterations += it;
      stop_unconverged(c, at, e.p, r, "no convergence within the iteration cap");
      return false;
    }
    // Newton step, or Levenberg-Marquardt where the Jacobian is (nearly) singular. Both are
    // invariant to scaling u or v: |det| is compared with the product of the column norms
    // (the sine of the angle between the columns), and the damping is Marquardt's diagonal.
    const double c0 = J.col(0).norm(), c1 = J.col(1).norm();
    const double det = J.determinant();
    Vec2 step;
    if (std::abs(det) > kSingularRel * c0 * c1) {
      step = -(Eigen::Matrix2d() << J(1, 1), -J(0, 1), -J(1, 0), J(0, 0)).finished() * f / det;
    } else {
      Eigen::Matrix2d A = J.transpose() * J;
      const Vec2 D(std::max(A(0, 0), 1e-300), std::max(A(1, 1), 1e-300));
      A(0, 0) += kLmDampingRel * D.x();
      A(1, 1) += kLmDampingRel * D.y();
      step = -A.inverse() * (J.transpose() * f);
    }
    if ((!step.allFinite() || !(c0 > 0.0 && c1 > 0.0)) && nudges < kMaxNudges) {
      // A vanishing derivative (a zero column): the iterate is moved off the point along that
      // parameter, into the domain, where the derivative no longer vanishes.
      const SurfaceLocation w = c.s.wrap(at);
      const ParamDomain& d = c.s.domain(w);
      Vec2 uv = w.uv;
      if (!(c0 > 0.0)) uv.x() += kNudgeRel * d.width_u() * (uv.x() < 0.5 * (d.u0 + d.u1) ? 1 : -1);
      if (!(c1 > 0.0)) uv.y() += kNudgeRel * d.width_v() * (uv.y() < 0.5 * (d.v0 + d.v1) ? 1 : -1);
      const SurfaceEval1 e2 = c.s.eval1(w.with_uv(uv));
      ++c.res.evaluations;
      ++nudges;
      if (e2.ok && (c0 > 0.0 || c1 > 0.0)) {
        at = w.with_uv(uv);
        e = e2;
        resid(e, f, J);
        r = f.cwiseAbs().sum();
        continue;
      }
    }
    if (!step.allFinite() || !(c0 + c1 > 0.0)) {
      c.res.iterations += it;
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "degenerate Jacobian";
      return false;
    }
    const double sn = c.scaled_norm(at, step);
    if (sn > c.max_step) step *= c.max_step / sn;
    if (!c.within_margin(c.s.locate(at, at.uv + step))) {
      // Only an iterate already past the domain edge, still pushed further out, has left;
      // an overshoot from inside is nonlinearity, and the line search shortens it.
      const SurfaceLocation w = c.s.wrap(at);
      const bool past_edge = !c.s.domain(w).contains(w.uv.x(), w.uv.y());
      if (++outside_strikes >= kOutsideStrikes && past_edge) {
        c.res.iterations += it + 1;
        c.res.status = SolveStatus::kLeftFace;
        c.res.reason = "iterate";
        c.res.at = c.s.wrap(at);
        c.res.point = e.p;
        c.res.residual = r;
        return false;
      }
    } else {
      outside_strikes = 0;
    }
    // Backtracking line search on |f|^2, staying within the margin.
    const double phi = f.squaredNorm();
    bool accepted = false;
    for (int h = 0; h <= c.st.tol.line_search_max_halvings; ++h, step *= 0.5) {
      const SurfaceLocation cand = c.s.locate(at, at.uv + step);
      if (!c.within_margin(cand)) continue;
      const SurfaceEval1 e2 = c.s.eval1(cand);
      ++c.res.evaluations;
      if (!e2.ok) continue;
      Vec2 f2;
      Eigen::Matrix2d J2;
      resid(e2, f2, J2);
      if (f2.squaredNorm() < phi) {
        at = cand;
        e = e2;
        f = f2;
        J = J2;
        r = f.cwiseAbs().sum();
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      c.res.iterations += it + 1;
      stop_unconverged(c, at, e.p, r, "no intersection (the residual stopped decreasing)");
      return false;
    }
  }
  c.res.status = SolveStatus::kFailed;
  c.res.reason = "non-finite residual";
  return false;
}

// Tolerance of eq. (9): relative to d, floored at the rounding level of the residual
// (residual_floor).
double residual_tolerance(const DrapeSurface& s, const SolverSettings& st, const Vec3& where,
                          double radius) {
  return std::max(st.tol.newton_residual_rel * st.spacing,
                  residual_floor(s, st.tol, where, radius));
}

// A solve that converged off its face: solved again from the location where the surface
// holds its point (DrapeSurface::settle: past a pole of the face, the face itself; on a
// shell, a neighbour face). c.res changes only if that solve converges on the surface; the
// iterations and evaluations count either way. Called right after Newton converged, before
// any test that uses the normal there (past a pole the extended face's orientation flips).
template <class Resid>
void settle(Ctx& c, Resid&& resid) {
  if (c.s.contains(c.res.at)) return;
  const SurfaceLocation other = c.s.settle(c.res.at, c.res.point, kSettleReachRel * c.st.spacing);
  if (other == c.res.at) return;
  const SolveResult before = c.res;
  const SurfaceEval1 last = c.last;
  if (newton(c, other, resid) && c.s.contains(c.res.at)) return;
  const int iterations = c.res.iterations, evaluations = c.res.evaluations;
  c.res = before;
  c.last = last;
  c.res.iterations = iterations;
  c.res.evaluations = evaluations;
}

// Finishes a converged solve (settled already, see settle()): in-face test (one contains()
// query). A solution a hair past a domain edge (a path along the edge, a node on it, or a
// pole reached from the extension beyond it) is on the face if the same point with the
// parameters clamped to the domain is a solution too: within eq. (9)'s tolerance of the
// point found, or the same parameters (Tolerances::param_rel: a node on the edge, found a
// rounding past it, where the rounding of the net it is solved from has carried it).
void classify_converged(Ctx& c) {
  if (c.s.contains(c.res.at)) {
    c.res.status = SolveStatus::kConverged;
    return;
  }
  const auto& d = c.s.domain(c.res.at);
  const Vec2& uv = c.res.at.uv;
  const SurfaceLocation clamped =
      c.res.at.with_uv(Vec2(std::clamp(uv.x(), d.u0, d.u1), std::clamp(uv.y(), d.v0, d.v1)));
  if (clamped != c.res.at && c.s.contains(clamped)) {
    const SurfaceEval1 e = c.s.eval1(clamped);
    ++c.res.evaluations;
    const Vec2 moved = (clamped.uv - uv).cwiseAbs();
    const bool same = moved.x() <= c.st.tol.param_rel * d.width_u() &&
                      moved.y() <= c.st.tol.param_rel * d.width_v();
    if (e.ok && (same || (e.p - c.res.point).norm() < c.eps)) {
      c.res.at = clamped;
      c.res.point = e.p;
      c.res.status = SolveStatus::kConverged;
      return;
    }
  }
  {
    c.res.status = SolveStatus::kLeftFace;
    c.res.extended = true;
    c.res.reason = "outside";
  }
}

// Margin and step cap from the length of the first step (scaled units).
void setup_margins(Ctx& c, const SurfaceLocation& from, const SurfaceLocation& guess) {
  c.anchor = from;
  const double step = std::max(c.scaled_norm(from, c.s.delta(from, guess)), 1e-300);
  c.margin = c.st.tol.extension_steps * step;
  c.max_step = kStepCapSteps * step;
}

// The point of the surface nearest q, by Gauss-Newton on |S(u, v) - q|^2 from `at` through
// DrapeSurface::locate (so across a shell's shared edges), staying on the surface (contains):
// at a crease or a free edge it stops on the edge, which is then the nearest point.
struct Foot {
  SurfaceLocation at;
  Vec3 p = Vec3::Zero();
  Vec3 n = Vec3::UnitZ();
  bool ok = false;
};
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

}  // namespace

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::kConverged:
      return "converged";
    case SolveStatus::kLeftFace:
      return "left_face";
    case SolveStatus::kShearLimit:
      return "shear_limit";
    case SolveStatus::kFailed:
      return "failed";
  }
  return "failed";
}

// The rounding level of a residual is set by the coordinates involved, the face's size (a
// point at the origin of a 40 mm saddle is still evaluated to a few ulps of 40 mm) and the
// surface's own evaluation rounding (the sums over its poles, and the spacing of the doubles
// near its parameters, which on a cylinder whose v runs from 1e5 mm leaves no point closer
// than 1.5e-11 mm to the solution).
double residual_floor(const DrapeSurface& s, const Tolerances& tol, const Vec3& where,
                      double radius) {
  return tol.roundoff_rel * (where.cwiseAbs().maxCoeff() + s.size() + radius) + s.rounding();
}

const char* to_string(ShearStop s) {
  switch (s) {
    case ShearStop::kNone:
      return "none";
    case ShearStop::kLock:
      return "lock";
    case ShearStop::kFoldAngle:
      return "fold_angle";
    case ShearStop::kFlatCell:
      return "flat_cell";
    case ShearStop::kCellFolds:
      return "cell_folds";
    case ShearStop::kBehindStop:
      return "behind_stop";
  }
  return "none";
}

Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - c);
}

namespace {

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

// uv_direction with the evaluation e and the face normal n at uv already known; `reach` is
// the length of the step to be taken (see singular_edge_direction), 0 if unknown.
UvDirection uv_direction_at(const DrapeSurface& surface, const SurfaceLocation& at,
                            const SurfaceEval1& e, const Vec3& n, const Vec3& dir,
                            double reach = 0.0) {
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

}  // namespace

UvDirection uv_direction(const DrapeSurface& surface, const SurfaceLocation& at, const Vec3& dir) {
  const SurfaceEval1 e = surface.eval1(at);
  if (!e.ok) return {at, Vec2::Zero(), false};
  return uv_direction_at(surface, at, e, face_normal(surface, at, e), dir);
}

namespace {

// The base plane's section of the surface traced forward from x0 (a known point of it, with
// the section's unit tangent t there), by arc length: a step h along the tangent, then Newton
// back onto the plane, on the plane through the predicted point square to the tangent (which
// needs no monotone distance from x0, so it goes round the section's turns where the
// plane-sphere march, stepping in that distance, stops). Used where the plane-sphere solve
// failed: the plane nearly touches the surface ahead, and its section turns tightly or closes.
// Returns
// - the solution, where the traced section reaches distance rho from x0 (the first point of
//   the section going forward at that distance, Newton on the plane and the sphere from the
//   bracketing traced points), classified as any solve (on the face, or past it);
// - kFailed with section_ends, where the section turns back towards x0 (its distance from x0
//   decreases) before reaching rho, or reaches a point where the plane touches the surface:
//   no forward point exists, the path ends there;
// - kLeftFace "outside", where the traced section leaves the face (past its edge, not into one
//   of its holes) before reaching rho;
// - nothing where the trace could not go on (Newton failing at the smallest step).
std::optional<SolveResult> trace_section(const DrapeSurface& s, const Vec3& x0,
                                         const SurfaceLocation& at0, const Vec3& pn, Vec3 t,
                                         double rho, const SolverSettings& st) {
  Ctx c(s, st);
  c.eps = residual_tolerance(s, st, x0, rho);
  SurfaceLocation at = at0;
  Vec3 p = x0;
  double chord = 0.0;
  double h = kTraceStepRel * rho;
  const double h_min = kTraceMinStepRel * rho;
  auto ends = [&](const char* reason) {
    SolveResult r;
    r.status = SolveStatus::kFailed;
    r.section_ends = true;
    r.reason = reason;
    r.iterations = c.res.iterations;
    r.evaluations = c.res.evaluations;
    return r;
  };
  auto outside = [&]() {
    SolveResult r;
    r.status = SolveStatus::kLeftFace;
    r.reason = "outside";
    r.iterations = c.res.iterations;
    r.evaluations = c.res.evaluations;
    return r;
  };
  for (int step = 0; step < kTraceMaxSteps; ++step) {
    const SurfaceEval1 e = s.eval1(at);
    ++c.res.evaluations;
    if (!e.ok) return std::nullopt;
    const Vec3 n = face_normal(s, at, e);
    Vec3 tn = n.cross(pn);
    if (!(tn.norm() > kSectionEndSin))
      return ends("the step's plane touches the surface ahead: its section ends within one link");
    tn.normalize();
    if (tn.dot(t) < 0.0) tn = -tn;
    Vec2 dir_uv;
    if (!metric_direction(e, tn, dir_uv)) return std::nullopt;
    const Vec3 q = p + h * tn;
    auto resid = [&](const SurfaceEval1& ev, Vec2& f, Eigen::Matrix2d& J) {
      f << pn.dot(ev.p - x0), tn.dot(ev.p - q);
      J << pn.dot(ev.du), pn.dot(ev.dv), tn.dot(ev.du), tn.dot(ev.dv);
    };
    const SurfaceLocation guess = s.locate(at, at.uv + h * dir_uv);
    setup_margins(c, at, guess);
    bool converged = newton(c, guess, resid);
    if (!converged) {
      // From the predicted point's nearest point of the face (no step cap: across a band of
      // the parameters where the surface barely moves, a CAD patch's collapsed strip, which
      // Newton's capped steps crawl into and stall at).
      const Foot fq = foot_near(s, st, q, at, c.res.evaluations);
      if (fq.ok && fq.at != at && (fq.p - q).norm() < h) {
        setup_margins(c, at, fq.at);
        converged = newton(c, fq.at, resid);
      }
    }
    Vec3 t_next = tn;
    bool sharp = false;
    if (converged) {
      Vec3 tt = face_normal(s, c.res.at, c.last).cross(pn);
      if (tt.norm() > kSectionEndSin) {
        tt.normalize();
        t_next = tt.dot(tn) < 0.0 ? Vec3(-tt) : tt;
      }
      sharp = std::acos(std::clamp(t_next.dot(tn), -1.0, 1.0)) > kTraceTurnMax;
    }
    if (!converged || (sharp && h > h_min)) {
      if (h > h_min) {
        h *= 0.5;
        continue;
      }
      // Newton fails at the smallest step: off the face's margin, outside; else unknown.
      if (c.res.status == SolveStatus::kLeftFace) return outside();
      return std::nullopt;
    }
    // (A turn sharper than kTraceTurnMax at the smallest step is a corner of the section, at
    // a crease of a shell: stepped over; whether it turns back the distance from x0 tells.)
    const SurfaceLocation at_next = c.res.at;
    const Vec3 p_next = c.res.point;
    // Past the face's edge (not into a hole of it, under which the path goes on) the section
    // has left the face before reaching rho: outside, as the march finds at an edge.
    if (!s.contains(at_next) && !s.in_hole(at_next)) return outside();
    const double chord_next = (p_next - x0).norm();
    if (chord_next >= rho) {
      // The section passes distance rho between p and p_next: solve there.
      const double w = (rho - chord) / std::max(chord_next - chord, 1e-300);
      const SurfaceLocation g = s.locate(at, at.uv + w * s.delta(at, at_next));
      auto sphere = [&](const SurfaceEval1& ev, Vec2& f, Eigen::Matrix2d& J) {
        const Vec3 r = ev.p - x0;
        f << pn.dot(r), (r.squaredNorm() - rho * rho) / (2 * rho);
        J << pn.dot(ev.du), pn.dot(ev.dv), r.dot(ev.du) / rho, r.dot(ev.dv) / rho;
      };
      setup_margins(c, at, g);
      if (newton(c, g, sphere) && (c.res.point - p).norm() <= 2.0 * (p_next - p).norm()) {
        settle(c, sphere);
        classify_converged(c);
        return c.res;
      }
      if (h <= h_min) return std::nullopt;
      h *= 0.5;  // trace closer to the crossing and try again
      c.res.status = SolveStatus::kFailed;
      continue;
    }
    if (chord_next < chord)
      return ends(
          "the section of the step's plane turns back within one link (the plane nearly "
          "touches the surface ahead)");
    at = at_next;
    p = p_next;
    chord = chord_next;
    t = t_next;
    h = std::min(2.0 * h, kTraceStepRel * rho);
  }
  return std::nullopt;
}

// Plane through x0 with unit normal `pn`, sphere of radius `rho` about x0, surface; the
// solution going forward along the unit tangent `t` (which lies in the plane). Solvers 1
// and 3 are this problem with different planes.
// The point beyond `b` continuing the parameter step a -> b, in b's chart.
SurfaceLocation continue_step(const DrapeSurface& s, const SurfaceLocation& a,
                              const SurfaceLocation& b) {
  if (s.same_chart(a, b)) return s.locate(b, b.uv + s.delta(a, b));
  return s.locate(b, b.uv - s.delta(b, a));
}

SolveResult plane_sphere_core(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0,
                              const SurfaceEval1& e0, const Vec3& n0, const Vec3& pn, const Vec3& t,
                              double rho, const SolverSettings& st, bool trace = false) {
  Ctx c(s, st);
  const UvDirection ud = uv_direction_at(s, at0, e0, n0, t, rho);
  if (ud.leaves_face) {
    c.res.status = SolveStatus::kLeftFace;
    c.res.reason =
        "the step leaves the face at a degenerate edge (a pole, or a singular parametrisation)";
    return c.res;
  }
  if (!ud.ok) {
    c.res.reason = "no tangent direction at the known point";
    return c.res;
  }
  c.eps = residual_tolerance(s, st, x0, rho);
  double rad = rho;
  auto resid = [&](const SurfaceEval1& e, Vec2& f, Eigen::Matrix2d& J) {
    const Vec3 r = e.p - x0;
    f << pn.dot(r), (r.squaredNorm() - rad * rad) / (2 * rad);
    J << pn.dot(e.du), pn.dot(e.dv), r.dot(e.du) / rad, r.dot(e.dv) / rad;
  };
  // True if the converged solution is not the backward one: the backward solution is the one
  // Newton reaches from the first-order guess behind x0 (at -t). Only asked where the solution
  // lies behind x0's tangent plane section, which the forward one does past a crease sharper
  // than 90 degrees (a path over a thin flange's edge).
  auto distinct_from_backward = [&]() {
    Ctx b(s, st);
    b.eps = c.eps;
    const SurfaceLocation g = s.locate(ud.from_at, ud.from_at.uv - rad * ud.dir_uv);
    setup_margins(b, ud.from_at, g);
    const bool ok = newton(b, g, resid);
    c.res.evaluations += b.res.evaluations;
    return ok && (b.res.point - x0).dot(t) < 0.0 &&
           (b.res.point - c.res.point).norm() > kDistinctSolutionRel * rad;
  };
  // One Newton solve for radius `rad` from `guess`; true if it converged forward.
  auto solve_from = [&](const SurfaceLocation& guess) {
    setup_margins(c, ud.from_at, guess);
    if (!newton(c, guess, resid)) return false;
    settle(c, resid);
    if ((c.res.point - x0).dot(t) > 0.0 || distinct_from_backward()) return true;
    c.res.status = SolveStatus::kFailed;
    c.res.reason = "converged backwards";
    return false;
  };
  // Direct attempt from the first-order guess (eqs. 7-8).
  const SurfaceLocation guess = s.locate(ud.from_at, ud.from_at.uv + rho * ud.dir_uv);
  // From a singular edge into the face, a solution past the edge is no continuation of the
  // curve (the direct guess lies far across the edge, where other solutions may be): the
  // march decides.
  if (solve_from(guess)) {
    classify_converged(c);
    if (!(ud.from_singular_edge && c.res.status == SolveStatus::kLeftFace)) return c.res;
  }
  // Leaving the face is the answer when the first-order model is trustworthy: the surface
  // point at the guess is close to the intended 3D point.
  if (c.res.status == SolveStatus::kLeftFace && !ud.from_singular_edge) {
    const SurfaceEval1 eg = s.eval1(guess);
    ++c.res.evaluations;
    if (eg.ok && (eg.p - (x0 + rho * t)).norm() <= kTrustRatio * rho) return c.res;
  }
  // With `trace` (the base path, solver 3), the section traced from x0 (trace_section), its
  // counts added to those of the solve so far; nothing without it or where it has no verdict.
  auto traced = [&](const SolveResult& so_far) {
    std::optional<SolveResult> tr;
    if (trace) tr = trace_section(s, x0, at0, pn, t, rho, st);
    if (tr) {
      tr->iterations += so_far.iterations;
      tr->evaluations += so_far.evaluations;
    }
    return tr;
  };
  // Otherwise march along the intersection curve: radius rho k / K, k = 1..K, each guess
  // extrapolated from the previous two solutions.
  const SolveResult first = c.res;
  for (int K : kMarchSteps) {
    // From a singular edge, the first sub-step starts where the metric models it.
    const UvDirection uk = ud.from_singular_edge ? uv_direction_at(s, at0, e0, n0, t, rho / K) : ud;
    if (!uk.ok) continue;
    SurfaceLocation prev = uk.from_at, prev2 = uk.from_at, g = uk.from_at;
    bool ok = true;
    for (int k = 1; k <= K && ok; ++k) {
      rad = rho * k / K;
      g = k == 1 ? s.locate(uk.from_at, uk.from_at.uv + rad * uk.dir_uv)
                 : continue_step(s, prev2, prev);
      ok = solve_from(g);
      if (ok) {
        prev2 = prev;
        prev = c.res.at;
      }
    }
    if (ok) {
      classify_converged(c);
      return c.res;
    }
    // A sub-step that fails where the curve, at the last sub-step or continued from it, is
    // already off the face ends the march: the node is outside. (Its iterate left the margin, or
    // Newton stalled on the surface extended past a domain edge, which need not go on.)
    // Otherwise try finer sub-steps.
    if (!s.contains(g) || (prev != uk.from_at && !s.contains(prev))) {
      if (auto tr = traced(c.res)) return *tr;
      c.res.status = SolveStatus::kLeftFace;
      c.res.extended = false;
      c.res.reason = "outside";
      return c.res;
    }
  }
  SolveResult out = first;
  out.iterations = c.res.iterations;
  out.evaluations = c.res.evaluations;
  // The base path: the plane's section traced forward tells a section that turns back or
  // closes within rho (the path ends) from one that leaves the face (outside), and finds the
  // point where the section turns too tightly for the march.
  if (auto tr = traced(out)) return *tr;
  // No point of the face lies on the circle where the plane meets the sphere when each of
  // kSectionSamples points on it lies further from the face than the longest distance from a
  // point of the circle to the nearest sample (their nearest points of the face found from
  // the last one and from x0): the plane section through x0 closes, or leaves the face,
  // within rho of it (a face narrower than the step). The step has no place on the face: the
  // node is outside.
  const Vec3 w = pn.cross(t);
  const double reach = 2.0 * rho * std::sin(kPi / (2.0 * kSectionSamples));
  SurfaceLocation seed = at0;
  bool misses = true;
  for (int k = 0; k < kSectionSamples && misses; ++k) {
    const double th = 2.0 * kPi * k / kSectionSamples;
    const Vec3 q = x0 + rho * (std::cos(th) * t + std::sin(th) * w);
    Foot f = foot_near(s, st, q, seed, out.evaluations);
    if (seed != at0) {
      const Foot g = foot_near(s, st, q, at0, out.evaluations);
      if (g.ok && (!f.ok || (g.p - q).norm() < (f.p - q).norm())) f = g;
    }
    misses = f.ok && (f.p - q).norm() > reach;
    seed = f.at;
  }
  if (misses) {
    out.status = SolveStatus::kLeftFace;
    out.extended = false;
    out.reason = "outside";
  }
  return out;
}

}  // namespace

SolveResult solve_base_path(const DrapeSurface& s, const BasePathStep& step,
                            const SolverSettings& st) {
  SolveResult bad;
  const Vec3 pn = step.plane_normal.normalized();
  const Vec3 fwd = step.forward.normalized();
  if (!pn.allFinite() || !fwd.allFinite() || !(step.distance > 0.0)) {
    bad.reason = "invalid base-path step";
    return bad;
  }
  // Tangent of the plane/surface intersection curve at x0, oriented forward: the exact
  // first-order direction of the path (eqs. 7-8 project the previous direction instead,
  // which is used where the plane is tangent to the surface).
  const SurfaceEval1 e0 = s.eval1(step.from_at);
  if (!e0.ok) {
    bad.reason = "the known point is not on the surface";
    return bad;
  }
  const Vec3 n0 = face_normal(s, step.from_at, e0);
  Vec3 t = n0.cross(pn);
  if (t.norm() > kTangentPlaneSin) {
    t.normalize();
    if (t.dot(fwd) < 0) t = -t;
  } else {
    t = (fwd - fwd.dot(pn) * pn).normalized();
  }
  SolveResult r =
      plane_sphere_core(s, step.from, step.from_at, e0, n0, pn, t, step.distance, st, true);
  ++r.evaluations;
  return r;
}

SolveResult solve_plane_sphere(const DrapeSurface& s, const PlaneSphereStep& step,
                               const SolverSettings& st) {
  SolveResult bad;
  if (!(step.radius > 0.0) || !step.direction.allFinite()) {
    bad.reason = "invalid plane-sphere step";
    return bad;
  }
  const SurfaceEval1 e0 = s.eval1(step.center_at);
  if (!e0.ok) {
    bad.reason = "the known point is not on the surface";
    return bad;
  }
  const Vec3 n = face_normal(s, step.center_at, e0);
  Vec3 t = step.direction - step.direction.dot(n) * n;
  if (!(t.norm() > 0.0)) {
    bad.reason = "the step direction is normal to the surface";
    return bad;
  }
  t.normalize();
  SolveResult r = plane_sphere_core(s, step.center, step.center_at, e0, n, n.cross(t), t,
                                    step.radius, st, true);
  ++r.evaluations;
  return r;
}

Vec2 two_sphere_guess(const DrapeSurface& s, const SurfaceLocation& a_at,
                      const SurfaceLocation& a_prev_at, const Vec3& a, const Vec3& a_prev,
                      double ra, const SurfaceLocation& b_at, const SurfaceLocation& b_prev_at,
                      const Vec3& b, const Vec3& b_prev, double rb) {
  // Eq. (10): each thread continued from its last node by its rest length, the (u, v)
  // gradient scaled by the (u, v) per 3D length ratio of the previous segment (eq. 8).
  const double la = (a - a_prev).norm(), lb = (b - b_prev).norm();
  const Vec2 pa = a_at.uv + s.delta(a_prev_at, a_at) * (la > 0 ? ra / la : 0.0);
  const Vec2 pb = b_at.uv + s.delta(b_prev_at, b_at) * (lb > 0 ? rb / lb : 0.0);
  // Eq. (11): the mean, taken the short way across seams.
  return pa + 0.5 * s.delta(a_at.with_uv(pa), a_at.with_uv(pb));
}

SolveResult solve_two_spheres(const DrapeSurface& s, const TwoSphereStep& step,
                              const SolverSettings& st) {
  Ctx c(s, st);
  const double L = (step.b - step.a).norm();
  if (!(step.ra > 0.0) || !(step.rb > 0.0) || !(L > 0.0)) {
    c.res.reason = "invalid two-sphere step";
    return c.res;
  }
  if (L > step.ra + step.rb) {
    c.res.reason = "no intersection (the spheres do not meet)";
    // The thread angle would have to pass pi: beyond any gamma_max (eq. 12).
    if (st.gamma_min > 0.0) {
      c.res.status = SolveStatus::kShearLimit;
      c.res.shear_stop = ShearStop::kLock;
      c.res.thread_angle = kPi;
      c.res.reason = "thread angle beyond the shear limit (the spheres do not meet)";
    }
    return c.res;
  }
  const Vec3 a = step.a, b = step.b;
  const double ra = step.ra, rb = step.rb;
  const double want = step.side >= 0 ? 1.0 : -1.0;
  // Planar two-circle solution in the tangent plane at `from` (a or b), on the requested
  // side: a 3D target on the right branch by construction.
  auto planar_target = [&](const SurfaceLocation& at, const SurfaceEval1& ea, Vec3& p3,
                           Vec3& n_out) {
    if (!ea.ok) return false;
    const Vec3 n = face_normal(s, at, ea);
    Vec3 e = b - a;
    e -= e.dot(n) * n;
    const double le = e.norm();
    if (!(le > 0.0)) return false;
    e /= le;
    const double x = (le * le + ra * ra - rb * rb) / (2 * le);
    const double h = std::sqrt(std::max(ra * ra - x * x, 0.0));
    p3 = a + x * e + want * h * n.cross(e);
    n_out = n;
    return true;
  };
  c.eps = residual_tolerance(s, st, a, std::max(ra, rb));
  auto resid = [&](const SurfaceEval1& e, Vec2& f, Eigen::Matrix2d& J) {
    const Vec3 da = e.p - a, db = e.p - b;
    f << (da.squaredNorm() - ra * ra) / (2 * ra), (db.squaredNorm() - rb * rb) / (2 * rb);
    J << da.dot(e.du) / ra, da.dot(e.dv) / ra, db.dot(e.du) / rb, db.dot(e.dv) / rb;
  };
  // The requested branch: across the line a-b from the cell's fourth corner where a, b and p
  // are not on one face and the corner is known; else on the `side` about the normal at p.
  const Vec3 e_ab = (b - a) / L;
  auto across_from_corner = [&](const SurfaceLocation& p_at) {
    return step.corner && (step.a_at.face != step.b_at.face || p_at.face != step.a_at.face);
  };
  // The offset of v from the line a-b that tells its sides apart: along the sideways
  // direction, perpendicular to the line and to the mean of the normals at a and b. (The full
  // perpendicular adds the sag of the surface below the chord a-b, the same on both sides,
  // which on a curved face outweighs the sideways offsets of a cell sheared nearly flat: on
  // sphere-8 at 80 degrees of shear both solutions then seemed on the corner's side.) Where
  // the normals nearly cancel (a knife edge), the full perpendicular.
  std::optional<Vec3> side_dir;
  bool side_dir_known = false;
  auto offset = [&](const Vec3& v) {
    if (!side_dir_known) {
      side_dir_known = true;
      const SurfaceEval1 ea = s.eval1(step.a_at), eb = s.eval1(step.b_at);
      c.res.evaluations += 2;
      if (ea.ok && eb.ok) {
        const Vec3 w = (face_normal(s, step.a_at, ea) + face_normal(s, step.b_at, eb)).cross(e_ab);
        if (w.norm() > kMeanNormalMin) side_dir = w.normalized();
      }
    }
    return side_dir ? Vec3(v.dot(*side_dir) * *side_dir) : Vec3(v - v.dot(e_ab) * e_ab);
  };
  auto on_branch = [&](const Vec3& p, const Vec3& n, const SurfaceLocation& p_at) {
    if (across_from_corner(p_at)) return offset(p - a).dot(offset(*step.corner - a)) < 0.0;
    return n.dot((b - a).cross(p - a)) * want > 0.0;
  };
  // A solution on the requested branch: its thread angle, the in-face test, eq. (12).
  auto finish = [&]() {
    const Vec3 pa = a - c.res.point, pb = b - c.res.point;
    c.res.thread_angle = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    classify_converged(c);
    if (c.res.status == SolveStatus::kConverged && st.gamma_min > 0.0 &&
        (c.res.thread_angle < st.gamma_min || c.res.thread_angle > kPi - st.gamma_min)) {
      c.res.status = SolveStatus::kShearLimit;
      c.res.shear_stop = ShearStop::kLock;
      c.res.reason = "thread angle beyond the shear limit";
    }
  };
  // Newton from g; true when it converged on the requested branch (c.res classified). An
  // attempt that left the face is kept: if no attempt finds the node on the face, it is
  // outside (a later attempt may find only the other branch, which lies on the face).
  std::optional<SolveResult> left;
  auto attempt = [&](const SurfaceLocation& g) {
    setup_margins(c, step.a_at, g);
    const double mb = c.scaled_norm(step.b_at, s.delta(step.b_at, g));
    c.margin = std::max(c.margin, st.tol.extension_steps * mb);
    c.max_step = std::max(c.max_step, kStepCapSteps * mb);
    if (!newton(c, g, resid)) {
      if (c.res.status == SolveStatus::kLeftFace && !left) left = c.res;
      return false;
    }
    settle(c, resid);
    if (!on_branch(c.res.point, face_normal(s, c.res.at, c.last), c.res.at)) {
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "only the folded branch was found";
      return false;
    }
    finish();
    return true;
  };
  // The circle of intersection of the two spheres, bisected for its crossing of the surface
  // on the requested side (step 4 below); true when it converged there (c.res classified).
  auto attempt_circle = [&]() {
    const SurfaceEval1 ea = s.eval1(step.a_at), eb = s.eval1(step.b_at);
    c.res.evaluations += 2;
    if (!ea.ok || !eb.ok) return false;
    const Vec3 e = (b - a) / L;
    Vec3 n = face_normal(s, step.a_at, ea) + face_normal(s, step.b_at, eb);
    n -= n.dot(e) * e;
    const double x = (L * L + ra * ra - rb * rb) / (2 * L);
    const double h = std::sqrt(std::max(ra * ra - x * x, 0.0));
    if (!(n.norm() > 0.0) || !(h > kCircleMinRel * std::min(ra, rb))) return false;
    n.normalize();
    const Vec3 m = a + x * e;
    Vec3 w1 = want * n.cross(e);
    if (step.corner && step.a_at.face != step.b_at.face) {
      // Across a crease the normals are no guide: the side away from the corner.
      const Vec3 away = -offset(*step.corner - a);
      if (away.norm() > 0.0) {
        w1 = away.normalized();
        n = e.cross(w1);
      }
    }
    auto on_circle = [&](double th) {
      return Vec3(m + h * (std::cos(th) * w1 + std::sin(th) * n));
    };
    SurfaceLocation seed = step.a_at;
    auto signed_distance = [&](double th, Foot& f) {
      const Vec3 q = on_circle(th);
      // Nearest of the feet from the last foot and from a and b (a knife edge has a local
      // nearest point on each of its faces).
      f = foot_near(s, st, q, seed, c.res.evaluations);
      for (const SurfaceLocation* from : {&step.a_at, &step.b_at}) {
        if (*from == seed) continue;
        const Foot g = foot_near(s, st, q, *from, c.res.evaluations);
        if (g.ok && (!f.ok || (g.p - q).norm() < (f.p - q).norm())) f = g;
      }
      if (!f.ok) return std::numeric_limits<double>::quiet_NaN();
      seed = f.at;
      return (q - f.p).dot(f.n);
    };
    // Illinois (regula falsi) on the circle's angle in [lo, hi], bounded; then Newton from
    // the point found, or that point itself if it meets eq. (9)'s tolerance. A sign change
    // can be false: where the nearest point of the face lies on its edge (a free edge, or an
    // edge where a derivative vanishes) the normal there does not measure the distance, and
    // the signed distance changes sign away from the surface. The bracket counts only where
    // the circle's point found in it lies on the surface (within kCircleNearRel of h, or
    // eq. (9)'s tolerance).
    auto solve_in_bracket = [&](double lo, double hi, double flo, double fhi, Foot f) {
      double th = lo;
      int side = 0;
      for (int it = 0; it < kCircleIterations && hi != lo; ++it) {
        th = (lo * fhi - hi * flo) / (fhi - flo);
        const double fth = signed_distance(th, f);
        if (!(fth == fth)) return false;
        if (std::abs(fth) < 0.5 * c.eps) break;
        if ((fth > 0.0) == (flo > 0.0)) {
          lo = th;
          flo = fth;
          if (side == -1) fhi *= 0.5;
          side = -1;
        } else {
          hi = th;
          fhi = fth;
          if (side == 1) flo *= 0.5;
          side = 1;
        }
      }
      if (!f.ok || (on_circle(th) - f.p).norm() > std::max(c.eps, kCircleNearRel * h)) return false;
      if (attempt(f.at)) return true;
      const SurfaceEval1 ef = s.eval1(f.at);
      ++c.res.evaluations;
      if (!ef.ok) return false;
      Vec2 r;
      Eigen::Matrix2d J;
      resid(ef, r, J);
      // The point itself, on the requested branch only: the circle is searched all round,
      // and past a face's edge Newton from the other branch's crossing fails (left the face)
      // where that point still fits both links.
      if (!(r.cwiseAbs().sum() < c.eps) || !on_branch(ef.p, face_normal(s, f.at, ef), f.at))
        return false;
      c.res.at = f.at;
      c.res.point = ef.p;
      c.res.residual = r.cwiseAbs().sum();
      c.last = ef;
      finish();
      return true;
    };
    // The whole circle, sampled from the middle of the requested side's half (the planar
    // solution) outwards on both sides; the sign changes are tried nearest the middle first,
    // until one holds a solution.
    Foot f0, f1;
    const double fmid = signed_distance(0.0, f0);
    if (!(fmid == fmid)) return false;
    if (std::abs(fmid) < 0.5 * c.eps && solve_in_bracket(0.0, 0.0, fmid, fmid, f0)) return true;
    double prev_th[2] = {0.0, 0.0}, prev_f[2] = {fmid, fmid};
    Foot prev_foot[2] = {f0, f0};
    for (int k = 1; k <= 2 * kCircleSamples; ++k)
      for (int side = 0; side < 2; ++side) {
        const double th = (side ? -1.0 : 1.0) * 0.5 * kPi * k / kCircleSamples;
        const double f = signed_distance(th, f1);
        if (!(f == f)) return false;
        if ((f > 0.0) != (prev_f[side] > 0.0) &&
            solve_in_bracket(prev_th[side], th, prev_f[side], f, prev_foot[side]))
          return true;
        prev_th[side] = th;
        prev_f[side] = f;
        prev_foot[side] = f1;
      }
    return false;
  };
  // 1. The caller's guess (eqs. 10-11).
  if (step.guess && attempt(s.locate(step.a_at, *step.guess))) return c.res;
  // 2. The planar solution mapped to (u, v) to first order, if that model is trustworthy
  //    (the surface point at the guess near the planar target); a trusted model that leaves
  //    the face is the answer.
  Vec3 p3, n3;
  const SurfaceEval1 ea = s.eval1(step.a_at);
  ++c.res.evaluations;
  if (planar_target(step.a_at, ea, p3, n3)) {
    Vec2 dir;
    if (metric_direction(ea, p3 - a, dir)) {
      const SurfaceLocation g = s.locate(step.a_at, step.a_at.uv + dir * (p3 - a).norm());
      const SurfaceEval1 eg = s.eval1(g);
      ++c.res.evaluations;
      const bool trusted = eg.ok && (eg.p - p3).norm() <= kTrustRatio * ra;
      if (trusted) {
        if (attempt(g)) return c.res;
        if (c.res.status == SolveStatus::kLeftFace) return c.res;
      }
    }
    // 3. A point on the surface at distance ra from a towards the planar target, found by
    //    the marching plane-sphere solver, then the same from b: robust guesses where the
    //    parametrisation is far from linear.
    for (int from_b = 0; from_b < 2; ++from_b) {
      const Vec3& o = from_b ? b : a;
      const SurfaceLocation& o_at = from_b ? step.b_at : step.a_at;
      const double r = from_b ? rb : ra;
      const SurfaceEval1 eo = from_b ? s.eval1(o_at) : ea;
      if (!eo.ok) continue;
      const Vec3 n = face_normal(s, o_at, eo);
      Vec3 t = p3 - o;
      t -= t.dot(n) * n;
      if (!(t.norm() > 0.0)) continue;
      t.normalize();
      const SolveResult q = plane_sphere_core(s, o, o_at, eo, n, n.cross(t), t, r, st);
      c.res.evaluations += q.evaluations;
      if (q.status != SolveStatus::kConverged &&
          !(q.status == SolveStatus::kLeftFace && q.extended))
        continue;
      if (attempt(q.at)) return c.res;
    }
  }
  // 4. Across a crease (a shell's G0 shared edge) Newton on either face may stall at the edge
  //    (the residual has a kink there). The spheres' circle of intersection, on the requested
  //    side of the line a-b, crosses the surface where its signed distance to it changes
  //    sign: found by bisection on the circle's angle.
  if (c.res.status != SolveStatus::kLeftFace && attempt_circle()) return c.res;
  if (c.res.status == SolveStatus::kFailed && left) {
    const int iterations = c.res.iterations, evaluations = c.res.evaluations;
    c.res = *left;
    c.res.iterations = iterations;
    c.res.evaluations = evaluations;
    return c.res;
  }
  // No point of the face fits both links when the spheres' circle of intersection (centre m,
  // radius h) passes the face at a distance: every point of the circle lies within h of m,
  // so a face whose nearest point to m is further than h from it misses the circle. With
  // the spheres meeting (checked above), the links, straight chords, would pass below a
  // curved face: for a weft and a warp link a cell sheared so nearly flat that the cloth
  // stops there as at the shear limit (its thread angle, fixed by the three lengths, is
  // reported); for two links of one thread, a thread that would have to stretch.
  if (c.res.status == SolveStatus::kFailed) {
    const double x = (L * L + ra * ra - rb * rb) / (2 * L);
    const double h = std::sqrt(std::max(ra * ra - x * x, 0.0));
    const Vec3 m = a + x * e_ab;
    double gap = std::numeric_limits<double>::infinity();
    for (const SurfaceLocation* from : {&step.a_at, &step.b_at}) {
      const Foot f = foot_near(s, st, m, *from, c.res.evaluations);
      gap = f.ok ? std::min(gap, (f.p - m).norm()) : -1.0;
      if (!(gap > h + c.eps)) break;
    }
    if (gap > h + c.eps) {
      c.res.no_point = true;
      c.res.reason = "no point of the face fits both links (they would pass below the face)";
      if (st.gamma_min > 0.0) {
        c.res.status = SolveStatus::kShearLimit;
        c.res.shear_stop = ShearStop::kFlatCell;
        c.res.thread_angle =
            std::acos(std::clamp((ra * ra + rb * rb - L * L) / (2 * ra * rb), -1.0, 1.0));
        c.res.reason =
            "no point of the face fits both links (the cell is sheared so flat that "
            "they pass below the curved face)";
      }
      return c.res;
    }
  }
  // Near the shear limit the spheres meet almost tangentially and Newton may stall:
  // eq. (12) on the last iterate tells the shear limit from a plain failure.
  if (c.res.status == SolveStatus::kFailed && st.gamma_min > 0.0 && c.res.point.allFinite()) {
    const Vec3 pa = a - c.res.point, pb = b - c.res.point;
    const double g = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    if (pa.norm() > 0 && pb.norm() > 0 && (g < st.gamma_min || g > kPi - st.gamma_min)) {
      c.res.status = SolveStatus::kShearLimit;
      c.res.shear_stop = ShearStop::kLock;
      c.res.thread_angle = g;
      c.res.reason = "thread angle beyond the shear limit (near-tangent spheres)";
    }
  }
  if (c.res.status == SolveStatus::kConverged) c.res.status = SolveStatus::kFailed;
  return c.res;
}

}  // namespace plyfit
