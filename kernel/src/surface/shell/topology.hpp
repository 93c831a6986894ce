#pragma once
// Private to the shell (kernel/src/surface/shell/): the per-face topology Shell::create builds
// and the rest of the shell reads, and the constants and helpers its files share.

#include "geometry/numeric.hpp"
#include "geometry/segment_index.hpp"
#include "surface/shell/shell.hpp"

#include <algorithm>

namespace plyfit {

// Per face: every boundary segment (the face's boundary() loops), its shared edge (or
// kFreeEdge), its kind, the sign of its inward side, and a grid over the segments that are
// real boundaries (not collapsed, not seams).
struct Shell::Topology {
  struct Seg {
    Vec2 a, b;
    std::int32_t edge = TrimLoop::kFreeEdge;
    BoundaryLoop::Kind kind = BoundaryLoop::kEdge;
    double inward = 1.0;  // the face lies on the side inward * perp(b - a)
    int loop = 0, index = 0;
  };
  struct FaceTopo {
    std::vector<Seg> segs;
    std::vector<BoundaryLoop> loops;  // the face's own boundary()
    detail::SegmentIndex index;       // over segs (id = position in segs)
    bool shared = false;              // has a shared edge
    // How far (3D) a point may lie off a shared edge and still be on the shell: the sewing
    // gap, and at least the rounding margin contains() grants at the face's domain.
    double near = 0.0;
    bool pole = false;  // has a collapsed edge shared with other faces (see neighbours_)
  };
  std::vector<FaceTopo> faces;
};

namespace detail {

// A point within kGapFactor times the sewing gap (the larger of the shell's tolerance and the
// largest distance measured between the two sides of a shared edge) of a shared edge is on
// the shell: the two faces' boundary polylines approximate the edge independently, and a
// solution can fall in the sliver between them.
inline constexpr double kGapFactor = 2.0;

// Parameter in [0, 1] of the point of segment ab nearest p.
inline double nearest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  return std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), kDivisionFloor), 0.0, 1.0);
}

// Distance from p to segment ab and the parameter of the nearest point.
inline double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double& t) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// The (u, v) step h in the face's parameters that is `length` long in 3D in each direction.
inline Vec2 param_reach(double length, const Vec2& speeds) {
  return Vec2(length / std::max(speeds.x(), kDivisionFloor),
              length / std::max(speeds.y(), kDivisionFloor));
}

}  // namespace detail

}  // namespace plyfit
