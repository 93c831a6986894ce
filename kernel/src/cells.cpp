#include <plyfit/kernel/cells.hpp>

#include <algorithm>
#include <map>

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
    if (p0->pos.x() > lo.x() && p0->pos.x() < hi.x() && p0->pos.y() > lo.y() && p0->pos.y() < hi.y()) {
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
  if (!r.ply) return;
  const Ply& ply = *r.ply;
  // Cells near the path (3 x 3 around each path node) may be crossed by it.
  std::unordered_set<std::uint64_t> near;
  std::vector<std::pair<std::int32_t, std::int32_t>> near_list;
  for (std::uint32_t k : r.base_path) {
    const DrapeNode& p = r.nodes[k];
    const auto i = static_cast<std::int32_t>(std::floor(p.ply.x() / ply.spec().d_weft));
    const auto j = static_cast<std::int32_t>(std::floor(p.ply.y() / ply.spec().d_warp));
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        if (near.insert(NodeId::regular(i + a, j + b).key()).second) near_list.push_back({i + a, j + b});
  }
  auto crossed = [&](std::int32_t i, std::int32_t j) {
    return near.count(NodeId::regular(i, j).key()) && cell_parts(ply, i, j).size() != 1;
  };
  std::uint32_t quad[4];
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    if (!n.mapped() || n.id.is_path_only()) continue;
    const std::int32_t i = n.id.i, j = n.id.j;
    const DrapeNode* x = r.neighbour(n, ThreadDir::kPlusX);
    const DrapeNode* y = r.neighbour(n, ThreadDir::kPlusY);
    const DrapeNode* xy = x ? r.neighbour(*x, ThreadDir::kPlusY) : nullptr;
    if (!x || !y || !xy || !x->mapped() || !y->mapped() || !xy->mapped()) continue;
    if (x->id != NodeId::regular(i + 1, j) || y->id != NodeId::regular(i, j + 1) ||
        xy->id != NodeId::regular(i + 1, j + 1) || crossed(i, j))
      continue;
    quad[0] = k;
    quad[1] = static_cast<std::uint32_t>(x - r.nodes.data());
    quad[2] = static_cast<std::uint32_t>(xy - r.nodes.data());
    quad[3] = static_cast<std::uint32_t>(y - r.nodes.data());
    f(i, j, quad, 4);
  }
  std::vector<std::uint32_t> idx;
  for (const auto& [i, j] : near_list) {
    const auto parts = cell_parts(ply, i, j);
    if (parts.size() == 1) continue;  // a whole cell: visited above
    for (const auto& part : parts) {
      idx.clear();
      for (const NodeId& id : part) {
        const auto k = r.index.find(id);
        if (k < 0 || !r.nodes[static_cast<std::size_t>(k)].mapped()) break;
        idx.push_back(static_cast<std::uint32_t>(k));
      }
      if (idx.size() == part.size()) f(i, j, idx.data(), static_cast<int>(idx.size()));
    }
  }
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

}  // namespace plyfit
