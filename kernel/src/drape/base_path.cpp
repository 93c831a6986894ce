// §5.1: the base path, mapped both ways from the start by intersecting the base plane, a
// sphere of the link length about the last point, and the surface.
#include "drape/scan/scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plyfit::detail {

// The base path both ways from the start.
void Scanner::map_path(const Vec3& t3) {
  const PathNode* p0 = ply_.path_node(0);
  const std::uint32_t i0 = node_for(p0->id, p0->pos);
  DrapeNode& n0 = node(i0);
  n0.status = NodeStatus::kMapped;
  n0.point = res_.start_point;
  n0.set_at(res_.start_at);
  n0.flags |= DrapeNode::kOnPath | DrapeNode::kStart;
  n0.order = order_++;
  overlaps(i0);  // records the start
  std::vector<std::uint32_t> ahead{i0}, behind;
  if (seed_curve_) curve_along_ = seed_curve_->tangent(seed_curve_->start_place()).dot(t3) >= 0.0;
  for (int dirn = 0; dirn < 2; ++dirn) {
    const bool fwd = dirn == 0;
    auto& chain = fwd ? ahead : behind;
    std::uint32_t prev = i0;
    Vec3 travel = fwd ? t3 : Vec3(-t3);
    CurvePlace place = seed_curve_ ? seed_curve_->start_place() : CurvePlace{};
    for (std::int32_t k = fwd ? 1 : -1;; k += fwd ? 1 : -1) {
      const PathNode* pk = ply_.path_node(k);
      if (!pk) {
        if (ply_.spec().rect) ++path_off_ply_;  // the cloth ends here
        break;
      }
      const double rest = std::abs(pk->tau - ply_.path_node_if(fwd ? k - 1 : k + 1)->tau);
      const PathNode pcopy = *pk;  // path_node() may reallocate; keep a copy
      if (res_.nodes.size() >= opt_.max_nodes) {
        truncated_ = true;
        break;
      }
      const auto aim = path_aim(node(prev), travel, rest, fwd, place);
      if (!aim) {  // the seed curve ends
        path_stop_[dirn] = pcopy.pos;
        break;
      }
      const std::uint32_t idx = node_for(pcopy.id, pcopy.pos);
      node(idx).flags |= DrapeNode::kOnPath;
      const DrapeNode& from = node(prev);
      const SolveResult r =
          solve_base_path(s_, {from.point, from.at(), aim->plane_normal, aim->travel, rest}, st_);
      resolve(idx, r);
      // Across a hole of the face the path goes on, on the face's surface under the hole
      // (kInHole: outside, extended), and comes back onto the face beyond it: the seed curve
      // is not cut by a cutout. Past the outer boundary it stops.
      if (!node(idx).carries()) {
        path_stop_[dirn] = pcopy.pos;
        break;
      }
      if (overlaps(idx)) {  // a closed plane section: the path came round
        stop_overlap(idx, kOnLaidCloth);
        break;
      }
      chain.push_back(idx);
      travel = node(idx).point - node(prev).point;
      prev = idx;
      if (cancelled_now()) break;
    }
  }
  std::reverse(behind.begin(), behind.end());
  res_.base_path = behind;
  res_.base_path.insert(res_.base_path.end(), ahead.begin(), ahead.end());
  for (std::uint32_t k = 0; k < res_.base_path.size(); ++k) path_pos_[res_.base_path[k]] = k;
  // The line's nodes the path reached, its stops included (they exist: never pushed again).
  for (const DrapeNode& n : res_.nodes) {
    if (!n.has(DrapeNode::kOnPath)) continue;
    const double t = (n.ply - ply_.spec().start).dot(ply_.base_dir());
    path_t_[0] = std::min(path_t_[0], t);
    path_t_[1] = std::max(path_t_[1], t);
  }
  for (std::uint32_t k : res_.base_path) push_neighbours(k);
}

// The plane the next path point lies in, through `from`: the base plane, or for a geodesic
// the plane holding the normal at `from` and the chord that arrived there (`travel`), so
// that the path turns neither left nor right on the surface. From the start the chord is the
// start's tangent, which the base plane holds.
Vec3 Scanner::path_plane(const DrapeNode& from, const Vec3& travel) const {
  if (res_.seed_curve != SeedCurve::kGeodesic || from.has(DrapeNode::kStart))
    return res_.base_normal;
  const SurfaceNormal sn = s_.normal(from.at());
  const Vec3 m = sn.n.cross(travel);
  return sn.ok && m.norm() > 0.0 ? m : res_.base_normal;
}

// The plane the next path point lies in and the direction it lies in. For a seed curve: the
// point of the curve at `rest` from `from` (`place` moves on to it), the plane through `from`
// holding the normal there and the chord to that point; none when the curve ends first.
std::optional<Scanner::PathAim> Scanner::path_aim(const DrapeNode& from, const Vec3& travel,
                                                  double rest, bool fwd, CurvePlace& place) const {
  if (!seed_curve_) return PathAim{path_plane(from, travel), travel};
  const auto next = seed_curve_->at_distance(place, from.point, rest, fwd == curve_along_);
  if (!next) return std::nullopt;
  place = next->second;
  const Vec3 chord = next->first - from.point;
  const SurfaceNormal sn = s_.normal(from.at());
  const Vec3 m = sn.n.cross(chord);
  return PathAim{sn.ok && m.norm() > 0.0 ? m : res_.base_normal, chord};
}

// Direction of the base path at path node a, along +tau (a chord to a path neighbour).
Vec3 Scanner::path_chord(const DrapeNode& a) const {
  const auto it = path_pos_.find(static_cast<std::uint32_t>(&a - res_.nodes.data()));
  if (it == path_pos_.end()) return res_.base_tangent;
  const auto& bp = res_.base_path;
  const std::uint32_t k = it->second;
  if (k + 1 < bp.size()) return res_.nodes[bp[k + 1]].point - a.point;
  if (k > 0) return a.point - res_.nodes[bp[k - 1]].point;
  return res_.base_tangent;
}

// The slit a path stopped at a gap leaves (see PathSlit): the lattice links around the
// path's line, beyond both its ends, whose two ends lie on the two sides and are mapped.
Scanner::PathSlit Scanner::path_slits() const {
  PathSlit out;
  if (res_.base_path.empty() || ply_.sweep_for_side(1) < 0 || ply_.sweep_for_side(-1) < 0)
    return out;
  const Vec2 o = ply_.spec().start, dir = ply_.base_dir();
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  for (const std::uint32_t k : res_.base_path) {
    const double t = (res_.nodes[k].ply - o).dot(dir);
    t0 = std::min(t0, t);
    t1 = std::max(t1, t);
  }
  const double merge = opt_.tol.ply_merge_rel * ply_.d();
  auto mapped_at = [&](std::int32_t i, std::int32_t j) {
    const DrapeNode* n = res_.find(NodeId::regular(i, j));
    return n && n->mapped();
  };
  constexpr std::int32_t kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const DrapeNode& a : res_.nodes) {
    if (!a.mapped() || a.id.is_path_only() || far_from_path(a.ply) || ply_.side(a.ply) <= 0)
      continue;
    for (const auto& st : kSteps) {
      // The node across the line: one link on, or two where the one between lies on it.
      std::int32_t i = a.id.i + st[0], j = a.id.j + st[1];
      int sb = ply_.side(ply_.pos(i, j));
      if (sb > 0) continue;
      if (sb == 0) {
        if (mapped_at(i, j)) continue;
        i += st[0];
        j += st[1];
        sb = ply_.side(ply_.pos(i, j));
      }
      if (sb >= 0 || !mapped_at(i, j)) continue;
      // Where the segment crosses the line, along the path.
      const Vec2 pb = ply_.pos(i, j);
      const double ca = cross2(dir, a.ply - o), cb = cross2(dir, pb - o);
      const double t = (a.ply + ca / (ca - cb) * (pb - a.ply) - o).dot(dir);
      if (t >= t0 - merge && t <= t1 + merge) continue;
      if (out.links++ == 0) out.stop = path_stop_[t > t1 ? 0 : 1];
    }
  }
  return out;
}

}  // namespace plyfit::detail
