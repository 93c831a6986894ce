#include "pattern/cells.hpp"

#include "pattern/mapped_cells.hpp"

#include <algorithm>
#include <climits>
#include <map>
#include <unordered_set>

namespace plyfit {

std::vector<std::vector<NodeId>> cell_parts(const Ply& ply, std::int32_t i, std::int32_t j) {
  const NodeId corner[4] = {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                            NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)};
  const ThreadDir edge_dir[4] = {ThreadDir::kPlusX, ThreadDir::kPlusY, ThreadDir::kMinusX,
                                 ThreadDir::kMinusY};
  std::vector<NodeId> ring;
  bool split = false;
  for (int e = 0; e < 4; ++e) {
    ring.push_back(corner[e]);
    const auto nb = ply.neighbour(corner[e].i, corner[e].j, edge_dir[e]);
    if (!nb) return {};
    if (nb->id.is_path_only()) {
      ring.push_back(nb->id);
      split = true;
    }
  }
  int sides = 0;
  for (const NodeId& c : corner) {
    const int s = ply.side(ply.pos(c.i, c.j));
    sides |= (s > 0 ? 1 : 0) | (s < 0 ? 2 : 0);
  }
  // The start, when it lies strictly inside this cell (on no thread).
  std::vector<NodeId> inside;
  if (const PathNode* p0 = ply.path_node_if(0); p0 && p0->id.is_path_only() && !p0->link_from) {
    const Vec2 lo = ply.pos(i, j), hi = ply.pos(i + 1, j + 1);
    if (p0->pos.x() > lo.x() && p0->pos.x() < hi.x() && p0->pos.y() > lo.y() &&
        p0->pos.y() < hi.y()) {
      inside.push_back(p0->id);
      split = true;
    }
  }
  if (!split && sides != 3) return {ring};
  std::vector<std::vector<NodeId>> parts;
  for (int s : {1, -1}) {
    std::vector<NodeId> part;
    for (const NodeId& id : ring) {
      const int sd = id.is_path_only() ? 0 : ply.side(ply.pos(id.i, id.j));
      if (sd == s || sd == 0) part.push_back(id);
    }
    bool has_side = false;
    for (const NodeId& id : part)
      if (!id.is_path_only() && ply.side(ply.pos(id.i, id.j)) == s) has_side = true;
    if (!has_side) continue;
    for (const NodeId& id : inside) part.push_back(id);
    if (part.size() < 3) continue;
    // Counter-clockwise about the centroid (the part is convex).
    Vec2 c = Vec2::Zero();
    for (const NodeId& id : part) c += ply.pos(id);
    c /= static_cast<double>(part.size());
    std::sort(part.begin(), part.end(), [&](const NodeId& a, const NodeId& b) {
      const Vec2 pa = ply.pos(a) - c, pb = ply.pos(b) - c;
      return std::atan2(pa.y(), pa.x()) < std::atan2(pb.y(), pb.x());
    });
    parts.push_back(std::move(part));
  }
  return parts;
}

void for_each_mapped_cell(
    const DrapeResult& r,
    const std::function<void(std::int32_t, std::int32_t, const std::uint32_t*, int)>& f) {
  detail::visit_mapped_cells(r, f);
}

std::vector<MappedCell> mapped_cells(const DrapeResult& r) {
  std::vector<MappedCell> out;
  for_each_mapped_cell(r, [&](std::int32_t i, std::int32_t j, const std::uint32_t* nodes, int n) {
    out.push_back({i, j, std::vector<std::uint32_t>(nodes, nodes + n)});
  });
  std::stable_sort(out.begin(), out.end(), [](const MappedCell& a, const MappedCell& b) {
    if (a.j != b.j) return a.j < b.j;
    return a.i < b.i;
  });
  return out;
}

namespace {

// The cell a mapped node marks: its own (i, j), or for a path-only node the cell it lies on.
CellIndex cell_of(const DrapeNode& n, double dx, double dy) {
  if (!n.id.is_path_only()) return {n.id.i, n.id.j};
  return {static_cast<std::int32_t>(std::floor(n.ply.x() / dx)),
          static_cast<std::int32_t>(std::floor(n.ply.y() / dy))};
}

// Cells seen are marked in a byte map over the box of the touched cells when that box holds
// at most this many cells per mapped node (a byte each: the map is freed on return), else in
// a hash set (a thin ply along a diagonal).
constexpr std::int64_t kByteMapCellsPerNode = 16;

}  // namespace

std::vector<CellIndex> touched_cells(const DrapeResult& res, int ring) {
  std::vector<CellIndex> out;
  const double dx = res.ply->spec().d_weft, dy = res.ply->spec().d_warp;
  std::int64_t i0 = INT64_MAX, j0 = INT64_MAX, i1 = INT64_MIN, j1 = INT64_MIN, count = 0;
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const CellIndex c = cell_of(n, dx, dy);
    i0 = std::min<std::int64_t>(i0, c.i - 1 - ring);
    i1 = std::max<std::int64_t>(i1, c.i + ring);
    j0 = std::min<std::int64_t>(j0, c.j - 1 - ring);
    j1 = std::max<std::int64_t>(j1, c.j + ring);
    ++count;
  }
  if (count == 0) return out;
  const std::int64_t w = i1 - i0 + 1, h = j1 - j0 + 1;
  const bool bytes = w * h <= kByteMapCellsPerNode * (count + 16);
  std::vector<std::uint8_t> seen_map(bytes ? static_cast<std::size_t>(w * h) : 0);
  std::unordered_set<std::uint64_t> seen_set;
  out.reserve(static_cast<std::size_t>(count) + static_cast<std::size_t>(2 * (w + h)));
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const CellIndex c = cell_of(n, dx, dy);
    for (std::int32_t a = -1 - ring; a <= ring; ++a)
      for (std::int32_t b = -1 - ring; b <= ring; ++b) {
        const std::int32_t i = c.i + a, j = c.j + b;
        if (bytes) {
          std::uint8_t& m = seen_map[static_cast<std::size_t>((j - j0) * w + (i - i0))];
          if (m) continue;
          m = 1;
        } else if (!seen_set.insert(NodeId::regular(i, j).key()).second) {
          continue;
        }
        out.push_back({i, j});
      }
  }
  return out;
}

}  // namespace plyfit
