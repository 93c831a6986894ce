#include "pattern/boundary_index.hpp"

namespace plyfit::detail {

BoundaryIndex::BoundaryIndex(const DrapeSurface& s, const std::vector<BoundaryLoop>& boundary)
    : faces_(static_cast<std::size_t>(s.face_count())) {
  std::vector<std::vector<SegmentIndex::Seg>> segs(faces_.size());
  for (int l = 0; l < static_cast<int>(boundary.size()); ++l) {
    const auto& L = boundary[static_cast<std::size_t>(l)].points;
    for (int k = 0; k < static_cast<int>(L.size()); ++k) {
      if (boundary[static_cast<std::size_t>(l)].kinds[static_cast<std::size_t>(k)] !=
          BoundaryLoop::kEdge)
        continue;
      const SurfaceLocation& A = L[static_cast<std::size_t>(k)];
      const SurfaceLocation& B = L[(static_cast<std::size_t>(k) + 1) % L.size()];
      if (A.face != B.face) continue;
      const auto& d = s.domain(A);
      const bool cu = s.wrap(A.with_uv(Vec2(d.u1 + 0.5 * d.width_u(), d.v0))).uv.x() <= d.u1;
      const bool cv = s.wrap(A.with_uv(Vec2(d.u0, d.v1 + 0.5 * d.width_v()))).uv.y() <= d.v1;
      auto& F = faces_[static_cast<std::size_t>(A.face)];
      for (int su = cu ? -1 : 0; su <= (cu ? 1 : 0); ++su)
        for (int sv = cv ? -1 : 0; sv <= (cv ? 1 : 0); ++sv) {
          const Vec2 sh(su * d.width_u(), sv * d.width_v());
          segs[static_cast<std::size_t>(A.face)].push_back(
              {A.uv + sh, B.uv + sh, static_cast<int>(F.refs.size())});
          F.refs.push_back({l, k, sh});
        }
    }
  }
  for (std::size_t f = 0; f < faces_.size(); ++f)
    faces_[f].index = SegmentIndex(std::move(segs[f]));
}

}  // namespace plyfit::detail
