#include "render/label_placement.hpp"

#include "net_util.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plyfit::exporters::render {

bool inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  bool in = false;  // even-odd over all loops
  for (const auto& l : loops) in = in != inside_polygon(l.points, p);
  return in;
}

namespace {

// Signed distance: positive inside the outline and clear of the obstacles.
double signed_distance(const std::vector<OutlineLoop>& loops, const Obstacles& obstacles,
                       const Vec2& p) {
  const double d = outline_distance(loops, p);
  return std::min(inside_outline(loops, p) ? d : -d, obstacles.distance(p));
}

// Distance from p to the box [lo, hi]: negative inside (minus the distance to its sides).
double box_distance(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  const Vec2 out = (lo - p).cwiseMax(p - hi);
  if (out.maxCoeff() <= 0.0) return out.maxCoeff();
  return out.cwiseMax(0.0).norm();
}

// Does segment ab meet the box [lo, hi]? (Liang-Barsky clipping.)
bool segment_meets_box(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      // side -1: a + t d >= lo; side +1: a + t d <= hi.
      const double q = side < 0 ? a[axis] - lo[axis] : hi[axis] - a[axis];
      const double pp = side < 0 ? -d[axis] : d[axis];
      if (pp == 0.0) {
        if (q < 0) return false;
      } else {
        const double t = q / pp;
        if (pp < 0)
          t0 = std::max(t0, t);
        else
          t1 = std::min(t1, t);
        if (t0 > t1) return false;
      }
    }
  }
  return true;
}

// A point and its signed distance to the outline.
struct Probe {
  Vec2 p;
  double d;
};

// The centres of square cells of side `cell` over `box` (row by row, at most
// kMaxInteriorProbes), best (farthest inside) first.
std::vector<Probe> grid_probes(const std::vector<OutlineLoop>& loops, const Obstacles& obstacles,
                               const detail::Box2& box, double cell) {
  const Vec2 size = box.size();
  std::vector<Probe> grid;
  const auto nx = static_cast<int>(std::ceil(size.x() / cell)),
             ny = static_cast<int>(std::ceil(size.y() / cell));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx && static_cast<int>(grid.size()) < kMaxInteriorProbes; ++i) {
      const Vec2 c = box.lo + cell * Vec2(i + 0.5, j + 0.5);
      grid.push_back({c, signed_distance(loops, obstacles, c)});
    }
  std::stable_sort(grid.begin(), grid.end(),
                   [](const Probe& a, const Probe& b) { return a.d > b.d; });
  return grid;
}

// Climbs from `at` uphill on the distance (pattern search: the best of eight neighbours at the
// current step, else half the step) to a local maximum, until the step is below precision / 4.
Probe climb(const std::vector<OutlineLoop>& loops, const Obstacles& obstacles, Probe at,
            double step, double precision) {
  for (int it = 0; it < kMaxClimbSteps && step > 0.25 * precision; ++it) {
    Probe next = at;
    for (int m = 0; m < 8; ++m) {
      const double a = m * detail::kPi / 4;
      const Vec2 q = at.p + step * Vec2(std::cos(a), std::sin(a));
      const double dq = signed_distance(loops, obstacles, q);
      if (dq > next.d) next = {q, dq};
    }
    if (next.d > at.d)
      at = next;
    else
      step *= 0.5;
  }
  return at;
}

}  // namespace

double Obstacles::distance(const Vec2& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : segments) best = std::min(best, segment_distance(p, a, b));
  for (const auto& [c, r] : discs) best = std::min(best, (p - c).norm() - r);
  for (const auto& [lo, hi] : boxes) best = std::min(best, box_distance(p, lo, hi));
  return best;
}

bool Obstacles::meet(const Vec2& lo, const Vec2& hi) const {
  for (const auto& [a, b] : segments)
    if (segment_meets_box(a, b, lo, hi)) return true;
  for (const auto& [c, r] : discs)
    if (box_distance(c, lo, hi) <= r) return true;
  for (const auto& [blo, bhi] : boxes)
    if (blo.x() <= hi.x() && lo.x() <= bhi.x() && blo.y() <= hi.y() && lo.y() <= bhi.y())
      return true;
  return false;
}

double outline_distance(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& l : loops) {
    const std::size_t n = l.points.size();
    for (std::size_t k = 0, m = n - 1; k < n; m = k++)
      best = std::min(best, segment_distance(p, l.points[m], l.points[k]));
  }
  return best;
}

namespace {

// The grid of interior_point() over the outline's box: its cell and its probes, best first
// (none without loops of positive area).
struct InteriorGrid {
  double cell = 0.0;
  std::vector<Probe> probes;
};
InteriorGrid interior_grid(const std::vector<OutlineLoop>& loops, const Obstacles& obstacles) {
  InteriorGrid g;
  detail::Box2 box;
  for (const auto& l : loops)
    if (l.points.size() >= 3)
      for (const Vec2& p : l.points) box.add(p);
  if (box.empty()) return g;
  const Vec2 size = box.size();
  const double lo_side = std::min(size.x(), size.y()), hi_side = std::max(size.x(), size.y());
  // Square cells: kGridCells along the long side, no wider than the short side (a thin
  // outline gets cells across it), and never more than kMaxInteriorProbes of them.
  g.cell = std::max(std::min(hi_side / kGridCells, lo_side),
                    hi_side / static_cast<double>(kMaxInteriorProbes));
  if (g.cell > 0) g.probes = grid_probes(loops, obstacles, box, g.cell);
  return g;
}

// The pole climbed from the grid's best probes.
InteriorPoint climb_to_pole(const std::vector<OutlineLoop>& loops, const Obstacles& obstacles,
                            const InteriorGrid& grid, double precision) {
  InteriorPoint out;
  Probe best{Vec2::Zero(), -std::numeric_limits<double>::infinity()};
  const std::size_t seeds = std::min<std::size_t>(grid.probes.size(), kClimbSeeds);
  for (std::size_t k = 0; k < seeds; ++k) {
    if (!(grid.probes[k].d > 0)) break;
    const Probe at = climb(loops, obstacles, grid.probes[k], 0.5 * grid.cell, precision);
    if (at.d > best.d) best = at;
  }
  if (!(best.d > 0)) return out;
  out.point = best.p;
  out.radius = best.d;
  out.found = true;
  return out;
}

}  // namespace

InteriorPoint interior_point(const std::vector<OutlineLoop>& loops, double precision,
                             const Obstacles& obstacles) {
  if (!(precision > 0)) return {};
  return climb_to_pole(loops, obstacles, interior_grid(loops, obstacles), precision);
}

bool box_inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& lo, const Vec2& hi) {
  if (!inside_outline(loops, 0.5 * (lo + hi))) return false;
  for (const auto& l : loops) {
    const std::size_t n = l.points.size();
    for (std::size_t k = 0, m = n - 1; k < n; m = k++)
      if (segment_meets_box(l.points[m], l.points[k], lo, hi)) return false;
  }
  return true;
}

BlockPlace place_block(const std::vector<OutlineLoop>& loops, const BlockShape& shape,
                       double extent, double max_h, const Vec2& fallback,
                       const Obstacles& obstacles) {
  const InteriorGrid grid = interior_grid(loops, obstacles);
  const InteriorPoint pole = climb_to_pole(loops, obstacles, grid, kPolePrecisionRel * extent);
  BlockPlace out;
  out.h = max_h;
  if (!pole.found) {
    out.top_left = fallback - Vec2(0.0, 2.0 * max_h);
    return out;
  }
  auto corner = [&](const Vec2& centre, double h) -> Vec2 {
    return centre + 0.5 * Vec2(-shape.width_at(h), shape.height_at(h));
  };
  auto fits = [&](const Vec2& centre, double h) {
    const Vec2 tl = corner(centre, h);
    const Vec2 lo(tl.x(), tl.y() - shape.height_at(h)), hi(tl.x() + shape.width_at(h), tl.y());
    const Vec2 gap = Vec2::Constant(kObstacleGap * h);
    return box_inside_outline(loops, lo, hi) && !obstacles.meet(lo - gap, hi + gap);
  };
  // The pole, then every grid point inside: a block wider than high fits best where the room
  // is wide, not always at the pole. A centre is tried only when it holds a block
  // kBlockGainRel larger than the best so far, then bisected: a block centred on a point
  // shrinks into itself (and so does its gap), so fitting is monotonic.
  std::vector<Vec2> centres = {pole.point};
  for (const auto& p : grid.probes)
    if (p.d > 0) centres.push_back(p.p);
  double best_h = 0.0;
  Vec2 best_centre = pole.point;
  for (const Vec2& c : centres) {
    if (best_h >= max_h) break;
    const double floor_h = best_h > 0 ? best_h * (1.0 + kBlockGainRel) : 0.0;
    if (floor_h > 0 && !fits(c, std::min(floor_h, max_h))) continue;
    double lo = floor_h, hi = max_h;
    if (fits(c, max_h)) {
      lo = max_h;
    } else {
      for (int k = 0; k < kFitSteps; ++k) {
        const double mid = 0.5 * (lo + hi);
        (fits(c, mid) ? lo : hi) = mid;
      }
    }
    if (lo > best_h) {
      best_h = lo;
      best_centre = c;
    }
  }
  out.h = best_h;
  out.top_left = corner(best_centre, best_h);
  return out;
}

Vec2 place_label(const Vec2& anchor, const Vec2& size, const Vec2& preferred, const Vec2& towards,
                 double gap, const Obstacles& obstacles, const Obstacles* avoid_also) {
  auto free = [&](const Vec2& lo, bool both) {
    return !obstacles.meet(lo, lo + size) && !(both && avoid_also->meet(lo, lo + size));
  };
  // Side -1, 0, +1 per axis: the box below/left of, across or above/right of the anchor.
  auto side_lo = [&](int side, int axis, double g) {
    return side > 0   ? anchor[axis] + g
           : side < 0 ? anchor[axis] - g - size[axis]
                      : anchor[axis] - 0.5 * size[axis];
  };
  std::vector<Vec2> sides = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::stable_sort(sides.begin(), sides.end(), [&](const Vec2& a, const Vec2& b) {
    return a.normalized().dot(towards) > b.normalized().dot(towards);
  });
  for (const bool both : {avoid_also != nullptr, false}) {
    if (free(preferred, both)) return preferred;
    for (int ring = 1; ring <= kLabelRings; ++ring)
      for (const Vec2& sd : sides) {
        const Vec2 lo(side_lo(static_cast<int>(sd.x()), 0, ring * gap),
                      side_lo(static_cast<int>(sd.y()), 1, ring * gap));
        if (free(lo, both)) return lo;
      }
  }
  return preferred;
}

}  // namespace plyfit::exporters::render
