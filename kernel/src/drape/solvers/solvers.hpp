#pragma once
/// \file The three mapping solvers of the paper (§5, §6.1): each intersects the surface with
/// two more surfaces (planes and spheres) by Newton's method on (u, v) with the analytic
/// Jacobian, eqs. (4)-(6). They return a result, never throw, never produce NaN.
///
/// Residuals are lengths: a plane gives F = n.(r - x0) with |n| = 1, a sphere of radius rho
/// about c gives F = (|r - c|^2 - rho^2) / (2 rho), which equals |r - c| - rho to first order.
/// The stop test is eq. (9), |F1| + |F2| < eps, with eps = newton_residual_rel * d (d the
/// spacing), floored at the rounding level of the residual: roundoff_rel times the largest
/// coordinate of the known point plus the face size plus the radius.

#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>
#include "surface/face.hpp"

#include <cstdint>
#include <optional>

namespace plyfit {

/// Outcome of one mapping solve.
enum class SolveStatus : std::uint8_t {
  kConverged,   ///< a point on the face satisfying both constraints
  kLeftFace,    ///< the solution (or the iterate) lies outside the face's domain or trims
  kShearLimit,  ///< eq. (12): the thread angle at the new node is below gamma_min or above
                ///< gamma_max = pi - gamma_min
  kFailed,      ///< no convergence within the iteration cap, or no intersection exists
};

/// Name of a status ("converged", "left_face", "shear_limit", "failed").
const char* to_string(SolveStatus s);

/// Which guard stopped a node at the shear limit (SolveStatus::kShearLimit): the lock's
/// (NodeStatus::kShearLimit) or a fold guard's (the cloth folds onto itself:
/// NodeStatus::kOverlap).
enum class ShearStop : std::uint8_t {
  kNone,
  /// Eq. (12): the thread angle at the node (SolveResult::thread_angle) passes gamma_min or
  /// pi - gamma_min; the drape tells a lock angle (kLock) from Tolerances::fold_angle
  /// (kFoldAngle) by that angle.
  kLock,
  kFoldAngle,
  /// No point of the face fits both links: the spheres' circle passes the face at a distance
  /// (the cell is sheared so flat that its links, chords, pass below the curved face).
  kFlatCell,
  /// The cell would fold: the node lies on the same side of the line between its two
  /// neighbours as the cell's fourth corner (the net around it is sheared past flat).
  kCellFolds,
  /// The node has one mapped neighbour and one stopped at the lock: its thread, continued
  /// straight past the stopped node, would fold over the cells left open.
  kBehindStop,
};
/// Reason code of a stop: "lock", "fold_angle", "flat_cell", "cell_folds", "behind_stop"
/// ("none" for kNone).
const char* to_string(ShearStop s);

/// Result of a mapping solve.
struct SolveResult {
  SolveStatus status = SolveStatus::kFailed;
  SurfaceLocation at;         ///< where the point lies (wrapped into closed domains)
  Vec3 point = Vec3::Zero();  ///< the 3D point
  int iterations = 0;         ///< Newton iterations
  int evaluations = 0;        ///< surface evaluations, line searches and restarts included
  double residual = 0.0;      ///< |F1| + |F2| at the returned point (model units)
  /// For kLeftFace: true when Newton converged on the surface extended past the face, so
  /// that at/point are the intersection there (used to find the exact boundary crossing).
  bool extended = false;
  /// For kFailed: set by the drape's scan, never by the solvers, where two fronts of cloth met
  /// at the node and disagree (NodeStatus::kConflict; `reason` says how).
  bool fronts_disagree = false;
  /// For the two-sphere solver: no point of the face fits both links, as shown by the
  /// spheres' circle of intersection passing the face at a distance (kShearLimit where the
  /// links are a weft and a warp link, else kFailed).
  bool no_point = false;
  /// For the two-sphere solver (kFailed): Newton converged only on the branch that folds the
  /// triangle (a, b, p) against the ply's orientation; `point` is that solution.
  bool folded_branch = false;
  /// For the base-path solver (kFailed): the base plane's section of the surface turns back
  /// towards the known point, or ends where the plane touches the surface, before it reaches
  /// the step's distance: no point ahead exists, and the path ends there (the plane nearly
  /// touches the surface ahead: its section curves with kappa_n / sin(theta), Meusnier).
  bool section_ends = false;
  /// Thread angle at the new node for the two-sphere solver (radians), else 0.
  double thread_angle = 0.0;
  /// For kShearLimit: the guard that stopped the node (kLock for any angle past gamma_min:
  /// the solvers know only SolverSettings::gamma_min; the drape sorts lock from fold angle).
  ShearStop shear_stop = ShearStop::kNone;
  const char* reason = "";  ///< why, for kFailed (and for kLeftFace: "outside" or "iterate")
};

/// Settings shared by the three solvers.
struct SolverSettings {
  double spacing = 1.0;    ///< d, the scale of every tolerance
  double gamma_min = 0.0;  ///< minimum thread angle, radians (eq. 12); 0 disables the test
  Tolerances tol;
};

/// The floor of eq. (9)'s tolerance for a solve near `where` with a sphere of `radius` (model
/// units): the rounding of the residual, Tolerances::roundoff_rel times the coordinates, the
/// surface's size and the radius, plus the surface's own evaluation rounding
/// (DrapeSurface::rounding). The solvers stop at max(newton_residual_rel * d, this): below it
/// the residual is rounding, and the node is solved.
double residual_floor(const DrapeSurface& surface, const Tolerances& tol, const Vec3& where,
                      double radius);

/// Solver 1 (eqs. 1-9): the next base-path point, on the base plane through `from` with
/// normal `plane_normal`, at distance `distance` from `from`, going forward along `forward`
/// (a 3D direction roughly along the path; the solution satisfies (p - from).forward > 0).
struct BasePathStep {
  Vec3 from;                ///< last known point x0 (on the surface)
  SurfaceLocation from_at;  ///< its location
  Vec3 plane_normal;        ///< base-plane normal (any length)
  Vec3 forward;             ///< direction of travel (any length)
  double distance = 1.0;    ///< d_xyz: rest length to the next point
};
/// Initial guess by eqs. (7)-(8): a step of `distance` along `forward` projected on the
/// tangent plane at x0, mapped to (u, v) with the local metric.
SolveResult solve_base_path(const DrapeSurface& surface, const BasePathStep& step,
                            const SolverSettings& settings);

/// Solver 2 (§5.2): the node at distance ra from `a` (its weft neighbour) and rb from `b`
/// (its warp neighbour). Of the two mirror solutions it returns the one with
/// side * n.((b - a) x (p - a)) > 0, n the face normal: the side that keeps the cell unfolded.
/// If Newton lands on the other branch it restarts from the mirrored guess.
struct TwoSphereStep {
  Vec3 a;
  SurfaceLocation a_at;
  double ra = 1.0;
  Vec3 b;
  SurfaceLocation b_at;
  double rb = 1.0;
  double side = 1.0;  ///< +1 or -1, see above
  /// Initial (u, v) in the chart (face) of `a` (eqs. 10-11), reached from a by
  /// DrapeSurface::locate; if absent, the planar two-circle solution in the tangent plane is
  /// used.
  std::optional<Vec2> guess;
  /// The cell's fourth corner (mapped), if known: the solution lies across the line a-b from
  /// it. Where a, b and the solution are not all on one face (a crease between them makes
  /// the normals disagree), this, not the normal, tells the branch.
  std::optional<Vec3> corner = std::nullopt;
};
SolveResult solve_two_spheres(const DrapeSurface& surface, const TwoSphereStep& step,
                              const SolverSettings& settings);

/// Initial guess of eqs. (10)-(11): each thread continued by its rest length from its last
/// known node along its previous segment (a_prev -> a, b_prev -> b) in (u, v), averaged; in
/// the chart of `a_at`. The four locations must share a chart (DrapeSurface::same_chart).
Vec2 two_sphere_guess(const DrapeSurface& surface, const SurfaceLocation& a_at,
                      const SurfaceLocation& a_prev_at, const Vec3& a, const Vec3& a_prev,
                      double ra, const SurfaceLocation& b_at, const SurfaceLocation& b_prev_at,
                      const Vec3& b, const Vec3& b_prev, double rb);

/// Solver 3 (§6.1, eq. 13): the node at distance `radius` from `center` in the plane through
/// `center` that contains the face normal there and `direction`; forward along `direction`.
/// Like solver 1, where the direct solve and the march fail it traces the plane's section
/// (section_ends where it turns back within the step).
struct PlaneSphereStep {
  Vec3 center;
  SurfaceLocation center_at;
  double radius = 1.0;
  Vec3 direction;  ///< tangent direction of the step (any length; projected on the tangent plane)
  /// Where the direct solve and the march fail, neither trace the section nor test it for a
  /// miss of the face: the march's verdict stands. For a caller that takes only a solution
  /// Newton reached (the flat pattern's outline): the tests only tell "outside" from a
  /// failure, and the trace finds a point only where the section turns too tightly for the
  /// march, at many times the cost of the solve.
  bool march_only = false;
};
SolveResult solve_plane_sphere(const DrapeSurface& surface, const PlaneSphereStep& step,
                               const SolverSettings& settings);

/// v rotated by `angle` (radians) about the unit `axis` (right hand).
Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle);

/// The (u, v) direction whose image J*a under the surface's first derivatives at a location
/// is the component of `dir` in the tangent plane (least squares), together with the location
/// to step from: at a degenerate point (a pole) the collapsed edge is searched for the
/// parameter whose non-vanishing derivative best matches `dir`; on a domain edge across which
/// the derivative vanishes but which is no pole (from_singular_edge), the step leaves the face
/// unless `dir` points into it, and starts from a point a short way across the edge. The
/// direction is scaled so that |J a| = 1 (a unit 3D step), in the chart of from_at.
struct UvDirection {
  SurfaceLocation from_at;
  Vec2 dir_uv = Vec2::Zero();
  bool ok = false;
  /// At a degenerate point: no direction the face offers (the fan of the collapsed edge's
  /// derivatives) points along `dir`, so a step along it leaves the face at once.
  bool leaves_face = false;
  /// The known point lies on a degenerate edge that is no pole (the derivative across the
  /// edge vanishes, the one along it does not) and the step goes into the face: from_at is
  /// a point across the edge, where the metric is regular.
  bool from_singular_edge = false;
};
UvDirection uv_direction(const DrapeSurface& surface, const SurfaceLocation& at, const Vec3& dir);

}  // namespace plyfit
