// Solvers 1 and 3 (eqs. 1-9, §6.1 eq. 13): a plane and a sphere about the known point.
#include "drape/solvers/plane_sphere.hpp"

#include "drape/solvers/newton.hpp"
#include "drape/solvers/tangent.hpp"

#include <cmath>

namespace plyfit {

namespace solvers {

namespace {

// After a failed direct solve whose first-order model is not trusted (kTrustRatio), the
// solver marches along the curve in kMarchSteps sub-steps.
constexpr int kMarchSteps[] = {4, 16};
// A plane-sphere step that no march solves is outside when the plane's and the sphere's
// circle of intersection, sampled at this many points, passes the face at a distance.
constexpr int kSectionSamples = 64;
// Two solutions of one plane-sphere step are distinct when they lie further apart than this
// fraction of the radius (the forward and backward ones lie about two radii apart).
constexpr double kDistinctSolutionRel = 0.5;

class PlaneSphere {
 public:
  PlaneSphere(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0,
              const SurfaceEval1& e0, const Vec3& n0, const Vec3& pn, const Vec3& t, double rho,
              const SolverSettings& st, Unmarched unmarched)
      : s_(s),
        x0_(x0),
        at0_(at0),
        e0_(e0),
        n0_(n0),
        pn_(pn),
        t_(t),
        rho_(rho),
        st_(st),
        unmarched_(unmarched),
        c_(s, st) {}

  // The direct solve from the first-order guess (eqs. 7-8); where it fails and leaving the
  // face is not trusted, the march along the curve; where that fails too, the section traced
  // (the base path) or sampled for a miss of the face.
  SolveResult run() {
    if (!tangent_direction()) return c_.res;
    c_.eps = residual_tolerance(s_, st_, x0_, rho_);
    rad_ = rho_;
    const SurfaceLocation guess = s_.locate(ud_.from_at, ud_.from_at.uv + rho_ * ud_.dir_uv);
    // From a singular edge into the face, a solution past the edge is no continuation of the
    // curve (the direct guess lies far across the edge, where other solutions may be): the
    // march decides.
    if (solve_from(guess)) {
      classify_converged(c_);
      if (!(ud_.from_singular_edge && c_.res.status == SolveStatus::kLeftFace)) return c_.res;
    }
    if (trusted_exit(guess)) return c_.res;
    const SolveResult first = c_.res;
    if (auto r = march()) return *r;
    return unmarched(first);
  }

 private:
  // The first-order direction of the step in (u, v) (c_.res says why where there is none).
  bool tangent_direction() {
    ud_ = uv_direction_at(s_, at0_, e0_, n0_, t_, rho_);
    if (ud_.leaves_face) {
      c_.res.status = SolveStatus::kLeftFace;
      c_.res.reason =
          "the step leaves the face at a degenerate edge (a pole, or a singular parametrisation)";
      return false;
    }
    if (!ud_.ok) {
      c_.res.reason = "no tangent direction at the known point";
      return false;
    }
    return true;
  }

  // True if the converged solution is not the backward one: the backward solution is the one
  // Newton reaches from the first-order guess behind x0 (at -t). Only asked where the solution
  // lies behind x0's tangent plane section, which the forward one does past a crease sharper
  // than 90 degrees (a path over a thin flange's edge).
  bool distinct_from_backward() {
    Ctx b(s_, st_);
    b.eps = c_.eps;
    const SurfaceLocation g = s_.locate(ud_.from_at, ud_.from_at.uv - rad_ * ud_.dir_uv);
    setup_margins(b, ud_.from_at, g);
    const bool ok = newton(b, g, resid_);
    c_.res.evaluations += b.res.evaluations;
    return ok && (b.res.point - x0_).dot(t_) < 0.0 &&
           (b.res.point - c_.res.point).norm() > kDistinctSolutionRel * rad_;
  }

  // One Newton solve for radius rad_ from `guess`; true if it converged forward.
  bool solve_from(const SurfaceLocation& guess) {
    setup_margins(c_, ud_.from_at, guess);
    if (!newton(c_, guess, resid_)) return false;
    settle(c_, resid_);
    if ((c_.res.point - x0_).dot(t_) > 0.0 || distinct_from_backward()) return true;
    c_.res.status = SolveStatus::kFailed;
    c_.res.reason = "converged backwards";
    return false;
  }

  // Leaving the face is the answer when the first-order model is trustworthy: the surface
  // point at the guess is close to the intended 3D point.
  bool trusted_exit(const SurfaceLocation& guess) {
    if (c_.res.status != SolveStatus::kLeftFace || ud_.from_singular_edge) return false;
    const SurfaceEval1 eg = s_.eval1(guess);
    ++c_.res.evaluations;
    return eg.ok && (eg.p - (x0_ + rho_ * t_)).norm() <= kTrustRatio * rho_;
  }

  // With Unmarched::kTrace (the base path, solver 3), the section traced from x0
  // (trace_section), its counts added to those of the solve so far; nothing without it or
  // where it has no verdict.
  std::optional<SolveResult> traced(const SolveResult& so_far) const {
    std::optional<SolveResult> tr;
    if (unmarched_ == Unmarched::kTrace) tr = trace_section(s_, x0_, at0_, pn_, t_, rho_, st_);
    if (tr) {
      tr->iterations += so_far.iterations;
      tr->evaluations += so_far.evaluations;
    }
    return tr;
  }

  // The march along the intersection curve: radius rho k / K, k = 1..K, each guess
  // extrapolated from the previous two solutions; nothing where no march reaches rho.
  std::optional<SolveResult> march() {
    for (int K : kMarchSteps) {
      // From a singular edge, the first sub-step starts where the metric models it.
      const UvDirection uk =
          ud_.from_singular_edge ? uv_direction_at(s_, at0_, e0_, n0_, t_, rho_ / K) : ud_;
      if (!uk.ok) continue;
      SurfaceLocation prev = uk.from_at, prev2 = uk.from_at, g = uk.from_at;
      bool ok = true;
      for (int k = 1; k <= K && ok; ++k) {
        rad_ = rho_ * k / K;
        g = k == 1 ? s_.locate(uk.from_at, uk.from_at.uv + rad_ * uk.dir_uv)
                   : continue_step(s_, prev2, prev);
        ok = solve_from(g);
        if (ok) {
          prev2 = prev;
          prev = c_.res.at;
        }
      }
      if (ok) {
        classify_converged(c_);
        return c_.res;
      }
      // A sub-step that fails where the curve, at the last sub-step or continued from it, is
      // already off the face ends the march: the node is outside. (Its iterate left the
      // margin, or Newton stalled on the surface extended past a domain edge, which need not
      // go on.) Otherwise try finer sub-steps.
      if (!s_.contains(g) || (prev != uk.from_at && !s_.contains(prev))) {
        if (auto tr = traced(c_.res)) return tr;
        c_.res.status = SolveStatus::kLeftFace;
        c_.res.extended = false;
        c_.res.reason = "outside";
        return c_.res;
      }
    }
    return std::nullopt;
  }

  // No march solved the step: the first attempt's verdict, unless the traced section (the
  // base path) tells a section that turns back or closes within rho (the path ends) from one
  // that leaves the face (outside), and finds the point where the section turns too tightly
  // for the march; or unless the section misses the face (outside). With Unmarched::kNothing,
  // the first attempt's verdict as it is.
  SolveResult unmarched(const SolveResult& first) {
    SolveResult out = first;
    out.iterations = c_.res.iterations;
    out.evaluations = c_.res.evaluations;
    if (unmarched_ == Unmarched::kNothing) return out;
    if (auto tr = traced(out)) return *tr;
    if (section_misses_face(out.evaluations)) {
      out.status = SolveStatus::kLeftFace;
      out.extended = false;
      out.reason = "outside";
    }
    return out;
  }

  // No point of the face lies on the circle where the plane meets the sphere when each of
  // kSectionSamples points on it lies further from the face than the longest distance from a
  // point of the circle to the nearest sample (their nearest points of the face found from
  // the last one and from x0): the plane section through x0 closes, or leaves the face,
  // within rho of it (a face narrower than the step). The step has no place on the face.
  bool section_misses_face(int& evaluations) const {
    const Vec3 w = pn_.cross(t_);
    const double reach = 2.0 * rho_ * std::sin(kPi / (2.0 * kSectionSamples));
    SurfaceLocation seed = at0_;
    bool misses = true;
    for (int k = 0; k < kSectionSamples && misses; ++k) {
      const double th = 2.0 * kPi * k / kSectionSamples;
      const Vec3 q = x0_ + rho_ * (std::cos(th) * t_ + std::sin(th) * w);
      Foot f = foot_near(s_, st_, q, seed, evaluations);
      if (seed != at0_) {
        const Foot g = foot_near(s_, st_, q, at0_, evaluations);
        if (g.ok && (!f.ok || (g.p - q).norm() < (f.p - q).norm())) f = g;
      }
      misses = f.ok && (f.p - q).norm() > reach;
      seed = f.at;
    }
    return misses;
  }

  const DrapeSurface& s_;
  const Vec3& x0_;
  const SurfaceLocation& at0_;
  const SurfaceEval1& e0_;
  const Vec3& n0_;
  const Vec3& pn_;
  const Vec3& t_;
  const double rho_;
  const SolverSettings& st_;
  const Unmarched unmarched_;
  Ctx c_;
  UvDirection ud_;
  double rad_ = 0.0;  // the sphere's radius: rho, or a march's sub-step
  PlaneSphereResidual resid_{x0_, pn_, rad_};
};

// The tangent of the plane/surface intersection curve at x0, oriented forward: the exact
// first-order direction of the path (eqs. 7-8 project the previous direction instead, which
// is used where the plane is tangent to the surface).
Vec3 base_path_tangent(const Vec3& n0, const Vec3& pn, const Vec3& fwd) {
  // Sine of the angle between base plane and tangent plane below which the plane is taken
  // as tangent to the surface (no intersection curve direction).
  constexpr double kTangentPlaneSin = 1e-6;
  Vec3 t = n0.cross(pn);
  if (t.norm() > kTangentPlaneSin) {
    t.normalize();
    if (t.dot(fwd) < 0) t = -t;
  } else {
    t = (fwd - fwd.dot(pn) * pn).normalized();
  }
  return t;
}

}  // namespace

SolveResult plane_sphere_core(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0,
                              const SurfaceEval1& e0, const Vec3& n0, const Vec3& pn, const Vec3& t,
                              double rho, const SolverSettings& st, Unmarched unmarched) {
  return PlaneSphere(s, x0, at0, e0, n0, pn, t, rho, st, unmarched).run();
}

namespace {

// Solvers 1 and 3 from the known point x0 (at at0), a step of rho: `plane` gives the plane's
// unit normal pn and the unit tangent t from the face normal n0 there, or why the step is
// invalid.
template <class Plane>
SolveResult from_known_point(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0,
                             double rho, const SolverSettings& st, Unmarched unmarched,
                             Plane&& plane) {
  SolveResult bad;
  const SurfaceEval1 e0 = s.eval1(at0);
  if (!e0.ok) {
    bad.reason = "the known point is not on the surface";
    return bad;
  }
  const Vec3 n0 = face_normal(s, at0, e0);
  Vec3 pn, t;
  if (const char* why = plane(n0, pn, t)) {
    bad.reason = why;
    return bad;
  }
  SolveResult r = plane_sphere_core(s, x0, at0, e0, n0, pn, t, rho, st, unmarched);
  ++r.evaluations;
  return r;
}

}  // namespace

}  // namespace solvers

SolveResult solve_base_path(const DrapeSurface& s, const BasePathStep& step,
                            const SolverSettings& st) {
  const Vec3 pn = step.plane_normal.normalized();
  const Vec3 fwd = step.forward.normalized();
  if (!pn.allFinite() || !fwd.allFinite() || !(step.distance > 0.0)) {
    SolveResult bad;
    bad.reason = "invalid base-path step";
    return bad;
  }
  return solvers::from_known_point(s, step.from, step.from_at, step.distance, st,
                                   solvers::Unmarched::kTrace,
                                   [&](const Vec3& n0, Vec3& plane, Vec3& t) -> const char* {
                                     plane = pn;
                                     t = solvers::base_path_tangent(n0, pn, fwd);
                                     return nullptr;
                                   });
}

SolveResult solve_plane_sphere(const DrapeSurface& s, const PlaneSphereStep& step,
                               const SolverSettings& st) {
  if (!(step.radius > 0.0) || !step.direction.allFinite()) {
    SolveResult bad;
    bad.reason = "invalid plane-sphere step";
    return bad;
  }
  // The plane through the normal and the step's direction.
  return solvers::from_known_point(
      s, step.center, step.center_at, step.radius, st,
      step.march_only ? solvers::Unmarched::kNothing : solvers::Unmarched::kTrace,
      [&](const Vec3& n, Vec3& plane, Vec3& t) -> const char* {
        t = step.direction - step.direction.dot(n) * n;
        if (!(t.norm() > 0.0)) return "the step direction is normal to the surface";
        t.normalize();
        plane = n.cross(t);
        return nullptr;
      });
}

}  // namespace plyfit
