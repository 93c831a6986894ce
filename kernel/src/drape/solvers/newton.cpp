// The parts of the solvers' Newton iteration that do not depend on the residual, and what
// finishes a converged solve.
#include "drape/solvers/newton.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace plyfit::solvers {

namespace {

// An iterate where a first derivative of the surface vanishes (a pole, or an edge along
// which the derivative across it vanishes: a degenerate parametrisation of a regular
// surface) has a zero Jacobian column, and neither Newton nor Levenberg-Marquardt can move
// it in that parameter. It is moved into the domain by this fraction of the domain's width in
// that parameter, at most kMaxNudges times per solve.
constexpr double kNudgeRel = 1e-6;
constexpr int kMaxNudges = 4;
// A Newton step proposing to leave the domain margin this many times in a row, from an
// iterate already past the domain edge, ends the solve with "left the face".
constexpr int kOutsideStrikes = 2;
// A solution off its face is solved again on a face within this fraction of d of it (3D),
// from the point's projection there (DrapeSurface::settle).
constexpr double kSettleReachRel = 0.1;

}  // namespace

bool start_iterate(Ctx& c, SurfaceLocation at, Iterate& x) {
  SurfaceEval1 e = c.s.eval1(at);
  ++c.res.evaluations;
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
  x.at = at;
  x.e = e;
  return true;
}

void accept_iterate(Ctx& c, const Iterate& x, int it) {
  c.res.at = c.s.wrap(x.at);
  c.res.point = x.e.p;
  c.res.residual = x.r;
  c.res.iterations += it;
  c.last = x.e;
}

// Failed, or left the face where the iterate lies past its face's domain edge (the surface
// extended past a free edge, where the residual has no zero near the face: the cloth leaves
// the face there).
void stop_unconverged(Ctx& c, const SurfaceLocation& at, const Vec3& p, double r, const char* why) {
  c.res.at = c.s.wrap(at);
  c.res.point = p;
  c.res.residual = r;
  const bool past_edge = !c.s.domain(c.res.at).contains(c.res.at.uv.x(), c.res.at.uv.y());
  c.res.status = past_edge ? SolveStatus::kLeftFace : SolveStatus::kFailed;
  c.res.reason = past_edge ? "iterate" : why;
}

// Both steps are invariant to scaling u or v: |det| is compared with the product of the
// column norms (the sine of the angle between the columns), and the damping is Marquardt's
// diagonal.
Vec2 newton_step(const Eigen::Matrix2d& J, const Vec2& f) {
  const double c0 = J.col(0).norm(), c1 = J.col(1).norm();
  const double det = J.determinant();
  if (std::abs(det) > kSingularRel * c0 * c1)
    return -(Eigen::Matrix2d() << J(1, 1), -J(0, 1), -J(1, 0), J(0, 0)).finished() * f / det;
  Eigen::Matrix2d A = J.transpose() * J;
  const Vec2 D(std::max(A(0, 0), 1e-300), std::max(A(1, 1), 1e-300));
  A(0, 0) += kLmDampingRel * D.x();
  A(1, 1) += kLmDampingRel * D.y();
  return -A.inverse() * (J.transpose() * f);
}

// The iterate is moved off the point along the parameter whose derivative vanishes, into the
// domain, where the derivative no longer vanishes.
bool nudge_off_vanishing_derivative(Ctx& c, Iterate& x, int& nudges) {
  if (nudges >= kMaxNudges) return false;
  const double c0 = x.J.col(0).norm(), c1 = x.J.col(1).norm();
  const SurfaceLocation w = c.s.wrap(x.at);
  const ParamDomain& d = c.s.domain(w);
  Vec2 uv = w.uv;
  if (!(c0 > 0.0)) uv.x() += kNudgeRel * d.width_u() * (uv.x() < 0.5 * (d.u0 + d.u1) ? 1 : -1);
  if (!(c1 > 0.0)) uv.y() += kNudgeRel * d.width_v() * (uv.y() < 0.5 * (d.v0 + d.v1) ? 1 : -1);
  const SurfaceEval1 e2 = c.s.eval1(w.with_uv(uv));
  ++c.res.evaluations;
  ++nudges;
  if (!(e2.ok && (c0 > 0.0 || c1 > 0.0))) return false;
  x.at = w.with_uv(uv);
  x.e = e2;
  return true;
}

// Only an iterate already past the domain edge, still pushed further out, has left; an
// overshoot from inside is nonlinearity, and the line search shortens it.
bool step_leaves_face(Ctx& c, const Iterate& x, Vec2& step, int& outside_strikes, int it,
                      bool& within) {
  const double sn = c.scaled_norm(x.at, step);
  if (sn > c.max_step) step *= c.max_step / sn;
  within = c.within_margin(c.s.locate(x.at, x.at.uv + step));
  if (within) {
    outside_strikes = 0;
    return false;
  }
  const SurfaceLocation w = c.s.wrap(x.at);
  const bool past_edge = !c.s.domain(w).contains(w.uv.x(), w.uv.y());
  if (!(++outside_strikes >= kOutsideStrikes && past_edge)) return false;
  c.res.iterations += it + 1;
  c.res.status = SolveStatus::kLeftFace;
  c.res.reason = "iterate";
  c.res.at = c.s.wrap(x.at);
  c.res.point = x.e.p;
  c.res.residual = x.r;
  return true;
}

double residual_tolerance(const DrapeSurface& s, const SolverSettings& st, const Vec3& where,
                          double radius) {
  return std::max(st.tol.newton_residual_rel * st.spacing,
                  residual_floor(s, st.tol, where, radius));
}

void setup_margins(Ctx& c, const SurfaceLocation& from, const SurfaceLocation& guess) {
  c.anchor = from;
  const double step = std::max(c.scaled_norm(from, c.s.delta(from, guess)), 1e-300);
  c.margin = c.st.tol.extension_steps * step;
  c.max_step = kStepCapSteps * step;
}

SurfaceLocation settle_location(const Ctx& c) {
  return c.s.settle(c.res.at, c.res.point, kSettleReachRel * c.st.spacing);
}

// The in-face test (one contains() query). A solution a hair past a domain edge (a path along
// the edge, a node on it, or a pole reached from the extension beyond it) is on the face if
// the same point with the parameters clamped to the domain is a solution too: within eq. (9)'s
// tolerance of the point found, or the same parameters (Tolerances::param_rel: a node on the
// edge, found a rounding past it, where the rounding of the net it is solved from has carried
// it).
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
  c.res.status = SolveStatus::kLeftFace;
  c.res.extended = true;
  c.res.reason = "outside";
}

}  // namespace plyfit::solvers
