#pragma once
// Private to the solvers: the damped Newton iteration on (u, v) that all three solvers run
// (eqs. 4-6, stop test eq. 9), with what finishes a converged solve (settle, in-face test).

#include "drape/solvers/solvers.hpp"

#include <Eigen/Core>

namespace plyfit::solvers {

using plyfit::kPi;
// A 2x2 Jacobian is treated as singular when |det| < kSingularRel * |col 0| * |col 1|; the
// step is then a Levenberg-Marquardt step with damping kLmDampingRel * diag(J^T J).
inline constexpr double kSingularRel = 1e-10;
inline constexpr double kLmDampingRel = 1e-8;
// Newton steps are capped at this many initial-step lengths in (u, v).
inline constexpr double kStepCapSteps = 10.0;
// The first-order model of a step is trusted when the surface point at the guess lies within
// kTrustRatio * rho of the intended point (plane-sphere and two-sphere solvers).
inline constexpr double kTrustRatio = 0.5;

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

// A Newton iterate: its location, the surface there, the residual F (model units), its
// Jacobian and |F1| + |F2|.
struct Iterate {
  SurfaceLocation at;
  SurfaceEval1 e;
  Vec2 f = Vec2::Zero();
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  double r = 0.0;
};

// The steps of newton() that do not depend on the residual.
// A guess where the surface is undefined or beyond the margin, pulled back towards the known
// point; false (c.res: left the face) when the surface stays undefined.
bool start_iterate(Ctx& c, SurfaceLocation at, Iterate& x);
// Converged: the solution into c.res (after `it` iterations).
void accept_iterate(Ctx& c, const Iterate& x, int it);
// A Newton solve that ends unconverged (for `why`) at `at`: failed, or left the face where
// that iterate lies past its face's domain edge.
void stop_unconverged(Ctx& c, const SurfaceLocation& at, const Vec3& p, double r, const char* why);
// The Newton step, or Levenberg-Marquardt where the Jacobian is (nearly) singular.
Vec2 newton_step(const Eigen::Matrix2d& J, const Vec2& f);
// Where a first derivative vanishes (a zero Jacobian column): the iterate moved into the
// domain along that parameter, at most kMaxNudges times per solve (`nudges` counts them);
// true (x.at, x.e set, the residual not yet) when it moved.
bool nudge_off_vanishing_derivative(Ctx& c, Iterate& x, int& nudges);
// The step capped at c.max_step; true (c.res: left the face, after `it` iterations) when it
// proposes to leave the domain margin kOutsideStrikes times in a row from past the edge.
// `within`: the full step's point lies within the margin.
bool step_leaves_face(Ctx& c, const Iterate& x, Vec2& step, int& outside_strikes, int it,
                      bool& within);

// Evaluates the residual functor resid(e, f, J) at x.e.
template <class Resid>
void evaluate(Iterate& x, Resid& resid) {
  resid(x.e, x.f, x.J);
  x.r = x.f.cwiseAbs().sum();
}

// Backtracking line search on |f|^2 along `step`, staying within the margin; true when a
// shorter step decreased it (x moved there). `full_within`: the full step's point lies within
// the margin (step_leaves_face tested it).
template <class Resid>
bool line_search(Ctx& c, Iterate& x, Vec2 step, Resid& resid, bool full_within) {
  const double phi = x.f.squaredNorm();
  for (int h = 0; h <= c.st.tol.line_search_max_halvings; ++h, step *= 0.5) {
    const SurfaceLocation cand = c.s.locate(x.at, x.at.uv + step);
    if (!(h == 0 ? full_within : c.within_margin(cand))) continue;
    Iterate y;
    y.e = c.s.eval1(cand);
    ++c.res.evaluations;
    if (!y.e.ok) continue;
    resid(y.e, y.f, y.J);
    if (y.f.squaredNorm() < phi) {
      y.at = cand;
      y.r = y.f.cwiseAbs().sum();
      x = y;
      return true;
    }
  }
  return false;
}

// Newton-Raphson on (u, v) for the residual functor resid(e, f, J) (f in model units).
// Returns true on convergence (|f1| + |f2| < eps); fills ctx.res with the point, counts and,
// on failure, status and reason.
template <class Resid>
bool newton(Ctx& c, SurfaceLocation at, Resid&& resid) {
  Iterate x;
  if (!start_iterate(c, at, x)) return false;
  evaluate(x, resid);
  int outside_strikes = 0, nudges = 0;
  for (int it = 0;; ++it) {
    if (!(x.r == x.r) || !x.f.allFinite()) break;  // defensive: never iterate on NaN
    if (x.r < c.eps) {
      accept_iterate(c, x, it);
      return true;
    }
    if (it >= c.st.tol.newton_max_iterations) {
      c.res.iterations += it;
      stop_unconverged(c, x.at, x.e.p, x.r, "no convergence within the iteration cap");
      return false;
    }
    Vec2 step = newton_step(x.J, x.f);
    const double c0 = x.J.col(0).norm(), c1 = x.J.col(1).norm();
    if ((!step.allFinite() || !(c0 > 0.0 && c1 > 0.0)) &&
        nudge_off_vanishing_derivative(c, x, nudges)) {
      evaluate(x, resid);
      continue;
    }
    if (!step.allFinite() || !(c0 + c1 > 0.0)) {
      c.res.iterations += it;
      c.res.status = SolveStatus::kFailed;
      c.res.reason = "degenerate Jacobian";
      return false;
    }
    bool within = false;
    if (step_leaves_face(c, x, step, outside_strikes, it, within)) return false;
    if (!line_search(c, x, step, resid, within)) {
      c.res.iterations += it + 1;
      stop_unconverged(c, x.at, x.e.p, x.r, "no intersection (the residual stopped decreasing)");
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
                          double radius);
// Margin and step cap from the length of the first step (scaled units).
void setup_margins(Ctx& c, const SurfaceLocation& from, const SurfaceLocation& guess);
// Finishes a converged, settled solve: on the face (kConverged, a solution a hair past a
// domain edge clamped onto it) or past its edge (kLeftFace, extended).
void classify_converged(Ctx& c);

// The face a solve that converged off its face is solved again on (DrapeSurface::settle);
// the location itself when there is none.
SurfaceLocation settle_location(const Ctx& c);

// A solve that converged off its face: solved again from the location where the surface
// holds its point (DrapeSurface::settle: past a pole of the face, the face itself; on a
// shell, a neighbour face). c.res changes only if that solve converges on the surface; the
// iterations and evaluations count either way. Called right after Newton converged, before
// any test that uses the normal there (past a pole the extended face's orientation flips).
template <class Resid>
void settle(Ctx& c, Resid&& resid) {
  if (c.s.contains(c.res.at)) return;
  const SurfaceLocation other = settle_location(c);
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

}  // namespace plyfit::solvers
