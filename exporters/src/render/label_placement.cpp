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

// Signed distance: positive inside the outline.
double signed_distance(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  const double d = outline_distance(loops, p);
  return inside_outline(loops, p) ? d : -d;
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
std::vector<Probe> grid_probes(const std::vector<OutlineLoop>& loops, const detail::Box2& box,
                               double cell) {
  const Vec2 size = box.size();
  std::vector<Probe> grid;
  const auto nx = static_cast<int>(std::ceil(size.x() / cell)),
             ny = static_cast<int>(std::ceil(size.y() / cell));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx && static_cast<int>(grid.size()) < kMaxInteriorProbes; ++i) {
      const Vec2 c = box.lo + cell * Vec2(i + 0.5, j + 0.5);
      grid.push_back({c, signed_distance(loops, c)});
    }
  std::stable_sort(grid.begin(), grid.end(),
                   [](const Probe& a, const Probe& b) { return a.d > b.d; });
  return grid;
}

// Climbs from `at` uphill on the distance (pattern search: the best of eight neighbours at the
// current step, else half the step) to a local maximum, until the step is below precision / 4.
Probe climb(const std::vector<OutlineLoop>& loops, Probe at, double step, double precision) {
  for (int it = 0; it < kMaxClimbSteps && step > 0.25 * precision; ++it) {
    Probe next = at;
    for (int m = 0; m < 8; ++m) {
      const double a = m * detail::kPi / 4;
      const Vec2 q = at.p + step * Vec2(std::cos(a), std::sin(a));
      const double dq = signed_distance(loops, q);
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

double outline_distance(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& l : loops) {
    const std::size_t n = l.points.size();
    for (std::size_t k = 0, m = n - 1; k < n; m = k++)
      best = std::min(best, segment_distance(p, l.points[m], l.points[k]));
  }
  return best;
}

InteriorPoint interior_point(const std::vector<OutlineLoop>& loops, double precision) {
  InteriorPoint out;
  detail::Box2 box;
  for (const auto& l : loops)
    if (l.points.size() >= 3)
      for (const Vec2& p : l.points) box.add(p);
  if (box.empty() || !(precision > 0)) return out;
  const Vec2 size = box.size();
  const double lo_side = std::min(size.x(), size.y()), hi_side = std::max(size.x(), size.y());
  // Square cells: kGridCells along the long side, no wider than the short side (a thin
  // outline gets cells across it), and never more than kMaxInteriorProbes of them.
  const double cell = std::max(std::min(hi_side / kGridCells, lo_side),
                               hi_side / static_cast<double>(kMaxInteriorProbes));
  if (!(cell > 0)) return out;
  const std::vector<Probe> grid = grid_probes(loops, box, cell);
  Probe best{Vec2::Zero(), -std::numeric_limits<double>::infinity()};
  const std::size_t seeds = std::min<std::size_t>(grid.size(), kClimbSeeds);
  for (std::size_t k = 0; k < seeds; ++k) {
    if (!(grid[k].d > 0)) break;
    const Probe at = climb(loops, grid[k], 0.5 * cell, precision);
    if (at.d > best.d) best = at;
  }
  if (!(best.d > 0)) return out;
  out.point = best.p;
  out.radius = best.d;
  out.found = true;
  return out;
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
                       double extent, double max_h, const Vec2& fallback) {
  const InteriorPoint pole = interior_point(loops, kPolePrecisionRel * extent);
  BlockPlace out;
  out.h = max_h;
  if (!pole.found) {
    out.top_left = fallback - Vec2(0.0, 2.0 * max_h);
    return out;
  }
  auto corner = [&](double h) -> Vec2 {
    return pole.point + 0.5 * Vec2(-shape.width_at(h), shape.height_at(h));
  };
  auto fits = [&](double h) {
    const Vec2 tl = corner(h);
    return box_inside_outline(loops, Vec2(tl.x(), tl.y() - shape.height_at(h)),
                              Vec2(tl.x() + shape.width_at(h), tl.y()));
  };
  if (fits(max_h)) {
    out.top_left = corner(max_h);
    return out;
  }
  // Bisection: a block centred on the pole shrinks into itself, so fitting is monotonic; a
  // small enough block always fits (the pole is at pole.radius > 0 from every edge).
  double lo = 0.0, hi = max_h;
  for (int k = 0; k < kFitSteps; ++k) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  out.h = lo;
  out.top_left = corner(lo);
  return out;
}

}  // namespace plyfit::exporters::render
