#pragma once
/// \file Cells of the ply and their parts: the base path splits the cells it crosses into two
/// convex parts. One enumeration serves the drape's areas, the flat pattern and the writers.

#include <plyfit/kernel/ply.hpp>
#include "drape/drape.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_set>
#include <vector>

namespace plyfit {

/// The parts of cell (i, j) (lower-left corner (i, j)): convex polygons of node ids,
/// counter-clockwise in ply coordinates; one part for a cell the path does not cross, two
/// for one it crosses. Empty if a path node splitting an edge was never generated.
std::vector<std::vector<NodeId>> cell_parts(const Ply& ply, std::int32_t i, std::int32_t j);

/// Calls f(i, j, nodes, n) for every mapped cell part (all its nodes mapped): the quadrangles
/// of four mapped regular nodes (nodes counter-clockwise from (i, j)) and the mapped parts of
/// the cells the path crosses. No allocation per cell.
void for_each_mapped_cell(const DrapeResult& r,
                          const std::function<void(std::int32_t i, std::int32_t j,
                                                   const std::uint32_t* nodes, int n)>& f);

/// Calls f(i, j) once for every cell within `ring` cells of a mapped node: ring 0 gives the
/// cells having a mapped regular node as a corner (and those a mapped path-only node lies
/// on), ring 1 one more layer around them. Cells are visited in the order of the nodes.
template <class F>
void for_each_touched_cell(const DrapeResult& res, F&& f, int ring = 0) {
  const double dx = res.ply->spec().d_weft, dy = res.ply->spec().d_warp;
  auto cell_of = [&](const DrapeNode& n) {
    if (!n.id.is_path_only()) return std::pair<std::int64_t, std::int64_t>(n.id.i, n.id.j);
    return std::pair<std::int64_t, std::int64_t>(
        static_cast<std::int64_t>(std::floor(n.ply.x() / dx)),
        static_cast<std::int64_t>(std::floor(n.ply.y() / dy)));
  };
  // Cells seen: a bitmap over the box of the touched cells, or a hash set where that box
  // is much larger than the node count (a thin ply along a diagonal).
  std::int64_t i0 = INT64_MAX, j0 = INT64_MAX, i1 = INT64_MIN, j1 = INT64_MIN, count = 0;
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const auto [i, j] = cell_of(n);
    i0 = std::min(i0, i - 1 - ring);
    i1 = std::max(i1, i + ring);
    j0 = std::min(j0, j - 1 - ring);
    j1 = std::max(j1, j + ring);
    ++count;
  }
  if (count == 0) return;
  const std::int64_t w = i1 - i0 + 1, h = j1 - j0 + 1;
  constexpr std::int64_t kBitmapCellsPerNode = 64;
  const bool bitmap = w * h <= kBitmapCellsPerNode * (count + 16);
  std::vector<bool> seen_bits(bitmap ? static_cast<std::size_t>(w * h) : 0);
  std::unordered_set<std::uint64_t> seen_set;
  auto visit = [&](std::int64_t i, std::int64_t j) {
    if (bitmap) {
      const auto k = static_cast<std::size_t>((j - j0) * w + (i - i0));
      if (seen_bits[k]) return;
      seen_bits[k] = true;
    } else if (!seen_set
                    .insert(
                        NodeId::regular(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j))
                            .key())
                    .second) {
      return;
    }
    f(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
  };
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const auto [i, j] = cell_of(n);
    for (int a = -1 - ring; a <= ring; ++a)
      for (int b = -1 - ring; b <= ring; ++b) visit(i + a, j + b);
  }
}

}  // namespace plyfit
