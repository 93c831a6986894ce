#pragma once
/// \file The free boundary of a drape surface indexed per face, for the flat pattern's
/// crossing queries (internal to pattern/).

#include "geometry/segment_index.hpp"
#include "surface/drape_surface.hpp"

#include <vector>

namespace plyfit::detail {

/// The free boundary's segments (kind kEdge, both ends on one face) indexed per face in that
/// face's (u, v), with copies shifted by a period across closed seams.
class BoundaryIndex {
 public:
  struct Ref {
    int loop, index;  ///< segment `index` of boundary loop `loop`
    Vec2 shift;       ///< the period the copy is shifted by
  };

  BoundaryIndex(const DrapeSurface& s, const std::vector<BoundaryLoop>& boundary);

  /// Calls f(a, b, ref) for the free-boundary segments of `face` whose boxes meet [lo, hi]
  /// (the face's (u, v)), a and b in that face's parameters.
  template <class F>
  void near(std::int32_t face, const Vec2& lo, const Vec2& hi, F&& f) const {
    const auto& Fi = faces_[static_cast<std::size_t>(face)];
    Fi.index.for_candidates(lo, hi, [&](int k) {
      const auto& g = Fi.index.seg(k);
      f(g.a, g.b, Fi.refs[static_cast<std::size_t>(g.id)]);
    });
  }

 private:
  struct FaceIndex {
    SegmentIndex index;
    std::vector<Ref> refs;
  };
  std::vector<FaceIndex> faces_;
};

}  // namespace plyfit::detail
