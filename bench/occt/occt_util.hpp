#pragma once
// What the benchmarks outside bench/occt/ ask of OpenCASCADE, without its headers: an
// independent point-to-surface distance (OpenCASCADE's evaluator on the same NURBS, converted
// by occt/src/nurbs_conversion) and the version of the OpenCASCADE linked.

#include <plyfit/kernel/nurbs.hpp>

#include <memory>
#include <string>

namespace plyfit::bench {

/// Distance from points to a surface, measured with OpenCASCADE's evaluator rather than
/// plyfit's: Gauss-Newton on |S(u, v) - p|^2 with Geom_BSplineSurface::D1 from a seed (u, v),
/// keeping the smallest distance met (an upper bound of the true distance that is exact to
/// second order in the foot point's error).
class OcctDistance {
 public:
  explicit OcctDistance(const NurbsSurfaceData& d);
  ~OcctDistance();
  /// Distance from p to the surface near `seed` (u, v).
  double operator()(const Vec3& p, const Vec2& seed) const;

 private:
  struct Surface;  // the OpenCASCADE surface and its parameter bounds
  std::unique_ptr<const Surface> s_;
};

/// OpenCASCADE's version as its headers state it (OCC_VERSION_COMPLETE), e.g. "7.6.3".
std::string occt_version();

}  // namespace plyfit::bench
