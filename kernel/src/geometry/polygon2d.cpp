#include <plyfit/kernel/polygon2d.hpp>

// Boost.Geometry's rescaling policy (the symmetric difference of two multi-polygons) reads
// its factor on a path GCC 12 cannot prove initialised (both branches of
// scale_box_to_integer_range set it): a false positive inside the library, silenced for its
// headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <utility>

namespace plyfit {

double signed_area(const std::vector<Vec2>& polygon) {
  double a = 0.0;
  for (std::size_t k = 0, n = polygon.size(); k < n; ++k)
    a += cross2(polygon[k], polygon[(k + 1) % n]);
  return 0.5 * a;
}

bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p) {
  bool inside = false;
  for (std::size_t k = 0, n = polygon.size(); k < n; ++k)
    if (crosses_ray(polygon[k], polygon[(k + 1) % n], p)) inside = !inside;
  return inside;
}

// The polygon booleans below go through Boost.Geometry (header-only, Debian's libboost-dev):
// a robust intersection of polygons with holes and shared (collinear) edges is a library's
// job, and the trims it clips come from CAD, full of edges shared with the domain's border.
namespace {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint>;
using BgMulti = bg::model::multi_polygon<BgPolygon>;

// One closed loop as a Boost.Geometry polygon (oriented and closed by correct()).
BgPolygon to_polygon(const std::vector<Vec2>& loop) {
  BgPolygon p;
  for (const Vec2& q : loop) p.outer().emplace_back(q.x(), q.y());
  bg::correct(p);
  return p;
}

// The parts combined by `op` two by two, a balanced tree: each part meets parts of its own
// size, not the whole result so far (a hundred darts' notches against a flat pattern's
// outline would each pass over the whole outline).
template <class Op>
BgMulti pairwise(std::vector<BgMulti> parts, Op op) {
  while (parts.size() > 1) {
    std::vector<BgMulti> next;
    for (std::size_t k = 0; k + 1 < parts.size(); k += 2) {
      BgMulti x;
      op(parts[k], parts[k + 1], x);
      next.push_back(std::move(x));
    }
    if (parts.size() % 2 == 1) next.push_back(std::move(parts.back()));
    parts = std::move(next);
  }
  return parts.empty() ? BgMulti{} : std::move(parts.front());
}

// An even-odd region as a union of disjoint polygons: the symmetric difference of its loops,
// taken two by two.
BgMulti to_multi(const Region2& r) {
  std::vector<BgMulti> parts;
  for (const auto& loop : r) {
    if (loop.size() < 3) continue;
    BgPolygon p = to_polygon(loop);
    BgMulti m;
    if (bg::is_valid(p))
      m.push_back(std::move(p));
    else  // a self-touching loop: its parts by a union with nothing (Boost splits it)
      bg::union_(p, BgMulti{}, m);
    parts.push_back(std::move(m));
  }
  return pairwise(std::move(parts), [](const BgMulti& a, const BgMulti& b, BgMulti& out) {
    bg::sym_difference(a, b, out);
  });
}

std::vector<Vec2> ring_points(const BgPolygon::ring_type& ring) {
  std::vector<Vec2> out;
  for (const BgPoint& p : ring) out.emplace_back(p.x(), p.y());
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

Region2 to_region(const BgMulti& m) {
  Region2 out;
  for (const BgPolygon& p : m) {
    if (auto outer = ring_points(p.outer()); outer.size() >= 3 && signed_area(outer) != 0.0)
      out.push_back(std::move(outer));
    for (const auto& inner : p.inners())
      if (auto hole = ring_points(inner); hole.size() >= 3 && signed_area(hole) != 0.0)
        out.push_back(std::move(hole));
  }
  return out;
}

}  // namespace

Region2 intersect_regions(const Region2& a, const Region2& b) {
  BgMulti out;
  bg::intersection(to_multi(a), to_multi(b), out);
  return to_region(out);
}

Region2 unite_regions(const Region2& a, const Region2& b) {
  BgMulti out;
  bg::union_(to_multi(a), to_multi(b), out);
  return to_region(out);
}

Region2 unite_all(const std::vector<Region2>& regions) {
  std::vector<BgMulti> parts;
  for (const Region2& r : regions) parts.push_back(to_multi(r));
  return to_region(pairwise(std::move(parts), [](const BgMulti& a, const BgMulti& b, BgMulti& out) {
    bg::union_(a, b, out);
  }));
}

std::optional<Region2> subtract_regions(const Region2& a, const Region2& b) {
  const BgMulti ma = to_multi(a), mb = to_multi(b);
  if (!bg::intersects(ma, mb)) return std::nullopt;
  BgMulti out;
  bg::difference(ma, mb, out);
  return to_region(out);
}

double region_area(const Region2& r) {
  return bg::area(to_multi(r));
}

}  // namespace plyfit

namespace plyfit {

namespace {

// A chain of a loop inside a half-plane: from where it enters (or a vertex, for a loop that
// never leaves) to where it leaves.
struct Chain {
  std::vector<ClipVertex> points;
  double entry_y = 0.0, exit_y = 0.0;
};

// The loops of `in` clipped to the half-plane side * x <= side * c (side = 1: x <= c; -1:
// x >= c). In the frame turned by 180 degrees for side -1 (orientation kept), the boundary
// along the line runs up (+y): from each exit to the entry next above it.
std::vector<std::vector<ClipVertex>> clip_half(const std::vector<std::vector<ClipVertex>>& in,
                                               double c, double side) {
  auto x_of = [&](const Vec2& p) { return side * p.x(); };
  auto y_of = [&](const Vec2& p) { return side * p.y(); };
  const double cc = side * c;
  std::vector<std::vector<ClipVertex>> out;
  std::vector<Chain> chains;
  for (const auto& loop : in) {
    const std::size_t n = loop.size();
    std::size_t first_exit = n;
    for (std::size_t k = 0; k < n && first_exit == n; ++k)
      if (x_of(loop[k].p) <= cc && x_of(loop[(k + 1) % n].p) > cc) first_exit = k;
    if (first_exit == n) {  // no exit: wholly inside or wholly outside
      if (n > 0 && x_of(loop[0].p) <= cc) out.push_back(loop);
      continue;
    }
    Chain chain;
    bool inside = false;
    for (std::size_t s = 2; s <= n + 1; ++s) {  // the edges after the first exit, round to it
      const std::size_t k = (first_exit + s) % n;
      const ClipVertex& a = loop[(k + n - 1) % n];
      const ClipVertex& b = loop[k];
      const bool a_in = x_of(a.p) <= cc, b_in = x_of(b.p) <= cc;
      if (a_in != b_in) {
        const double t = (cc - x_of(a.p)) / (x_of(b.p) - x_of(a.p));
        ClipVertex v = a;  // on a's edge of the input: a's own edge and t compose linearly
        v.p = a.p + t * (b.p - a.p);
        v.p.x() = c;
        const ClipVertex& next = b;
        v.t = a.t + t * ((next.edge == a.edge && next.loop == a.loop ? next.t : 1.0) - a.t);
        if (!a_in) {
          chain = Chain{{v}, y_of(v.p), 0.0};
          inside = true;
        } else {
          chain.points.push_back(v);
          chain.exit_y = y_of(v.p);
          // A chain that only touches the line (all its points one) is no boundary.
          const bool touch = std::all_of(chain.points.begin(), chain.points.end(),
                                         [&](const ClipVertex& q) { return q.p == v.p; });
          if (!touch) chains.push_back(std::move(chain));
          chain = Chain{};
          inside = false;
        }
      }
      if (b_in && inside && (b.p - chain.points.back().p).squaredNorm() > 0.0)
        chain.points.push_back(b);
    }
  }
  // Link each chain's exit to the entry next above it on the line.
  std::vector<int> next(chains.size(), -1);
  for (std::size_t a = 0; a < chains.size(); ++a) {
    double best = INFINITY;
    for (std::size_t b = 0; b < chains.size(); ++b)
      if (chains[b].entry_y >= chains[a].exit_y && chains[b].entry_y < best) {
        best = chains[b].entry_y;
        next[a] = static_cast<int>(b);
      }
  }
  std::vector<bool> used(chains.size(), false);
  for (std::size_t a = 0; a < chains.size(); ++a) {
    if (used[a]) continue;
    std::vector<ClipVertex> loop;
    for (int k = static_cast<int>(a); k >= 0 && !used[static_cast<std::size_t>(k)];
         k = next[static_cast<std::size_t>(k)]) {
      used[static_cast<std::size_t>(k)] = true;
      for (const ClipVertex& v : chains[static_cast<std::size_t>(k)].points)
        if (loop.empty() || (v.p - loop.back().p).squaredNorm() > 0.0) loop.push_back(v);
    }
    while (loop.size() > 1 && (loop.front().p - loop.back().p).squaredNorm() == 0.0)
      loop.pop_back();
    if (loop.size() >= 3) out.push_back(std::move(loop));
  }
  return out;
}

}  // namespace

std::vector<std::vector<ClipVertex>> clip_to_slab(const Region2& loops, double lo, double hi) {
  std::vector<std::vector<ClipVertex>> in;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    std::vector<ClipVertex> loop;
    for (std::size_t k = 0; k < loops[l].size(); ++k) loop.push_back({loops[l][k], l, k, 0.0});
    in.push_back(std::move(loop));
  }
  return clip_half(clip_half(in, hi, 1.0), lo, -1.0);
}

}  // namespace plyfit
