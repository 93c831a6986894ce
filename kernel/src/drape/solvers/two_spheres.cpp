// Solver 2 (§5.2, eqs. 9-11): the node at the rest lengths from its weft and warp neighbours.
#include "drape/solvers/newton.hpp"
#include "drape/solvers/plane_sphere.hpp"
#include "drape/solvers/tangent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace plyfit::solvers {

namespace {

// Eq. (12) with gamma_max = pi - gamma_min.
bool past_shear_limit(double angle, double gamma_min) {
  return angle < gamma_min || angle > kPi - gamma_min;
}

// The fallback across creases samples this many points on each quarter of the spheres'
// circle of intersection (the requested side's half first, then the other half: where the
// normals at a and b disagree, at a pinch of the face, "the requested side" of the circle may
// hold no solution while the other does, on the requested branch) and bisects the sign change
// for at most this many steps; a circle smaller than kCircleMinRel of the radii (the spheres
// just touch) is not tried.
constexpr int kCircleSamples = 8;
constexpr int kCircleIterations = 100;
constexpr double kCircleMinRel = 1e-6;
// A sign change of the signed distance on that circle holds a crossing of the surface only
// where the circle's point found in it lies within this fraction of the circle's radius of
// the face (or within eq. (9)'s tolerance): not where the nearest point is on a face edge.
constexpr double kCircleNearRel = 1e-3;
// The sides of the line a-b are told apart sideways, across the mean of the normals at a and
// b, while that mean (of two unit normals) is at least this long: the normals turn by less
// than about 174 degrees between a and b.
constexpr double kMeanNormalMin = 0.1;

// The residual of a point on the sphere of radius ra about a and on that of radius rb about b.
struct TwoSphereResidual {
  const Vec3& a;
  const Vec3& b;
  double ra, rb;
  void operator()(const SurfaceEval1& e, Vec2& f, Eigen::Matrix2d& J) const {
    const Vec3 da = e.p - a, db = e.p - b;
    f << (da.squaredNorm() - ra * ra) / (2 * ra), (db.squaredNorm() - rb * rb) / (2 * rb);
    J << da.dot(e.du) / ra, da.dot(e.dv) / ra, db.dot(e.du) / rb, db.dot(e.dv) / rb;
  }
};

// The spheres' circle of intersection: centre m, radius h, spanned by the unit w1 (towards
// the requested side) and n.
struct Circle {
  Vec3 m, w1, n;
  double h = 0.0;
  SurfaceLocation seed;  // where the last nearest point of the face was found
  Vec3 at(double th) const { return Vec3(m + h * (std::cos(th) * w1 + std::sin(th) * n)); }
};

class TwoSpheres {
 public:
  TwoSpheres(const DrapeSurface& s, const TwoSphereStep& step, const SolverSettings& st)
      : s_(s),
        step_(step),
        st_(st),
        c_(s, st),
        a_(step.a),
        b_(step.b),
        ra_(step.ra),
        rb_(step.rb),
        L_((step.b - step.a).norm()),
        want_(step.side >= 0 ? 1.0 : -1.0),
        e_ab_((b_ - a_) / L_),
        resid_{a_, b_, ra_, rb_} {}

  // The guesses in turn (the caller's, the planar solution, points on each sphere), then the
  // fallbacks: the circle of intersection, leaving the face, no point fitting both links, the
  // shear limit.
  SolveResult run() {
    if (!spheres_meet()) return c_.res;
    c_.eps = residual_tolerance(s_, st_, a_, std::max(ra_, rb_));
    // 1. The caller's guess (eqs. 10-11).
    if (step_.guess && attempt(s_.locate(step_.a_at, *step_.guess))) return c_.res;
    Vec3 p3;
    const SurfaceEval1 ea = s_.eval1(step_.a_at);
    ++c_.res.evaluations;
    if (planar_target(ea, p3) && (planar_guess(ea, p3) || sphere_point_guesses(ea, p3)))
      return c_.res;
    // 4. Across a crease (a shell's G0 shared edge) Newton on either face may stall at the
    //    edge (the residual has a kink there). The spheres' circle of intersection, on the
    //    requested side of the line a-b, crosses the surface where its signed distance to it
    //    changes sign: found by bisection on the circle's angle.
    if (c_.res.status != SolveStatus::kLeftFace && attempt_circle()) return c_.res;
    if (c_.res.status == SolveStatus::kFailed && left_) return left_face();
    if (c_.res.status == SolveStatus::kFailed && no_point_fits()) return c_.res;
    near_tangent_shear_limit();
    if (c_.res.status == SolveStatus::kConverged) c_.res.status = SolveStatus::kFailed;
    return c_.res;
  }

 private:
  // False (c_.res says why) for an invalid step or spheres that do not meet.
  bool spheres_meet() {
    if (!(ra_ > 0.0) || !(rb_ > 0.0) || !(L_ > 0.0)) {
      c_.res.reason = "invalid two-sphere step";
      return false;
    }
    if (L_ <= ra_ + rb_) return true;
    c_.res.reason = "no intersection (the spheres do not meet)";
    // The thread angle would have to pass pi: beyond any gamma_max (eq. 12).
    if (st_.gamma_min > 0.0) {
      c_.res.status = SolveStatus::kShearLimit;
      c_.res.shear_stop = ShearStop::kLock;
      c_.res.thread_angle = kPi;
      c_.res.reason = "thread angle beyond the shear limit (the spheres do not meet)";
    }
    return false;
  }

  // The distance x of the circle's centre from a along a-b, and its radius h.
  void circle_offsets(double& x, double& h) const {
    x = (L_ * L_ + ra_ * ra_ - rb_ * rb_) / (2 * L_);
    h = std::sqrt(std::max(ra_ * ra_ - x * x, 0.0));
  }

  // Planar two-circle solution in the tangent plane at a, on the requested side: a 3D target
  // on the right branch by construction.
  bool planar_target(const SurfaceEval1& ea, Vec3& p3) const {
    if (!ea.ok) return false;
    const Vec3 n = face_normal(s_, step_.a_at, ea);
    Vec3 e = b_ - a_;
    e -= e.dot(n) * n;
    const double le = e.norm();
    if (!(le > 0.0)) return false;
    e /= le;
    const double x = (le * le + ra_ * ra_ - rb_ * rb_) / (2 * le);
    const double h = std::sqrt(std::max(ra_ * ra_ - x * x, 0.0));
    p3 = a_ + x * e + want_ * h * n.cross(e);
    return true;
  }

  // 2. The planar solution mapped to (u, v) to first order, if that model is trustworthy (the
  //    surface point at the guess near the planar target); a trusted model that leaves the
  //    face is the answer. True when c_.res is the answer.
  bool planar_guess(const SurfaceEval1& ea, const Vec3& p3) {
    Vec2 dir;
    if (!metric_direction(ea, p3 - a_, dir)) return false;
    const SurfaceLocation g = s_.locate(step_.a_at, step_.a_at.uv + dir * (p3 - a_).norm());
    const SurfaceEval1 eg = s_.eval1(g);
    ++c_.res.evaluations;
    const bool trusted = eg.ok && (eg.p - p3).norm() <= kTrustRatio * ra_;
    if (!trusted) return false;
    return attempt(g) || c_.res.status == SolveStatus::kLeftFace;
  }

  // 3. A point on the surface at distance ra from a towards the planar target, found by the
  //    marching plane-sphere solver, then the same from b: robust guesses where the
  //    parametrisation is far from linear. True when one converged on the branch.
  bool sphere_point_guesses(const SurfaceEval1& ea, const Vec3& p3) {
    for (int from_b = 0; from_b < 2; ++from_b) {
      const Vec3& o = from_b ? b_ : a_;
      const SurfaceLocation& o_at = from_b ? step_.b_at : step_.a_at;
      const double r = from_b ? rb_ : ra_;
      const SurfaceEval1 eo = from_b ? s_.eval1(o_at) : ea;
      if (!eo.ok) continue;
      const Vec3 n = face_normal(s_, o_at, eo);
      Vec3 t = p3 - o;
      t -= t.dot(n) * n;
      if (!(t.norm() > 0.0)) continue;
      t.normalize();
      const SolveResult q = plane_sphere_core(s_, o, o_at, eo, n, n.cross(t), t, r, st_);
      c_.res.evaluations += q.evaluations;
      if (q.status != SolveStatus::kConverged &&
          !(q.status == SolveStatus::kLeftFace && q.extended))
        continue;
      if (attempt(q.at)) return true;
    }
    return false;
  }

  // The requested branch: across the line a-b from the cell's fourth corner where a, b and p
  // are not on one face and the corner is known; else on the `side` about the normal at p.
  bool across_from_corner(const SurfaceLocation& p_at) const {
    return step_.corner && (step_.a_at.face != step_.b_at.face || p_at.face != step_.a_at.face);
  }

  // The offset of v from the line a-b that tells its sides apart: along the sideways
  // direction, perpendicular to the line and to the mean of the normals at a and b. (The full
  // perpendicular adds the sag of the surface below the chord a-b, the same on both sides,
  // which on a curved face outweighs the sideways offsets of a cell sheared nearly flat.)
  // Where the normals nearly cancel (a knife edge), the full perpendicular.
  Vec3 offset(const Vec3& v) {
    if (!side_dir_known_) {
      side_dir_known_ = true;
      const SurfaceEval1 ea = s_.eval1(step_.a_at), eb = s_.eval1(step_.b_at);
      c_.res.evaluations += 2;
      if (ea.ok && eb.ok) {
        const Vec3 w =
            (face_normal(s_, step_.a_at, ea) + face_normal(s_, step_.b_at, eb)).cross(e_ab_);
        if (w.norm() > kMeanNormalMin) side_dir_ = w.normalized();
      }
    }
    return side_dir_ ? Vec3(v.dot(*side_dir_) * *side_dir_) : Vec3(v - v.dot(e_ab_) * e_ab_);
  }

  bool on_branch(const Vec3& p, const Vec3& n, const SurfaceLocation& p_at) {
    if (across_from_corner(p_at)) return offset(p - a_).dot(offset(*step_.corner - a_)) < 0.0;
    return n.dot((b_ - a_).cross(p - a_)) * want_ > 0.0;
  }

  // A solution on the requested branch: its thread angle, the in-face test, eq. (12).
  void finish() {
    const Vec3 pa = a_ - c_.res.point, pb = b_ - c_.res.point;
    c_.res.thread_angle = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    classify_converged(c_);
    if (c_.res.status == SolveStatus::kConverged && st_.gamma_min > 0.0 &&
        past_shear_limit(c_.res.thread_angle, st_.gamma_min)) {
      c_.res.status = SolveStatus::kShearLimit;
      c_.res.shear_stop = ShearStop::kLock;
      c_.res.reason = "thread angle beyond the shear limit";
    }
  }

  // Newton from g; true when it converged on the requested branch (c_.res classified). An
  // attempt that left the face is kept: if no attempt finds the node on the face, it is
  // outside (a later attempt may find only the other branch, which lies on the face).
  bool attempt(const SurfaceLocation& g) {
    setup_margins(c_, step_.a_at, g);
    const double mb = c_.scaled_norm(step_.b_at, s_.delta(step_.b_at, g));
    c_.margin = std::max(c_.margin, st_.tol.extension_steps * mb);
    c_.max_step = std::max(c_.max_step, kStepCapSteps * mb);
    if (!newton(c_, g, resid_)) {
      if (c_.res.status == SolveStatus::kLeftFace && !left_) left_ = c_.res;
      return false;
    }
    settle(c_, resid_);
    if (!on_branch(c_.res.point, face_normal(s_, c_.res.at, c_.last), c_.res.at)) {
      c_.res.status = SolveStatus::kFailed;
      c_.res.reason = "only the folded branch was found";
      c_.res.folded_branch = true;
      return false;
    }
    finish();
    return true;
  }

  // The circle of intersection, its w1 on the requested side (across a crease, where the
  // normals are no guide, the side away from the corner); false where it is too small.
  bool circle_frame(Circle& k) {
    const SurfaceEval1 ea = s_.eval1(step_.a_at), eb = s_.eval1(step_.b_at);
    c_.res.evaluations += 2;
    if (!ea.ok || !eb.ok) return false;
    const Vec3 e = e_ab_;
    Vec3 n = face_normal(s_, step_.a_at, ea) + face_normal(s_, step_.b_at, eb);
    n -= n.dot(e) * e;
    double x = 0.0;
    circle_offsets(x, k.h);
    if (!(n.norm() > 0.0) || !(k.h > kCircleMinRel * std::min(ra_, rb_))) return false;
    n.normalize();
    k.m = a_ + x * e;
    k.w1 = want_ * n.cross(e);
    k.n = n;
    if (step_.corner && step_.a_at.face != step_.b_at.face) {
      const Vec3 away = -offset(*step_.corner - a_);
      if (away.norm() > 0.0) {
        k.w1 = away.normalized();
        k.n = e.cross(k.w1);
      }
    }
    k.seed = step_.a_at;
    return true;
  }

  // The signed distance of the circle's point at angle th from the face, along the normal at
  // its nearest point f: the nearest of the feet from the last foot and from a and b (a knife
  // edge has a local nearest point on each of its faces); NaN where none is found.
  double signed_distance(Circle& k, double th, Foot& f) {
    const Vec3 q = k.at(th);
    f = foot_near(s_, st_, q, k.seed, c_.res.evaluations);
    for (const SurfaceLocation* from : {&step_.a_at, &step_.b_at}) {
      if (*from == k.seed) continue;
      const Foot g = foot_near(s_, st_, q, *from, c_.res.evaluations);
      if (g.ok && (!f.ok || (g.p - q).norm() < (f.p - q).norm())) f = g;
    }
    if (!f.ok) return std::numeric_limits<double>::quiet_NaN();
    k.seed = f.at;
    return (q - f.p).dot(f.n);
  }

  // Illinois (regula falsi) on the circle's angle in [lo, hi], bounded: the angle found (f its
  // foot), NaN where the distance is undefined.
  double illinois(Circle& k, double lo, double hi, double flo, double fhi, Foot& f) {
    double th = lo;
    int side = 0;
    for (int it = 0; it < kCircleIterations && hi != lo; ++it) {
      th = (lo * fhi - hi * flo) / (fhi - flo);
      const double fth = signed_distance(k, th, f);
      if (!(fth == fth)) return fth;
      if (std::abs(fth) < 0.5 * c_.eps) break;
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
    return th;
  }

  // The sign change in [lo, hi], then Newton from the point found, or that point itself if it
  // meets eq. (9)'s tolerance. A sign change can be false: where the nearest point of the face
  // lies on its edge (a free edge, or an edge where a derivative vanishes) the normal there
  // does not measure the distance, and the signed distance changes sign away from the
  // surface. The bracket counts only where the circle's point found in it lies on the surface
  // (within kCircleNearRel of h, or eq. (9)'s tolerance).
  bool solve_in_bracket(Circle& k, double lo, double hi, double flo, double fhi, Foot f) {
    const double th = illinois(k, lo, hi, flo, fhi, f);
    if (!(th == th)) return false;
    if (!f.ok || (k.at(th) - f.p).norm() > std::max(c_.eps, kCircleNearRel * k.h)) return false;
    if (attempt(f.at)) return true;
    const SurfaceEval1 ef = s_.eval1(f.at);
    ++c_.res.evaluations;
    if (!ef.ok) return false;
    Vec2 r;
    Eigen::Matrix2d J;
    resid_(ef, r, J);
    // The point itself, on the requested branch only: the circle is searched all round, and
    // past a face's edge Newton from the other branch's crossing fails (left the face) where
    // that point still fits both links.
    if (!(r.cwiseAbs().sum() < c_.eps) || !on_branch(ef.p, face_normal(s_, f.at, ef), f.at))
      return false;
    c_.res.at = f.at;
    c_.res.point = ef.p;
    c_.res.residual = r.cwiseAbs().sum();
    c_.last = ef;
    finish();
    return true;
  }

  // The whole circle, sampled from the middle of the requested side's half (the planar
  // solution) outwards on both sides; the sign changes are tried nearest the middle first,
  // until one holds a solution (c_.res classified).
  bool attempt_circle() {
    Circle k;
    if (!circle_frame(k)) return false;
    Foot f0, f1;
    const double fmid = signed_distance(k, 0.0, f0);
    if (!(fmid == fmid)) return false;
    if (std::abs(fmid) < 0.5 * c_.eps && solve_in_bracket(k, 0.0, 0.0, fmid, fmid, f0)) return true;
    double prev_th[2] = {0.0, 0.0}, prev_f[2] = {fmid, fmid};
    Foot prev_foot[2] = {f0, f0};
    for (int j = 1; j <= 2 * kCircleSamples; ++j)
      for (int side = 0; side < 2; ++side) {
        const double th = (side ? -1.0 : 1.0) * 0.5 * kPi * j / kCircleSamples;
        const double f = signed_distance(k, th, f1);
        if (!(f == f)) return false;
        if ((f > 0.0) != (prev_f[side] > 0.0) &&
            solve_in_bracket(k, prev_th[side], th, prev_f[side], f, prev_foot[side]))
          return true;
        prev_th[side] = th;
        prev_f[side] = f;
        prev_foot[side] = f1;
      }
    return false;
  }

  // No attempt found the node on the face, one left it: outside (with every attempt's counts).
  SolveResult left_face() {
    const int iterations = c_.res.iterations, evaluations = c_.res.evaluations;
    c_.res = *left_;
    c_.res.iterations = iterations;
    c_.res.evaluations = evaluations;
    return c_.res;
  }

  // No point of the face fits both links when the spheres' circle of intersection (centre m,
  // radius h) passes the face at a distance: every point of the circle lies within h of m,
  // so a face whose nearest point to m is further than h from it misses the circle. With
  // the spheres meeting, the links, straight chords, would pass below a curved face: for a
  // weft and a warp link a cell sheared so nearly flat that the cloth stops there as at the
  // shear limit (its thread angle, fixed by the three lengths, is reported); for two links of
  // one thread, a thread that would have to stretch. True (c_.res says so) in that case.
  bool no_point_fits() {
    double x = 0.0, h = 0.0;
    circle_offsets(x, h);
    const Vec3 m = a_ + x * e_ab_;
    double gap = std::numeric_limits<double>::infinity();
    for (const SurfaceLocation* from : {&step_.a_at, &step_.b_at}) {
      const Foot f = foot_near(s_, st_, m, *from, c_.res.evaluations);
      gap = f.ok ? std::min(gap, (f.p - m).norm()) : -1.0;
      if (!(gap > h + c_.eps)) break;
    }
    if (!(gap > h + c_.eps)) return false;
    c_.res.no_point = true;
    c_.res.reason = "no point of the face fits both links (they would pass below the face)";
    if (st_.gamma_min > 0.0) {
      c_.res.status = SolveStatus::kShearLimit;
      c_.res.shear_stop = ShearStop::kFlatCell;
      c_.res.thread_angle =
          std::acos(std::clamp((ra_ * ra_ + rb_ * rb_ - L_ * L_) / (2 * ra_ * rb_), -1.0, 1.0));
      c_.res.reason =
          "no point of the face fits both links (the cell is sheared so flat that "
          "they pass below the curved face)";
    }
    return true;
  }

  // Near the shear limit the spheres meet almost tangentially and Newton may stall: eq. (12)
  // on the last iterate tells the shear limit from a plain failure.
  void near_tangent_shear_limit() {
    if (!(c_.res.status == SolveStatus::kFailed && st_.gamma_min > 0.0 && c_.res.point.allFinite()))
      return;
    const Vec3 pa = a_ - c_.res.point, pb = b_ - c_.res.point;
    const double g = std::atan2(pa.cross(pb).norm(), pa.dot(pb));
    if (pa.norm() > 0 && pb.norm() > 0 && past_shear_limit(g, st_.gamma_min)) {
      c_.res.status = SolveStatus::kShearLimit;
      c_.res.shear_stop = ShearStop::kLock;
      c_.res.thread_angle = g;
      c_.res.reason = "thread angle beyond the shear limit (near-tangent spheres)";
    }
  }

  const DrapeSurface& s_;
  const TwoSphereStep& step_;
  const SolverSettings& st_;
  Ctx c_;
  const Vec3 a_, b_;
  const double ra_, rb_, L_;
  const double want_;  // the requested side, +1 or -1
  const Vec3 e_ab_;    // the unit direction a -> b
  const TwoSphereResidual resid_;
  std::optional<Vec3> side_dir_;  // see offset()
  bool side_dir_known_ = false;
  std::optional<SolveResult> left_;  // the first attempt that left the face
};

}  // namespace

}  // namespace plyfit::solvers

namespace plyfit {

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
  return solvers::TwoSpheres(s, step, st).run();
}

}  // namespace plyfit
