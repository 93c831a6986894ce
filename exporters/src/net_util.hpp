#pragma once
// What the writers draw of a drape: the mapped cells of the net with their shear, node shear,
// and the box of what a picture shows.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

namespace plyfit::exporters::detail {

using plyfit::kPi;
using plyfit::kRadToDeg;

/// A 2D box grown point by point (empty until the first point).
struct Box2 {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  /// Every point of the loops.
  void add(const std::vector<OutlineLoop>& loops) {
    for (const auto& l : loops)
      for (const Vec2& p : l.points) add(p);
  }
  /// The ply position of every mapped node.
  void add_mapped(const DrapeResult& r) {
    for (const DrapeNode& n : r.nodes)
      if (n.mapped()) add(n.ply);
  }
  bool empty() const { return !(lo.x() <= hi.x() && lo.y() <= hi.y()); }
  Vec2 size() const { return hi - lo; }
};

/// Shear of a node: |pi/2 - thread_angle| (radians), or a negative value if the node has no
/// thread angle.
double node_shear(const DrapeNode& n);

/// A mapped cell (or the mapped part of a cell the base path splits): a convex polygon of
/// node indices, counter-clockwise in ply coordinates, every node mapped.
struct NetCell {
  std::int32_t i = 0, j = 0;         ///< the cell: lower-left regular node (i, j)
  std::vector<std::uint32_t> nodes;  ///< indices into DrapeResult::nodes
  /// The cell's shear: the largest |pi/2 - gamma| over its corners that have a thread angle
  /// (radians); negative when none has one.
  double shear = -1.0;
};

/// Every mapped cell part (plyfit::mapped_cells: the parts the kernel counts in
/// DrapeMetrics::flat_area), with its shear. Sorted by (j, i): deterministic.
std::vector<NetCell> mapped_cells(const DrapeResult& r);

/// The ply positions of a cell's corners, in order.
std::vector<Vec2> cell_ply_points(const DrapeResult& r, const NetCell& c);

/// Segments (from, to along the other axis) of the line {p : p[axis] = c} inside the loops
/// (even-odd over all loops, each edge half-open so that a vertex on the line counts once).
std::vector<std::pair<double, double>> clip_line(const std::vector<OutlineLoop>& loops, int axis,
                                                 double c);

}  // namespace plyfit::exporters::detail
