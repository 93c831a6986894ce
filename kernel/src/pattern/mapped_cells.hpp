#pragma once
// The enumeration of mapped cell parts behind for_each_mapped_cell (cells.hpp), as a template
// so that the drape's own metrics call their functor directly (no std::function per cell).

#include "pattern/cells.hpp"

#include <cmath>
#include <unordered_set>
#include <vector>

namespace plyfit::detail {

/// Calls f(i, j, nodes, n) for every mapped cell part, in the order documented for
/// for_each_mapped_cell.
template <class F>
void visit_mapped_cells(const DrapeResult& r, F&& f) {
  if (!r.ply) return;
  const Ply& ply = *r.ply;
  const double dx = ply.spec().d_weft, dy = ply.spec().d_warp;
  // Cells near the path (3 x 3 around each path node) may be crossed by it.
  std::unordered_set<std::uint64_t> near;
  std::vector<std::pair<std::int32_t, std::int32_t>> near_list;
  for (std::uint32_t k : r.base_path) {
    const DrapeNode& p = r.nodes[k];
    const auto i = static_cast<std::int32_t>(std::floor(p.ply.x() / dx));
    const auto j = static_cast<std::int32_t>(std::floor(p.ply.y() / dy));
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        if (near.insert(NodeId::regular(i + a, j + b).key()).second)
          near_list.push_back({i + a, j + b});
  }
  // Every near cell lies within two cell diagonals of the path line (its path node is in a
  // neighbouring cell, on the line): cells farther away skip the hash lookup.
  const Vec2 o = ply.spec().start, dir = ply.base_dir();
  const double strip = 2.5 * std::hypot(dx, dy);
  auto crossed = [&](std::int32_t i, std::int32_t j) {
    const Vec2 c((i + 0.5) * dx, (j + 0.5) * dy);
    if (std::abs(cross2(dir, c - o)) > strip) return false;
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
    f(i, j, static_cast<const std::uint32_t*>(quad), 4);
  }
  std::vector<std::uint32_t> idx;
  for (const auto& [i, j] : near_list) {
    const auto parts = cell_parts(ply, i, j);
    if (parts.size() == 1) continue;  // a whole cell: visited above
    for (const auto& part : parts) {
      idx.clear();
      for (const NodeId& id : part) {
        const auto k = r.index->find(id);
        if (k < 0 || !r.nodes[static_cast<std::size_t>(k)].mapped()) break;
        idx.push_back(static_cast<std::uint32_t>(k));
      }
      if (idx.size() == part.size())
        f(i, j, static_cast<const std::uint32_t*>(idx.data()), static_cast<int>(idx.size()));
    }
  }
}

}  // namespace plyfit::detail
