#pragma once
// An independent point-to-surface distance for plyfit-bench, computed with OpenCASCADE's
// evaluator on the same NURBS (converted by exporters/src/occt_geometry).

#include <plyfit/kernel/nurbs.hpp>

#include <Geom_BSplineSurface.hxx>

namespace plyfit::bench {

/// Distance from points to a surface, measured with OpenCASCADE's evaluator rather than
/// plyfit's: Gauss-Newton on |S(u, v) - p|^2 with Geom_BSplineSurface::D1 from a seed (u, v),
/// keeping the smallest distance met (an upper bound of the true distance that is exact to
/// second order in the foot point's error).
class OcctDistance {
 public:
  explicit OcctDistance(const NurbsSurfaceData& d);
  /// Distance from p to the surface near `seed` (u, v).
  double operator()(const Vec3& p, const Vec2& seed) const;

 private:
  Handle(Geom_BSplineSurface) s_;
  double u0_, u1_, v0_, v1_;
};

}  // namespace plyfit::bench
