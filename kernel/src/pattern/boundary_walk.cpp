// The walk along the face's free boundary from a part's exit to its entry, and the
// direction of each boundary loop that keeps the surface on its left.

#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// Boundary loops' direction: the kDirectionVotes longest segments of a loop are probed on
// both sides at kDirectionProbe times their (u, v) length.
constexpr int kDirectionVotes = 9;
constexpr double kDirectionProbe = 1e-3;

Vec2 perp(const Vec2& d) {
  return Vec2(-d.y(), d.x());
}

}  // namespace

// From exit item x, walks its boundary loop in the direction that keeps the surface on the
// left (into the part; `turn` -1: on the right, in a folded part) to the first crossing of
// the part's edges, and returns it (its item index, -1 if it is no entry or none is found).
// The loop vertices passed go to `path`, each 3D point once: across a junction of two
// faces, a collapsed edge (a pole) or a seam (the walk goes on from the seam's other side)
// the vertex is not repeated.
int OutlineBuilder::walk(const std::vector<Item>& items, std::size_t x, int turn,
                         std::vector<int>& path) const {
  const Vertex& X = verts_[static_cast<std::size_t>(items[x].v)];
  if (X.bloop < 0) return -1;
  const int dir = turn * dirs_[static_cast<std::size_t>(X.bloop)];
  if (dir == 0) return -1;
  const auto& B = boundary_[static_cast<std::size_t>(X.bloop)];
  const int n = static_cast<int>(B.points.size());
  int seg = X.bseg;
  double s = X.bs;
  for (int guard = 0; guard <= 2 * n; ++guard) {
    int best = -1;
    double bs = 0.0;
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (k == x || items[k].kind == 0) continue;
      const Vertex& V = verts_[static_cast<std::size_t>(items[k].v)];
      if (V.bloop != X.bloop || V.bseg != seg) continue;
      if (dir > 0 ? !(V.bs > s) : !(V.bs < s)) continue;
      if (best < 0 || (dir > 0 ? V.bs < bs : V.bs > bs)) {
        best = static_cast<int>(k);
        bs = V.bs;
      }
    }
    if (best >= 0) return items[static_cast<std::size_t>(best)].kind == 2 ? best : -1;
    // On to the vertex at the segment's end, then past segments that are no boundary: a
    // seam (on from its twin), a junction or a collapsed edge (no 3D length).
    int v = dir > 0 ? (seg + 1) % n : seg;
    path.push_back(v);
    int next = dir > 0 ? v : (v + n - 1) % n;
    for (int hop = 0; hop <= n && B.kinds[static_cast<std::size_t>(next)] != BoundaryLoop::kEdge;
         ++hop) {
      if (B.kinds[static_cast<std::size_t>(next)] == BoundaryLoop::kSeam) {
        v = seam_twin(X.bloop, v, dir);
        if (v < 0) return -1;
      } else {
        v = dir > 0 ? (next + 1) % n : next;
      }
      next = dir > 0 ? v : (v + n - 1) % n;
    }
    seg = next;
    s = dir > 0 ? -1.0 : 2.0;  // any crossing on the new segment is beyond
  }
  return -1;
}

// Loop vertex of loop l at the same point as vertex v across a seam, from which a segment
// other than a seam goes on in direction dir; -1 if none.
int OutlineBuilder::seam_twin(int l, int v, int dir) const {
  const auto& B = boundary_[static_cast<std::size_t>(l)];
  const int n = static_cast<int>(B.points.size());
  const auto& d = s_.domain(B.points[static_cast<std::size_t>(v)]);
  const double same = st_.tol.param_rel * std::max(d.width_u(), d.width_v()) * 16;
  for (int k = 0; k < n; ++k) {
    if (k == v ||
        B.points[static_cast<std::size_t>(k)].face != B.points[static_cast<std::size_t>(v)].face)
      continue;
    const int next = dir > 0 ? k : (k + n - 1) % n;
    if (B.kinds[static_cast<std::size_t>(next)] == BoundaryLoop::kSeam) continue;
    if (s_.delta(B.points[static_cast<std::size_t>(v)], B.points[static_cast<std::size_t>(k)])
            .norm() <= same)
      return k;
  }
  return -1;
}

// Per boundary loop, the direction (+1 forward, -1 backward, 0 unknown) in which it runs
// with the surface on its left seen from the outward normal: the longest segments vote,
// each probing contains() just left and right of its middle.
void OutlineBuilder::loop_directions() {
  for (const auto& b : boundary_) {
    const std::size_t n = b.points.size();
    std::vector<std::pair<double, std::size_t>> segs;
    for (std::size_t k = 0; k < n; ++k) {
      const SurfaceLocation& a = b.points[k];
      const SurfaceLocation& c = b.points[(k + 1) % n];
      if (b.kinds[k] != BoundaryLoop::kEdge || a.face != c.face) continue;
      const Vec2 sp = s_.speeds(a);
      const Vec2 d = s_.delta(a, c);
      segs.push_back({-std::hypot(d.x() * sp.x(), d.y() * sp.y()), k});
    }
    const std::size_t votes = std::min<std::size_t>(kDirectionVotes, segs.size());
    std::partial_sort(segs.begin(), segs.begin() + static_cast<std::ptrdiff_t>(votes), segs.end());
    int vote = 0;
    for (std::size_t q = 0; q < votes; ++q) {
      const std::size_t k = segs[q].second;
      const SurfaceLocation& a = b.points[k];
      const Vec2 d = s_.delta(a, b.points[(k + 1) % n]);
      const Vec2 mid = a.uv + 0.5 * d, off = kDirectionProbe * perp(d);
      const bool left = s_.contains(s_.wrap(a.with_uv(mid + off)));
      const bool right = s_.contains(s_.wrap(a.with_uv(mid - off)));
      if (left != right) vote += (left ? 1 : -1) * (s_.orientation(a) > 0 ? 1 : -1);
    }
    dirs_.push_back(vote > 0 ? 1 : vote < 0 ? -1 : 0);
  }
}

}  // namespace plyfit::detail
