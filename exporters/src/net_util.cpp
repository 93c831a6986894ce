#include "net_util.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::detail {

double node_shear(const DrapeNode& n) {
  if (!n.mapped() || !n.has(DrapeNode::kHasAngle)) return -1.0;
  return std::abs(kPi / 2 - n.thread_angle);
}

std::vector<NetCell> mapped_cells(const DrapeResult& r) {
  std::vector<NetCell> out;
  for (const MappedCell& m : plyfit::mapped_cells(r)) {
    NetCell c;
    c.i = m.i;
    c.j = m.j;
    c.nodes = m.nodes;
    for (std::uint32_t k : c.nodes) c.shear = std::max(c.shear, node_shear(r.nodes[k]));
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<Vec2> cell_ply_points(const DrapeResult& r, const NetCell& c) {
  std::vector<Vec2> pts;
  for (const std::uint32_t k : c.nodes) pts.push_back(r.nodes[k].ply);
  return pts;
}

}  // namespace plyfit::exporters::detail
