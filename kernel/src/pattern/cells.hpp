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

/// Cell (i, j) of the ply, by its lower-left corner.
struct CellIndex {
  std::int32_t i, j;
};

/// Every cell within `ring` cells of a mapped node, once each: ring 0 gives the cells having a
/// mapped regular node as a corner (and those a mapped path-only node lies on), ring 1 one
/// more layer around them. In the order of the nodes.
std::vector<CellIndex> touched_cells(const DrapeResult& res, int ring = 0);

}  // namespace plyfit
