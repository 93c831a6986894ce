// The solvers' statuses and reason codes, and the rounding floor of their residuals. The
// solvers: plane_sphere.cpp (1 and 3), two_spheres.cpp (2), on newton.hpp and tangent.hpp.
#include "drape/solvers/solvers.hpp"

namespace plyfit {

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

}  // namespace plyfit
