#pragma once
// Private to the solvers: the plane-sphere problem that solvers 1 and 3 solve (and the
// two-sphere solver uses for its guesses), and the trace of a plane's section of the surface.

#include "drape/solvers/solvers.hpp"

#include <Eigen/Core>

#include <optional>

namespace plyfit::solvers {

// The residual of a point on the plane through x0 with unit normal pn and on the sphere of
// radius rad about x0 (both lengths, see solvers.hpp), with its Jacobian.
struct PlaneSphereResidual {
  const Vec3& x0;
  const Vec3& pn;
  const double& rad;
  void operator()(const SurfaceEval1& e, Vec2& f, Eigen::Matrix2d& J) const {
    const Vec3 r = e.p - x0;
    f << pn.dot(r), (r.squaredNorm() - rad * rad) / (2 * rad);
    J << pn.dot(e.du), pn.dot(e.dv), r.dot(e.du) / rad, r.dot(e.dv) / rad;
  }
};

// What a plane-sphere solve does where the direct solve and the march fail: trace the plane's
// section (trace_section; solvers 1 and 3), test whether the section misses the face (which
// tells "outside" from a failure), or nothing (the caller asks only whether the step lands).
enum class Unmarched { kTrace, kMissTest, kNothing };

// Plane through x0 (at at0, where the surface is e0 and its normal n0) with unit normal `pn`,
// sphere of radius `rho` about x0, surface: the solution going forward along the unit tangent
// `t` (which lies in the plane). Solvers 1 and 3 are this problem with different planes.
SolveResult plane_sphere_core(const DrapeSurface& s, const Vec3& x0, const SurfaceLocation& at0,
                              const SurfaceEval1& e0, const Vec3& n0, const Vec3& pn, const Vec3& t,
                              double rho, const SolverSettings& st,
                              Unmarched unmarched = Unmarched::kMissTest);

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
                                         const SurfaceLocation& at0, const Vec3& pn, const Vec3& t,
                                         double rho, const SolverSettings& st);

}  // namespace plyfit::solvers
