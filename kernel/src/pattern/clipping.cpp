// Clipping of a cell part at the face boundary: the part's corners on the surface, the
// boundary crossings on its edges, and from each exit the free boundary itself up to the
// next entry, carried into ply coordinates by the part's own interpolation.

#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// Barycentric slack when locating a (u, v) point in a cell's triangles (rounding only).
constexpr double kBarycentricSlack = 1e-12;
// A boundary vertex lies on the part's edge when this close to it, relative to the part's
// extent in its chart (rounding of the chart's coordinates).
constexpr double kOnPartRel = 1e-9;

// True when p lies inside polygon `poly` (even-odd rule).
bool in_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (std::size_t k = 0, n = poly.size(); k < n; ++k) {
    const Vec2& a = poly[k];
    const Vec2& b = poly[(k + 1) % n];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

// True when p lies in polygon `poly` or on its edges, within `slack`: a boundary vertex on a
// corner or an edge of the part (a node on a corner of the boundary) is in the part.
bool in_or_on_polygon(const std::vector<Vec2>& poly, const Vec2& p, double slack) {
  if (in_polygon(poly, p)) return true;
  for (std::size_t k = 0, n = poly.size(); k < n; ++k)
    if (segment_distance(p, poly[k], poly[(k + 1) % n]) <= slack) return true;
  return false;
}

}  // namespace

void OutlineBuilder::add_part(const std::vector<NodeId>& part) {
  Polygon poly;
  int nin = 0;
  bool all_uv = true, cut_out = false;
  for (const NodeId& id : part) {
    const int v = node_vertex(id);
    poly.push_back(v);
    nin += verts_[v].in ? 1 : 0;
    all_uv = all_uv && verts_[v].has_uv;
    cut_out = cut_out || verts_[v].cut_out;
  }
  if (nin == static_cast<int>(poly.size()) && !cut_out) {
    stair_.push_back(poly);
    // Still clip: the boundary may cross an edge twice between two mapped nodes.
  }
  if (!all_uv) {
    if (nin == static_cast<int>(poly.size())) exact_.push_back(poly);
    return;  // a corner without a position: only whole mapped parts count
  }
  for (auto& c : clip(poly))
    if (c.size() >= 3) exact_.push_back(std::move(c));
}

OutlineBuilder::Chart OutlineBuilder::part_chart(const Polygon& poly) const {
  Chart c;
  c.base = verts_[static_cast<std::size_t>(poly[0])].at;
  bool tangent = false;
  for (int v : poly)
    tangent = tangent || near_pole(verts_[static_cast<std::size_t>(v)].p3) ||
              !s_.same_chart(c.base, verts_[static_cast<std::size_t>(v)].at);
  if (!tangent) return c;
  Vec3 n = Vec3::Zero();
  for (int v : poly) {
    c.o += verts_[static_cast<std::size_t>(v)].p3;
    n += normal_at(verts_[static_cast<std::size_t>(v)]);
  }
  c.o /= static_cast<double>(poly.size());
  // Near a pole, the plane through the pole normal to the surface there: its meridians
  // (the lines through the pole) project onto straight lines, on a surface of revolution
  // exactly, so a boundary along one stays on the part's edge along it.
  if (const int q = nearest_pole(c.o); q >= 0) {
    c.o = poles_[static_cast<std::size_t>(q)];
    n = pole_normals_[static_cast<std::size_t>(q)];
  }
  const Vec3 a =
      verts_[static_cast<std::size_t>(poly[1])].p3 - verts_[static_cast<std::size_t>(poly[0])].p3;
  Vec3 e1 = a - n * (n.dot(a) / std::max(n.squaredNorm(), 1e-300));
  if (!(n.norm() > 0.0) || !(e1.norm() > 0.0)) return c;
  c.tangent = true;
  c.e1 = e1.normalized();
  c.e2 = n.normalized().cross(c.e1);
  return c;
}

// Coordinates in chart c of a point at `at` (3D point p).
Vec2 OutlineBuilder::chart_point(const Chart& c, const SurfaceLocation& at, const Vec3& p) const {
  if (c.tangent) return Vec2((p - c.o).dot(c.e1), (p - c.o).dot(c.e2));
  return c.base.uv + s_.delta(c.base, at);
}

// The part's corners in its chart; in (u, v) a pole corner takes the mean free parameter of
// its two neighbours in the part.
std::vector<Vec2> OutlineBuilder::chart_corners(const Polygon& poly, const Chart& chart) const {
  const std::size_t m = poly.size();
  std::vector<Vec2> cw(m);
  for (std::size_t k = 0; k < m; ++k) {
    const Vertex& v = verts_[static_cast<std::size_t>(poly[k])];
    cw[k] = chart_point(chart, v.at, v.p3);
  }
  if (chart.tangent) return cw;
  for (std::size_t k = 0; k < m; ++k) {
    const Vertex& v = verts_[static_cast<std::size_t>(poly[k])];
    if (!v.pole || !s_.same_chart(chart.base, v.at)) continue;
    const Vec2& a = cw[(k + m - 1) % m];
    const Vec2& b = cw[(k + 1) % m];
    cw[k][v.free] = 0.5 * (a[v.free] + b[v.free]);
  }
  return cw;
}

// The ring of the part: its corners on the surface and the crossings on its edges (exits
// and entries, alternating); true when an edge crosses the boundary.
bool OutlineBuilder::ring_items(const Polygon& poly, std::vector<Item>& items) {
  bool crossed = false;
  for (std::size_t k = 0, m = poly.size(); k < m; ++k) {
    const int a = poly[k], b = poly[(k + 1) % m];
    bool in = verts_[static_cast<std::size_t>(a)].in;
    if (in) items.push_back({a, 0});
    for (int x : crossings(a, b)) {
      items.push_back({x, in ? 1 : 2});
      in = !in;
      crossed = true;
    }
  }
  return crossed;
}

// Each exit's entry: along the boundary (walk), or where the walks disagree with the ring
// (two exits on one entry, or a walk that leaves the part) the next entry round the part.
OutlineBuilder::Pairing OutlineBuilder::pair_exits(const std::vector<Item>& items,
                                                   const Chart& chart, const std::vector<Vec2>& cw,
                                                   int turn) {
  const std::size_t n = items.size();
  Pairing pr{std::vector<int>(n, -1), std::vector<std::vector<int>>(n)};
  std::vector<int> taken(n, 0);
  bool bijective = true;
  double extent = 0.0;
  for (const Vec2& c : cw) extent = std::max(extent, (c - cw[0]).cwiseAbs().maxCoeff());
  const double slack = kOnPartRel * extent;
  for (std::size_t k = 0; k < n; ++k) {
    if (items[k].kind != 1) continue;
    pr.entry[k] = walk(items, k, turn, pr.path[k]);
    if (pr.entry[k] < 0 || taken[static_cast<std::size_t>(pr.entry[k])]++) bijective = false;
    // The boundary between an exit and its entry lies in the part: a walk that leaves it
    // went round the loop the wrong way (an exit and entry at one boundary point, as a
    // node on a corner of the boundary, whose order along the loop is rounding).
    const int bl = verts_[static_cast<std::size_t>(items[k].v)].bloop;
    for (int lv : pr.path[k]) {
      const SurfaceLocation& at =
          boundary_[static_cast<std::size_t>(bl)].points[static_cast<std::size_t>(lv)];
      if (!in_or_on_polygon(cw, chart_point(chart, at, loop_point(bl, lv)), slack)) {
        bijective = false;
        pr.entry[k] = -1;
        pr.path[k].clear();
        break;
      }
    }
  }
  if (bijective) return pr;
  auto ring_next_entry = [&](std::size_t k) {
    for (std::size_t q = 1; q < n; ++q)
      if (items[(k + q) % n].kind == 2) return static_cast<int>((k + q) % n);
    return -1;
  };
  for (std::size_t k = 0; k < n; ++k) {
    if (items[k].kind != 1) continue;
    const int e = ring_next_entry(k);
    if (pr.entry[k] != e) {
      pr.entry[k] = e;
      pr.path[k].clear();
    }
  }
  return pr;
}

// The clipped pieces: from each entry round the ring to the next exit, then along the
// boundary (its loop vertices carried into ply coordinates) to that exit's entry, until
// the piece closes.
std::vector<OutlineBuilder::Polygon> OutlineBuilder::chain_pieces(const Polygon& poly,
                                                                  const Chart& chart,
                                                                  const std::vector<Vec2>& cw,
                                                                  const std::vector<Item>& items,
                                                                  const Pairing& pairing) {
  const std::size_t n = items.size();
  std::vector<Polygon> out;
  std::vector<char> done(n, 0);
  for (std::size_t start = 0; start < n; ++start) {
    if (items[start].kind != 2 || done[start]) continue;
    Polygon p;
    std::size_t k = start;
    for (std::size_t guard = 0; guard <= n; ++guard) {
      done[k] = 1;
      p.push_back(items[k].v);
      for (k = (k + 1) % n; items[k].kind == 0; k = (k + 1) % n) p.push_back(items[k].v);
      // k is an exit: the boundary from it to its entry.
      p.push_back(items[k].v);
      // (By value: surface_vertex() appends to verts_, which may move it.)
      const int bloop = verts_[static_cast<std::size_t>(items[k].v)].bloop;
      for (int lv : pairing.path[k]) {
        const SurfaceLocation& at =
            boundary_[static_cast<std::size_t>(bloop)].points[static_cast<std::size_t>(lv)];
        const Vec3 p3 = loop_point(bloop, lv);
        p.push_back(
            surface_vertex(at, to_ply(poly, cw, chart_point(chart, at, p3)), -1, -1, 0.0, &p3));
      }
      if (pairing.entry[k] < 0) break;
      k = static_cast<std::size_t>(pairing.entry[k]);
      if (k == start || done[k]) break;
    }
    if (p.size() >= 3) out.push_back(std::move(p));
  }
  return out;
}

// The part of a polygon on the surface, as polygons: its vertices on the surface, the
// boundary crossings on its edges, and from each exit the free boundary itself, walked
// with the surface on its left to the next crossing of the part's edges (an entry), its
// vertices carried into ply coordinates by the part's own piecewise-affine interpolation
// in its chart.
std::vector<OutlineBuilder::Polygon> OutlineBuilder::clip(const Polygon& poly) {
  const std::size_t m = poly.size();
  const Chart chart = part_chart(poly);
  const std::vector<Vec2> cw = chart_corners(poly, chart);
  std::vector<Item> items;
  if (!ring_items(poly, items)) {
    if (items.size() == m) return {poly};
    return {};
  }
  // A part whose chart image runs clockwise about the outward normal (a cell the drape
  // folded over) sees the boundary the other way round.
  double area = 0.0;
  for (std::size_t k = 0; k < m; ++k) area += cross2(cw[k], cw[(k + 1) % m]);
  if (!chart.tangent) area *= s_.orientation(chart.base);
  const int turn = area < 0.0 ? -1 : 1;
  return chain_pieces(poly, chart, cw, items, pair_exits(items, chart, cw, turn));
}

// Ply coordinates of a chart point of the part: the fan triangles (0, k, k + 1) map
// affinely between the chart and the ply.
Vec2 OutlineBuilder::to_ply(const Polygon& poly, const std::vector<Vec2>& cw,
                            const Vec2& uv) const {
  Vec2 best = verts_[poly[0]].p2;
  double best_min = -INFINITY;
  for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
    const Vec2 a = cw[0], b = cw[k], c = cw[k + 1];
    const double det = cross2(b - a, c - a);
    if (det == 0.0) continue;
    const double l1 = cross2(uv - a, c - a) / det, l2 = cross2(b - a, uv - a) / det;
    const double l0 = 1.0 - l1 - l2;
    const double mn = std::min({l0, l1, l2});
    if (mn > best_min) {
      best_min = mn;
      best = l0 * verts_[poly[0]].p2 + l1 * verts_[poly[k]].p2 + l2 * verts_[poly[k + 1]].p2;
    }
    if (mn >= -kBarycentricSlack) break;
  }
  return best;
}

}  // namespace plyfit::detail
