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

std::vector<std::pair<double, double>> clip_line(const std::vector<OutlineLoop>& loops, int axis,
                                                 double c) {
  const int other = 1 - axis;
  std::vector<double> xs;
  for (const auto& l : loops) {
    const auto n = l.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = l.points[k];
      const Vec2& b = l.points[(k + 1) % n];
      if ((a[axis] <= c) == (b[axis] <= c)) continue;
      const double t = (c - a[axis]) / (b[axis] - a[axis]);
      xs.push_back(a[other] + t * (b[other] - a[other]));
    }
  }
  std::sort(xs.begin(), xs.end());
  std::vector<std::pair<double, double>> segs;
  for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
    if (xs[k + 1] > xs[k]) segs.emplace_back(xs[k], xs[k + 1]);
  return segs;
}

}  // namespace plyfit::exporters::detail
