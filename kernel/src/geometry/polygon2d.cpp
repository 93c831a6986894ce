#include <plyfit/kernel/polygon2d.hpp>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

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

// An even-odd region as a union of disjoint polygons: the symmetric difference of its loops.
BgMulti to_multi(const Region2& r) {
  BgMulti acc;
  for (const auto& loop : r) {
    if (loop.size() < 3) continue;
    BgPolygon p = to_polygon(loop);
    if (!bg::is_valid(p)) {
      // A self-touching loop: its parts by a union with nothing (Boost splits it).
      BgMulti parts;
      bg::union_(p, BgMulti{}, parts);
      BgMulti next;
      bg::sym_difference(acc, parts, next);
      acc = std::move(next);
      continue;
    }
    BgMulti next;
    bg::sym_difference(acc, p, next);
    acc = std::move(next);
  }
  return acc;
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

double region_area(const Region2& r) {
  return bg::area(to_multi(r));
}

}  // namespace plyfit
