#pragma once
// OpenCASCADE counterparts of kernel surfaces for plyfit-bench: the same NURBS as a
// Geom_BSplineSurface, and an independent point-to-surface distance computed with it.

#include <plyfit/kernel/nurbs_surface.hpp>

#include <Geom_BSplineSurface.hxx>

namespace plyfit::bench {

/// The surface as an OpenCASCADE B-spline (flat knot vector compressed to knots and
/// multiplicities; weights if rational).
Handle(Geom_BSplineSurface) to_occt(const NurbsSurfaceData& d);

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
