// A ply's seed, rosette and angle turned into the paper's initial conditions
// (ply_definition.hpp).
#include <plyfit/kernel/ply_definition.hpp>

#include <cmath>

namespace plyfit {

namespace {

// Until types.hpp gives them (one definition for the kernel).
constexpr double kHalfTurn = 3.14159265358979323846;
constexpr double kDegreesPerRadian = 180.0 / kHalfTurn;

/// `v` turned by `angle` about the unit axis `n` (Rodrigues), counter-clockwise seen from +n.
Vec3 turned_about(const Vec3& v, const Vec3& n, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * n.cross(v) + (1.0 - c) * n.dot(v) * n;
}

/// The signed angle from `a` to `b` about the unit normal `n` (both on its tangent plane).
double angle_about(const Vec3& a, const Vec3& b, const Vec3& n) {
  return std::atan2(a.cross(b).dot(n), a.dot(b));
}

/// The frame at `at` with its warp along `warp` (unit, tangent), measured from the rosette.
Result<PlyFrame> frame_with_warp(const MoldSurface& mold, const SurfaceLocation& at,
                                 const Vec3& warp, const Vec3& rosette, const Tolerances& tol) {
  PlyFrame f;
  f.at = at;
  f.point = mold.eval1(at).p;
  const SurfaceNormal sn = mold.normal(at);
  if (!sn.ok) return Error{ErrorCode::kStartNoNormal, "seed"};
  f.normal = sn.n;
  auto zero = rosette_zero(rosette, f.normal, tol);
  if (!zero) return zero.error();
  f.zero = *zero;
  f.warp = warp;
  f.weft = warp.cross(f.normal).normalized();
  f.angle = angle_about(f.zero, f.warp, f.normal);
  return f;
}

}  // namespace

Result<Vec3> rosette_zero(const Vec3& rosette, const Vec3& n, const Tolerances& tol) {
  if (!rosette.allFinite() || !(rosette.norm() > 0.0))
    return Error{ErrorCode::kRosetteZero, "rosette"};
  const Vec3 r = rosette.normalized();
  const Vec3 t = r - r.dot(n) * n;
  if (!(t.norm() >= tol.rosette_min_sin))
    return Error{ErrorCode::kRosetteAlongNormal,
                 "rosette",
                 {std::asin(std::min(t.norm(), 1.0)) * kDegreesPerRadian}};
  return t.normalized();
}

Result<PlyFrame> ply_frame(const MoldSurface& mold, const PlyDefinition& def,
                           const Tolerances& tol) {
  if (!def.seed.allFinite()) return Error{ErrorCode::kSeedNotFinite, "seed"};
  if (!(std::abs(def.angle) <= kHalfTurn)) return Error{ErrorCode::kPlyAngleRange, "ply-angle"};
  const Projection pr = mold.project(def.seed);
  const double half = 0.5 * mold.size();
  if (!pr.ok || !(pr.distance <= half))
    return Error{ErrorCode::kSeedOffMold, "seed", {pr.ok ? pr.distance : -1.0, half}};
  const SurfaceNormal sn = mold.normal(pr.at);
  if (!sn.ok) return Error{ErrorCode::kStartNoNormal, "seed"};
  auto zero = rosette_zero(def.rosette, sn.n, tol);
  if (!zero) return zero.error();
  auto f = frame_with_warp(mold, pr.at, turned_about(*zero, sn.n, def.angle), def.rosette, tol);
  if (!f) return f.error();
  f->point = pr.point;
  f->moved = pr.distance;
  return f;
}

Result<DrapeProblem> ply_problem(const MoldSurface& mold, const PlyDefinition& def, PlySpec cloth,
                                 const Tolerances& tol) {
  auto f = ply_frame(mold, def, tol);
  if (!f) return f.error();
  DrapeProblem pb;
  pb.ply = std::move(cloth);
  pb.ply.base_dir = Vec2(0.0, 1.0);
  pb.ply.sweeps = {Vec2(1.0, 0.0), Vec2(-1.0, 0.0)};
  pb.start = f->point;
  // The plane through the seed holding the warp and the normal: its normal is the weft.
  pb.base_normal = f->weft;
  // Ply +x (right of the warp seen from outside) is the weft direction warp x n.
  pb.sweeps = {f->weft, -f->weft};
  return pb;
}

Result<DrapeProblem> turned_problem(const MoldSurface& mold, DrapeProblem problem, double angle) {
  if (!(std::abs(angle) <= kHalfTurn)) return Error{ErrorCode::kPlyAngleRange, "ply-angle"};
  if (angle == 0.0) return problem;
  if (!problem.start.allFinite()) return Error{ErrorCode::kStartNotFinite, "start3d"};
  const Projection pr = mold.project(problem.start);
  if (!pr.ok) return Error{ErrorCode::kStartNotProjected, "start3d"};
  const SurfaceNormal sn = mold.normal(pr.at);
  if (!sn.ok) return Error{ErrorCode::kStartNoNormal, "start3d"};
  problem.base_normal = turned_about(problem.base_normal, sn.n, angle);
  for (Vec3& w : problem.sweeps) w = turned_about(w, sn.n, angle);
  return problem;
}

Result<PlyFrame> draped_frame(const MoldSurface& mold, const DrapeResult& result,
                              const Vec3& rosette, const Tolerances& tol) {
  if (!result.ply) return Error{ErrorCode::kInternal, "drape result without a ply"};
  const SurfaceNormal sn = mold.normal(result.start_at);
  if (!sn.ok) return Error{ErrorCode::kStartNoNormal, "start3d"};
  // The warp (ply +y) is the base path turned in the ply from its direction to +y; the frame
  // (x, y, n) is right-handed on the part, so a turn in the ply is the same turn about n.
  const Vec2 b = result.ply->base_dir();
  const double to_warp = std::atan2(b.x(), b.y());
  Vec3 t = result.base_tangent - result.base_tangent.dot(sn.n) * sn.n;
  if (!(t.norm() > 0.0)) return Error{ErrorCode::kBaseNormalTangent, "base-normal"};
  const Vec3 warp = turned_about(t.normalized(), sn.n, to_warp);
  auto f = frame_with_warp(mold, result.start_at, warp, rosette, tol);
  if (!f) return f.error();
  f->point = result.start_point;
  return f;
}

}  // namespace plyfit
