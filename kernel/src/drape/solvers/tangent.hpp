#pragma once
// Private to the solvers: the surface near a known point as the solvers use it (its normal,
// the (u, v) direction of a 3D tangent direction, the nearest point to a 3D point).

#include "drape/solvers/solvers.hpp"

namespace plyfit::solvers {

// The face normal at a location: the limit normal at poles, else the normalised cross product
// with the face orientation.
Vec3 face_normal(const DrapeSurface& s, const SurfaceLocation& at, const SurfaceEval1& e);

// Least-squares (u, v) direction a with J a = dir_t, scaled to |J a| = 1.
bool metric_direction(const SurfaceEval1& e, const Vec3& dir, Vec2& a);

// uv_direction with the evaluation e and the face normal n at `at` already known; `reach` is
// the length of the step to be taken (a step from a degenerate edge that is no pole looks
// that far across it), 0 if unknown.
UvDirection uv_direction_at(const DrapeSurface& surface, const SurfaceLocation& at,
                            const SurfaceEval1& e, const Vec3& n, const Vec3& dir,
                            double reach = 0.0);

// The point of the surface nearest q, by Gauss-Newton on |S(u, v) - q|^2 from `at` through
// DrapeSurface::locate (so across a shell's shared edges), staying on the surface (contains):
// at a crease or a free edge it stops on the edge, which is then the nearest point.
struct Foot {
  SurfaceLocation at;
  Vec3 p = Vec3::Zero();
  Vec3 n = Vec3::UnitZ();
  bool ok = false;
};
Foot foot_near(const DrapeSurface& s, const SolverSettings& st, const Vec3& q, SurfaceLocation at,
               int& evaluations);

// The point beyond `b` continuing the parameter step a -> b, in b's chart.
SurfaceLocation continue_step(const DrapeSurface& s, const SurfaceLocation& a,
                              const SurfaceLocation& b);

}  // namespace plyfit::solvers
