#include <plyfit/kernel/solvers.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A 2x2 Jacobian is treated as singular when |det| < kSingularRel * |col 0| * |col 1|; the
// step is then a Levenberg-Marquardt step with damping kLmDampingRel * diag(J^T J).
constexpr double kSingularRel = 1e-10;
constexpr double kLmDampingRel = 1e-8;
// At a pole, a step must make a cosine above this with some direction the face offers (the
// fan of the collapsed edge's derivatives); otherwise it leaves the face at once.
constexpr double kMinFanCos = 1e-6;
// Samples and golden-section refinements when searching a collapsed edge for a direction.
constexpr int kEdgeSamples = 64;
constexpr int kEdgeRefinements = 30;
// Newton steps are capped at this many initial-step lengths in (u, v).
constexpr double kStepCapSteps = 10.0;
// The first-order model of a plane-sphere step is trusted when the surface point at the
// guess lies within kTrustRatio * rho of the intended point; otherwise, and after a failed
// solve, the solver marches along the curve in kMarchSteps sub-steps.
constexpr double kTrustRatio = 0.5;
constexpr int kMarchSteps[] = {4, 16};
// Sine of the angle between base plane and tangent plane below which the plane is taken
// as tangent to the surface (no intersection curve direction).
constexpr double kTangentPlaneSin = 1e-6;
// A solution off its face is solved again on a face within this fraction of d of it (3D),
// from the point's projection there (DrapeSurface::settle).
constexpr double kSettleReachRel = 0.1;
// A Newton step proposing to leave the domain margin this many times in a row, from an
// iterate already past the domain edge, ends the solve with "left the face".
constexpr int kOutsideStrikes = 2;

Vec3 face_normal(const DrapeSurface& s, const SurfaceLocation& at, const SurfaceEval1& e) {
  // The limit normal at poles, else the normalised cross product with the face orientation.
  if (s.degenerate(at, e)) return s.normal(at).n;
  return s.orientation(at) * e.du.cross(e.dv).normalized();
}

// Least-squares (u, v) direction a with J a = dir_t, scaled to |J a| = 1.
bool metric_direction(const SurfaceEval1& e, const Vec3& dir, Vec2& a) {
  Eigen::Matrix2d G;
  G << e.du.dot(e.du), e.du.dot(e.dv), e.du.dot(e.dv), e.dv.dot(e.dv);
  const Vec2 rhs(e.du.dot(dir), e.dv.dot(dir));
  if (!(G(0, 0) > 0.0 || G(1, 1) > 0.0)) return false;
  // Marquardt-style regularisation, relative to each diagonal entry: |Su| and |Sv| may
  // differ by many orders of magnitude.
  G(0, 0) = G(0, 0) * (1.0 + kSingularRel) + 1e-300;
  G(1, 1) = G(1, 1) * (1.0 + kSingularRel) + 1e-300;
  a = G.inverse() * rhs;
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
  int outside_strikes = 0;
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
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "no convergence within the iteration cap";
      c.res.at = c.s.wrap(at);
      c.res.point = e.p;
      c.res.residual = r;
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
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "no intersection (the residual stopped decreasing)";
      c.res.at = c.s.wrap(at);
      c.res.point = e.p;
      c.res.residual = r;
      return false;
    }
  }
  c.res.status = SolveStatus::kFailed;
  c.res.reason = "non-finite residual";
  return false;
}

// Tolerance of eq. (9): relative to d, floored at the rounding level of the residual. That
// level is set by the coordinates involved and by the surface's own evaluation, whose
// rounding grows with the size of the control net it sums over (a point at the origin of a
// 40 mm saddle is still evaluated to a few ulps of 40 mm): the face size counts too.
double residual_tolerance(const DrapeSurface& s, const SolverSettings& st, const Vec3& where,
                          double radius) {
  return std::max(st.tol.newton_residual_rel * st.spacing,
                  st.tol.roundoff_rel * (where.cwiseAbs().maxCoeff() + s.size() + radius));
}

// Finishes a converged solve: in-face test (one contains() query). A solution a hair past
// a domain edge (a path along the edge, or a pole reached from the extension beyond it) is
// on the face if the same point is reached with the parameters clamped to the domain.
template <class Resid>
void classify_converged(Ctx& c, Resid&& resid) {
  if (c.s.contains(c.res.at)) {
    c.res.status = SolveStatus::kConverged;
    return;
  }
  // Off its face but on another face of the surface (a shell's neighbour past a pole, or one
  // the iterate reached without crossing a shared edge): solved again there, from the point's
  // projection.
  const SurfaceLocation other = c.s.settle(c.res.at, c.res.point, kSettleReachRel * c.st.spacing);
  if (other != c.res.at) {
    const SolveResult before = c.res;
    const SurfaceEval1 last = c.last;
    if (newton(c, other, resid) && c.s.contains(c.res.at)) {
      c.res.status = SolveStatus::kConverged;
      return;
    }
    c.res = before;
    c.last = last;
  }
  const auto& d = c.s.domain(c.res.at);
  const Vec2& uv = c.res.at.uv;
  const SurfaceLocation clamped =
      c.res.at.with_uv(Vec2(std::clamp(uv.x(), d.u0, d.u1), std::clamp(uv.y(), d.v0, d.v1)));
  if (clamped != c.res.at && c.s.contains(clamped)) {
    const SurfaceEval1 e = c.s.eval1(clamped);
    ++c.res.evaluations;
    if (e.ok && (e.p - c.res.point).norm() < c.eps) {
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

Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - c);
}

namespace {

// uv_direction with the evaluation e and the face normal n at uv already known.
UvDirection uv_direction_at(const DrapeSurface& surface, const SurfaceLocation& at,
                            const SurfaceEval1& e, const Vec3& n, const Vec3& dir) {
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
  // A pole: one derivative vanishes along a collapsed edge. Slide along that edge to the
  // parameter whose remaining derivative points best along dir.
  const bool v_collapsed = e.dv.norm() * sp.x() <= e.du.norm() * sp.y();
  const auto& d = surface.domain(at);
  const double lo = v_collapsed ? d.v0 : d.u0, hi = v_collapsed ? d.v1 : d.u1;
  auto score = [&](double t) {
    const SurfaceLocation q = at.with_uv(v_collapsed ? Vec2(uv.x(), t) : Vec2(t, uv.y()));
    const SurfaceEval1 eq = surface.eval1(q);
    const Vec3 g = v_collapsed ? eq.du : eq.dv;
    // The edge is left towards the interior: at the domain end the derivative flips sign.
    const double inward = v_collapsed ? ((uv.x() <= 0.5 * (d.u0 + d.u1)) ? 1.0 : -1.0)
                                      : ((uv.y() <= 0.5 * (d.v0 + d.v1)) ? 1.0 : -1.0);
    const double gn = g.norm();
    return (eq.ok && gn > 0.0) ? inward * g.dot(dt) / (gn * dt.norm()) : -2.0;
  };
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
  const double t = (f1 > best || f2 > best) ? (f1 > f2 ? x1 : x2) : best_t;
  if (std::max({best, f1, f2}) <= kMinFanCos) {
    out.leaves_face = true;
    return out;
  }
  out.from_at = at.with_uv(v_collapsed ? Vec2(uv.x(), t) : Vec2(t, uv.y()));
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
                              double rho, const SolverSettings& st) {
  Ctx c(s, st);
  const UvDirection ud = uv_direction_at(s, at0, e0, n0, t);
  if (ud.leaves_face) {
    c.res.status = SolveStatus::kLeftFace;
    c.res.reason = "the step leaves the face at a collapsed edge (pole)";
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
  // One Newton solve for radius `rad` from `guess`; true if it converged forward.
  auto solve_from = [&](const SurfaceLocation& guess) {
    setup_margins(c, ud.from_at, guess);
    if (!newton(c, guess, resid)) return false;
    if ((c.res.point - x0).dot(t) > 0.0) return true;
    c.res.status = SolveStatus::kFailed;
    c.res.reason = "converged backwards";
    return false;
  };
  // Direct attempt from the first-order guess (eqs. 7-8).
  const SurfaceLocation guess = s.locate(ud.from_at, ud.from_at.uv + rho * ud.dir_uv);
  if (solve_from(guess)) {
    classify_converged(c, resid);
    return c.res;
  }
  // Leaving the face is the answer when the first-order model is trustworthy: the surface
  // point at the guess is close to the intended 3D point.
  if (c.res.status == SolveStatus::kLeftFace) {
    const SurfaceEval1 eg = s.eval1(guess);
    ++c.res.evaluations;
    if (eg.ok && (eg.p - (x0 + rho * t)).norm() <= kTrustRatio * rho) return c.res;
  }
  // Otherwise march along the intersection curve: radius rho k / K, k = 1..K, each guess
  // extrapolated from the previous two solutions.
  const SolveResult first = c.res;
  for (int K : kMarchSteps) {
    SurfaceLocation prev = ud.from_at, prev2 = ud.from_at, g = ud.from_at;
    bool ok = true;
    for (int k = 1; k <= K && ok; ++k) {
      rad = rho * k / K;
      g = k == 1 ? s.locate(ud.from_at, ud.from_at.uv + rad * ud.dir_uv)
                 : continue_step(s, prev2, prev);
      ok = solve_from(g);
      if (ok) {
        prev2 = prev;
        prev = c.res.at;
      }
    }
    if (ok) {
      classify_converged(c, resid);
      return c.res;
    }
    // A sub-step that fails where the curve, at the last sub-step or continued from it, is
    // already off the face ends the march: the node is outside. (Its iterate left the margin, or
    // Newton stalled on the surface extended past a domain edge, which need not go on.)
    // Otherwise try finer sub-steps.
    if (!s.contains(g) || (prev != ud.from_at && !s.contains(prev))) {
      c.res.status = SolveStatus::kLeftFace;
      c.res.extended = false;
      c.res.reason = "outside";
      return c.res;
    }
  }
  SolveResult out = first;
  out.iterations = c.res.iterations;
  out.evaluations = c.res.evaluations;
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
  SolveResult r = plane_sphere_core(s, step.from, step.from_at, e0, n0, pn, t, step.distance, st);
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
  SolveResult r =
      plane_sphere_core(s, step.center, step.center_at, e0, n, n.cross(t), t, step.radius, st);
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
  // Newton from g; true when it converged on the requested branch (c.res classified).
  auto attempt = [&](const SurfaceLocation& g) {
    setup_margins(c, step.a_at, g);
    const double mb = c.scaled_norm(step.b_at, s.delta(step.b_at, g));
    c.margin = std::max(c.margin, st.tol.extension_steps * mb);
    c.max_step = std::max(c.max_step, kStepCapSteps * mb);
    if (!newton(c, g, resid)) return false;
    const Vec3 n = face_normal(s, c.res.at, c.last);
    if (n.dot((b - a).cross(c.res.point - a)) * want <= 0.0) {
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "only the folded branch was found";
      return false;
    }
    const Vec3 pa = a - c.res.point, pb = b - c.res.point;
    c.res.thread_angle = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    classify_converged(c, resid);
    if (c.res.status == SolveStatus::kConverged && st.gamma_min > 0.0 &&
        (c.res.thread_angle < st.gamma_min || c.res.thread_angle > kPi - st.gamma_min)) {
      c.res.status = SolveStatus::kShearLimit;
      c.res.reason = "thread angle beyond the shear limit";
    }
    return true;
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
  // Near the shear limit the spheres meet almost tangentially and Newton may stall:
  // eq. (12) on the last iterate tells the shear limit from a plain failure.
  if (c.res.status == SolveStatus::kFailed && st.gamma_min > 0.0 && c.res.point.allFinite()) {
    const Vec3 pa = a - c.res.point, pb = b - c.res.point;
    const double g = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    if (pa.norm() > 0 && pb.norm() > 0 && (g < st.gamma_min || g > kPi - st.gamma_min)) {
      c.res.status = SolveStatus::kShearLimit;
      c.res.thread_angle = g;
      c.res.reason = "thread angle beyond the shear limit (near-tangent spheres)";
    }
  }
  if (c.res.status == SolveStatus::kConverged) c.res.status = SolveStatus::kFailed;
  return c.res;
}

}  // namespace plyfit
