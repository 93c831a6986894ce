// The trace of a plane's section of the surface (plane_sphere.hpp: trace_section).
#include "drape/solvers/newton.hpp"
#include "drape/solvers/plane_sphere.hpp"
#include "drape/solvers/tangent.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::solvers {

namespace {

// Steps of kTraceStepRel of the link at first, halved while the section's tangent turns by
// more than kTraceTurnMax radians in one step or Newton fails, down to kTraceMinStepRel of
// the link; at most kTraceMaxSteps steps. The section ends where the plane comes within
// kSectionEndSin (the sine of the angle) of the surface's tangent plane: a point where the
// section stops, or crosses itself.
constexpr double kTraceStepRel = 1.0 / 8.0;
constexpr double kTraceMinStepRel = 1.0 / 4096.0;
constexpr double kTraceTurnMax = 0.35;
constexpr int kTraceMaxSteps = 512;
constexpr double kSectionEndSin = 1e-3;

class SectionTrace {
 public:
  SectionTrace(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0, const Vec3& pn,
               const Vec3& t, double rho, const SolverSettings& st)
      : s_(s), x0_(x0), pn_(pn), rho_(rho), c_(s, st), at_(at0), p_(x0), t_(t) {
    c_.eps = residual_tolerance(s, st, x0, rho);
    h_ = kTraceStepRel * rho;
    h_min_ = kTraceMinStepRel * rho;
  }

  std::optional<SolveResult> run() {
    for (int step = 0; step < kTraceMaxSteps; ++step) {
      const SurfaceEval1 e = s_.eval1(at_);
      ++c_.res.evaluations;
      if (!e.ok) return std::nullopt;
      Vec3 tn;
      if (!section_tangent(face_normal(s_, at_, e), t_, tn))
        return ends("the step's plane touches the surface ahead: its section ends within one link");
      Vec2 dir_uv;
      if (!metric_direction(e, tn, dir_uv)) return std::nullopt;
      bool sharp = false;
      const bool converged = step_onto_section(tn, dir_uv);
      const Vec3 t_next = converged ? turned_tangent(tn, sharp) : tn;
      if (!converged || (sharp && h_ > h_min_)) {
        if (h_ > h_min_) {
          h_ *= 0.5;
          continue;
        }
        // Newton fails at the smallest step: off the face's margin, outside; else unknown.
        if (c_.res.status == SolveStatus::kLeftFace) return outside();
        return std::nullopt;
      }
      // (A turn sharper than kTraceTurnMax at the smallest step is a corner of the section, at
      // a crease of a shell: stepped over; whether it turns back the distance from x0 tells.)
      const SurfaceLocation at_next = c_.res.at;
      const Vec3 p_next = c_.res.point;
      // Past the face's edge (not into a hole of it, under which the path goes on) the section
      // has left the face before reaching rho: outside, as the march finds at an edge.
      if (!s_.contains(at_next) && !s_.in_hole(at_next)) return outside();
      const double chord_next = (p_next - x0_).norm();
      if (chord_next >= rho_) {
        const Crossing k = solve_crossing(at_next, p_next, chord_next);
        if (k == Crossing::kSolved) return c_.res;
        if (k == Crossing::kGiveUp) return std::nullopt;
        continue;
      }
      if (chord_next < chord_)
        return ends(
            "the section of the step's plane turns back within one link (the plane nearly "
            "touches the surface ahead)");
      at_ = at_next;
      p_ = p_next;
      chord_ = chord_next;
      t_ = t_next;
      h_ = std::min(2.0 * h_, kTraceStepRel * rho_);
    }
    return std::nullopt;
  }

 private:
  enum class Crossing { kSolved, kGiveUp, kRetry };

  // The section's unit tangent at a point of normal n, oriented along t; false where the
  // plane touches the surface.
  bool section_tangent(const Vec3& n, const Vec3& t, Vec3& tn) const {
    tn = n.cross(pn_);
    if (!(tn.norm() > kSectionEndSin)) return false;
    tn.normalize();
    if (tn.dot(t) < 0.0) tn = -tn;
    return true;
  }

  // A step of h_ along tn from p_, then Newton back onto the plane on the plane through the
  // predicted point square to tn; true when it converged (c_.res, c_.last).
  bool step_onto_section(const Vec3& tn, const Vec2& dir_uv) {
    const Vec3 q = p_ + h_ * tn;
    auto resid = [&](const SurfaceEval1& ev, Vec2& f, Eigen::Matrix2d& J) {
      f << pn_.dot(ev.p - x0_), tn.dot(ev.p - q);
      J << pn_.dot(ev.du), pn_.dot(ev.dv), tn.dot(ev.du), tn.dot(ev.dv);
    };
    const SurfaceLocation guess = s_.locate(at_, at_.uv + h_ * dir_uv);
    setup_margins(c_, at_, guess);
    if (newton(c_, guess, resid)) return true;
    // From the predicted point's nearest point of the face (no step cap: across a band of
    // the parameters where the surface barely moves, a CAD patch's collapsed strip, which
    // Newton's capped steps crawl into and stall at).
    const Foot fq = foot_near(s_, c_.st, q, at_, c_.res.evaluations);
    if (!(fq.ok && fq.at != at_ && (fq.p - q).norm() < h_)) return false;
    setup_margins(c_, at_, fq.at);
    return newton(c_, fq.at, resid);
  }

  // The section's tangent at the converged point, oriented along tn; `sharp` when it turned
  // by more than kTraceTurnMax.
  Vec3 turned_tangent(const Vec3& tn, bool& sharp) const {
    Vec3 t_next = tn;
    Vec3 tt = face_normal(s_, c_.res.at, c_.last).cross(pn_);
    if (tt.norm() > kSectionEndSin) {
      tt.normalize();
      t_next = tt.dot(tn) < 0.0 ? Vec3(-tt) : tt;
    }
    sharp = std::acos(std::clamp(t_next.dot(tn), -1.0, 1.0)) > kTraceTurnMax;
    return t_next;
  }

  // The section passes distance rho between p_ and p_next: solved there (kSolved, c_.res),
  // else traced closer to the crossing (kRetry, a halved step) down to the smallest step.
  Crossing solve_crossing(const SurfaceLocation& at_next, const Vec3& p_next, double chord_next) {
    const double w = (rho_ - chord_) / std::max(chord_next - chord_, 1e-300);
    const SurfaceLocation g = s_.locate(at_, at_.uv + w * s_.delta(at_, at_next));
    const PlaneSphereResidual sphere{x0_, pn_, rho_};
    setup_margins(c_, at_, g);
    if (newton(c_, g, sphere) && (c_.res.point - p_).norm() <= 2.0 * (p_next - p_).norm()) {
      settle(c_, sphere);
      classify_converged(c_);
      return Crossing::kSolved;
    }
    if (h_ <= h_min_) return Crossing::kGiveUp;
    h_ *= 0.5;
    c_.res.status = SolveStatus::kFailed;
    return Crossing::kRetry;
  }

  SolveResult ends(const char* reason) const {
    SolveResult r;
    r.status = SolveStatus::kFailed;
    r.section_ends = true;
    r.reason = reason;
    r.iterations = c_.res.iterations;
    r.evaluations = c_.res.evaluations;
    return r;
  }

  SolveResult outside() const {
    SolveResult r;
    r.status = SolveStatus::kLeftFace;
    r.reason = "outside";
    r.iterations = c_.res.iterations;
    r.evaluations = c_.res.evaluations;
    return r;
  }

  const DrapeSurface& s_;
  const Vec3& x0_;
  const Vec3& pn_;
  const double rho_;
  Ctx c_;
  SurfaceLocation at_;  // the last traced point, its position, its distance from x0
  Vec3 p_;
  double chord_ = 0.0;
  Vec3 t_;  // the section's tangent there
  double h_ = 0.0, h_min_ = 0.0;
};

}  // namespace

std::optional<SolveResult> trace_section(const DrapeSurface& s, const Vec3& x0,
                                         const SurfaceLocation& at0, const Vec3& pn, const Vec3& t,
                                         double rho, const SolverSettings& st) {
  return SectionTrace(s, x0, at0, pn, t, rho, st).run();
}

}  // namespace plyfit::solvers
