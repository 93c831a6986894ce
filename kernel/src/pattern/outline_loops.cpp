// The loops of the outline: the clipped pieces the cloth reaches, their union chained into
// loops (outer ones counter-clockwise, holes clockwise).

#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// The directed edges of the union of `polys` and the `extra` edges, with their counts:
// edges shared by two polygons (in opposite directions) cancel. Ordered: deterministic
// output.
std::map<std::pair<int, int>, int> union_edges(const std::vector<std::vector<int>>& polys,
                                               const std::vector<std::pair<int, int>>& extra) {
  std::map<std::pair<int, int>, int> edges;
  auto add = [&](int a, int b) {
    if (a == b) return;
    auto rev = edges.find({b, a});
    if (rev != edges.end()) {
      if (--rev->second == 0) edges.erase(rev);
    } else {
      ++edges[{a, b}];
    }
  };
  for (const auto& p : polys)
    for (std::size_t k = 0; k < p.size(); ++k) add(p[k], p[(k + 1) % p.size()]);
  for (const auto& [a, b] : extra) add(a, b);
  return edges;
}

}  // namespace

// Drops the clipped pieces the cloth does not reach: those joined to no piece with a
// mapped corner through a chain of shared edges (a piece of a cell all of whose corners
// lie beyond the face, where a face corner pokes into it, whose neighbour towards the face
// the drape stopped short of, as at a lock: the cloth never gets there). Pieces with a
// mapped corner, and so every whole cell, are reached.
void OutlineBuilder::drop_unreached(std::vector<Polygon>& polys) const {
  std::vector<char> reached(polys.size(), 0);
  std::vector<std::size_t> todo;
  for (std::size_t k = 0; k < polys.size(); ++k)
    for (int v : polys[k])
      if (!reached[k] && verts_[static_cast<std::size_t>(v)].node &&
          verts_[static_cast<std::size_t>(v)].in) {
        reached[k] = 1;
        todo.push_back(k);
      }
  if (todo.size() == polys.size()) return;  // every piece has a mapped corner (most drapes)
  struct Edge {
    int a, b;
    std::size_t poly;
    bool operator<(const Edge& o) const { return a != o.a ? a < o.a : b < o.b; }
  };
  std::vector<Edge> edges;  // directed edges of the pieces, sorted
  for (std::size_t k = 0; k < polys.size(); ++k)
    for (std::size_t q = 0; q < polys[k].size(); ++q)
      edges.push_back({polys[k][q], polys[k][(q + 1) % polys[k].size()], k});
  std::sort(edges.begin(), edges.end());
  while (!todo.empty()) {  // each piece is pushed once
    const std::size_t k = todo.back();
    todo.pop_back();
    for (std::size_t q = 0; q < polys[k].size(); ++q) {
      const Edge back{polys[k][(q + 1) % polys[k].size()], polys[k][q], 0};
      for (auto it = std::lower_bound(edges.begin(), edges.end(), back);
           it != edges.end() && it->a == back.a && it->b == back.b; ++it)
        if (!reached[it->poly]) {
          reached[it->poly] = 1;
          todo.push_back(it->poly);
        }
    }
  }
  std::size_t kept = 0;
  for (std::size_t k = 0; k < polys.size(); ++k)
    if (reached[k]) {
      if (kept != k) polys[kept] = std::move(polys[k]);
      ++kept;
    }
  polys.resize(kept);
}

// Boundary of the union of counter-clockwise polygons: edges shared by two polygons (in
// opposite directions) cancel; the rest chain into loops, outer ones counter-clockwise,
// sorted outer loops first, larger first.
std::vector<OutlineLoop> OutlineBuilder::assemble(
    const std::vector<Polygon>& polys, const std::vector<std::pair<int, int>>& extra) const {
  const std::map<std::pair<int, int>, int> edges = union_edges(polys, extra);
  std::multimap<int, int> out;  // from -> to
  for (const auto& [e, c] : edges)
    for (int k = 0; k < c; ++k) out.emplace(e.first, e.second);
  std::vector<OutlineLoop> loops;
  while (!out.empty())
    if (auto l = make_loop(chain_loop(out, edges.size() + 1))) loops.push_back(std::move(*l));
  std::stable_sort(loops.begin(), loops.end(), [](const OutlineLoop& a, const OutlineLoop& b) {
    if (a.hole != b.hole) return !a.hole;
    return a.area > b.area;
  });
  return loops;
}

// One loop's vertices, taken from the union's edges `out` from its first edge on (at most
// guard_limit steps).
std::vector<int> OutlineBuilder::chain_loop(std::multimap<int, int>& out,
                                            std::size_t guard_limit) const {
  auto it = out.begin();
  const int start = it->first;
  int prev = start, cur = it->second;
  out.erase(it);
  std::vector<int> ids{start};
  for (std::size_t guard = 0; cur != start && guard <= guard_limit; ++guard) {
    ids.push_back(cur);
    auto range = out.equal_range(cur);
    if (range.first == range.second) break;  // open chain (should not happen)
    auto pick = range.first;
    if (std::next(range.first) != range.second) {
      // Pinch vertex: the outgoing edge first clockwise from the reversed incoming one
      // keeps the region on the left and the loops simple.
      const Vec2 back = verts_[prev].p2 - verts_[cur].p2;
      double best = INFINITY;
      for (auto q = range.first; q != range.second; ++q) {
        const Vec2 d = verts_[q->second].p2 - verts_[cur].p2;
        double ang = std::atan2(cross2(d, back), d.dot(back));
        if (ang <= 0) ang += 2 * kPi;
        if (ang < best) {
          best = ang;
          pick = q;
        }
      }
    }
    prev = cur;
    cur = pick->second;
    out.erase(pick);
  }
  return ids;
}

// The outline loop through vertices `ids`, or none when fewer than three points or no area
// are left. Vertices closer than outline_merge_rel * d are one (a crossing computed on a
// cell edge and the same boundary corner carried in by the cell's map, 1e-11 d apart, or a
// corner a hair from the edge that rounding puts on the wrong side of a crossing).
std::optional<OutlineLoop> OutlineBuilder::make_loop(const std::vector<int>& ids) const {
  const double merge = st_.tol.outline_merge_rel * ply_.d();
  OutlineLoop l;
  for (int v : ids) {
    const Vec2& p = verts_[v].p2;
    if (l.points.empty() || (p - l.points.back()).norm() > merge) {
      l.points.push_back(p);
      l.points3d.push_back(verts_[v].p3);
    }
  }
  while (l.points.size() > 1 && (l.points.front() - l.points.back()).norm() <= merge) {
    l.points.pop_back();
    l.points3d.pop_back();
  }
  if (!measure_loop(l)) return std::nullopt;
  return l;
}

bool measure_loop(OutlineLoop& l) {
  if (l.points.size() < 3) return false;
  double a = 0.0, per = 0.0;
  for (std::size_t k = 0; k < l.points.size(); ++k) {
    const Vec2& p = l.points[k];
    const Vec2& q = l.points[(k + 1) % l.points.size()];
    a += cross2(p, q);
    per += (q - p).norm();
  }
  if (a == 0.0) return false;
  l.area = std::abs(a) / 2;
  l.hole = a < 0;
  l.perimeter = per;
  return true;
}

}  // namespace plyfit::detail
