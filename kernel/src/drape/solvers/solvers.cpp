// The solvers' statuses and reason codes, and the rounding floor of their residuals. The
// solvers: plane_sphere.cpp (1 and 3), two_spheres.cpp (2), on newton.hpp and tangent.hpp.
#include "drape/solvers/solvers.hpp"

#include "named_values.hpp"

namespace plyfit {

namespace {

constexpr detail::Named<SolveStatus> kSolveStatuses[] = {{SolveStatus::kConverged, "converged"},
                                                         {SolveStatus::kLeftFace, "left_face"},
                                                         {SolveStatus::kShearLimit, "shear_limit"},
                                                         {SolveStatus::kFailed, "failed"}};
static_assert(detail::lists_enum(kSolveStatuses, SolveStatus::kFailed));

constexpr detail::Named<ShearStop> kShearStops[] = {{ShearStop::kNone, "none"},
                                                    {ShearStop::kLock, "lock"},
                                                    {ShearStop::kFoldAngle, "fold_angle"},
                                                    {ShearStop::kFlatCell, "flat_cell"},
                                                    {ShearStop::kCellFolds, "cell_folds"},
                                                    {ShearStop::kBehindStop, "behind_stop"}};
static_assert(detail::lists_enum(kShearStops, ShearStop::kBehindStop));

}  // namespace

const char* to_string(SolveStatus s) {
  return detail::name_in(kSolveStatuses, s, "failed");
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
  return detail::name_in(kShearStops, s, "none");
}

}  // namespace plyfit
