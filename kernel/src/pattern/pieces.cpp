// Pieces of the cloth, and the cloth laid twice left out of the cut outline (pieces.hpp).

#include "pattern/pieces.hpp"

#include "drape/drape.hpp"
#include "drape/scan/scanner.hpp"
#include "pattern/grid_keys.hpp"
#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace plyfit::detail {

namespace {

// Distance from q to triangle abc: to its plane where q projects inside it, else to its
// nearest edge (a triangle of no area has only edges).
double triangle_distance(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    const Vec3 p = q - n * (n.dot(q - a) / nn);
    if (n.dot((b - a).cross(p - a)) >= 0.0 && n.dot((c - b).cross(p - b)) >= 0.0 &&
        n.dot((a - c).cross(p - c)) >= 0.0)
      return std::abs(n.dot(q - a)) / std::sqrt(nn);
  }
  return std::min(
      {segment_distance(q, a, b), segment_distance(q, b, c), segment_distance(q, c, a)});
}

// Distance from q to a polygon of cloth: to its fan of triangles from the first corner.
double polygon_distance(const Vec3& q, const std::vector<ClothCorner>& c) {
  if (c.empty()) return INFINITY;
  if (c.size() == 1) return (q - c[0].p3).norm();
  if (c.size() == 2) return segment_distance(q, c[0].p3, c[1].p3);
  double best = INFINITY;
  for (std::size_t k = 1; k + 1 < c.size(); ++k)
    best = std::min(best, triangle_distance(q, c[0].p3, c[k].p3, c[k + 1].p3));
  return best;
}

bool box(const std::vector<ClothCorner>& c, Vec3& lo, Vec3& hi) {
  if (c.empty()) return false;
  lo = hi = c[0].p3;
  for (const ClothCorner& x : c) {
    lo = lo.cwiseMin(x.p3);
    hi = hi.cwiseMax(x.p3);
  }
  return true;
}

// The cloth laid so far, in a uniform grid over the cells that hold a node corner to be
// tested (only those are ever looked up).
class ClothIndex {
 public:
  ClothIndex(const std::vector<std::vector<int>>& pieces, const ClothCorners& corners,
             double radius, double separation)
      : corners_(corners), radius_(radius), separation_(separation) {
    // Cells wider than any polygon's box grown by the radius: a polygon meets at most two
    // per axis.
    double extent = 0.0;
    Vec3 lo, hi;
    for (const auto& piece : pieces)
      for (int p : piece) {
        corners_(p, c_);
        if (box(c_, lo, hi)) extent = std::max(extent, (hi - lo).maxCoeff());
      }
    cell_ = extent + 2.0 * radius_;
    for (std::size_t k = 1; k < pieces.size(); ++k)
      for (int p : pieces[k]) {
        corners_(p, c_);
        for (const ClothCorner& x : c_)
          if (x.node) wanted_.insert(key(x.p3));
      }
  }

  // Adds polygon p to the cloth.
  void add(int p) {
    corners_(p, c_);
    Vec3 lo, hi;
    if (!box(c_, lo, hi)) return;
    const Vec3 grow = Vec3::Constant(radius_);
    for_grid_cells(lo - grow, hi + grow, cell_, [&](std::uint64_t k) {
      if (wanted_.count(k)) grid_[k].push_back(p);
    });
  }

  // True when a node corner of polygon p lies on the cloth.
  bool covers(int p) {
    corners_(p, c_);
    for (const ClothCorner& x : c_)
      if (x.node && on_cloth(x)) return true;
    return false;
  }

 private:
  std::uint64_t key(const Vec3& x) const {
    std::uint64_t out = 0;
    for_grid_cells(x, x, cell_, [&](std::uint64_t k) { out = k; });
    return out;
  }

  // Within the radius of a polygon of the cloth at least the separation away on the ply.
  bool on_cloth(const ClothCorner& x) {
    const auto it = grid_.find(key(x.p3));
    if (it == grid_.end()) return false;
    for (int p : it->second) {
      corners_(p, other_);
      double ply = INFINITY;
      for (const ClothCorner& o : other_) ply = std::min(ply, (o.p2 - x.p2).norm());
      if (ply >= separation_ && polygon_distance(x.p3, other_) <= radius_) return true;
    }
    return false;
  }

  const ClothCorners& corners_;
  double radius_, separation_;
  double cell_ = 1.0;
  std::unordered_set<std::uint64_t> wanted_;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
  std::vector<ClothCorner> c_, other_;
};

// The signed area of a ring of vertices (their ply points p2(v)).
template <class P2>
double ring_area(const int* v, std::size_t n, P2&& p2) {
  double a = 0.0;
  for (std::size_t k = 0; k < n; ++k) a += cross2(p2(v[k]), p2(v[(k + 1) % n]));
  return 0.5 * a;
}

double net_area(const std::vector<OutlineLoop>& loops) {
  double a = 0.0;
  for (const auto& l : loops) a += l.hole ? -l.area : l.area;
  return a;
}

}  // namespace

std::vector<bool> polygons_laid_twice(const std::vector<std::vector<int>>& pieces,
                                      std::size_t polygons, const ClothCorners& corners,
                                      double radius, double separation, const SeamBorder& border) {
  std::vector<bool> twice(polygons, false);
  if (pieces.size() < 2) return twice;
  ClothIndex cloth(pieces, corners, radius, separation);
  for (int p : pieces[0]) cloth.add(p);
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    bool enclosed = static_cast<bool>(border), seam = false;
    for (int p : pieces[k]) {
      twice[static_cast<std::size_t>(p)] = cloth.covers(p);
      if (!enclosed || twice[static_cast<std::size_t>(p)]) continue;
      const int b = border(p);
      enclosed = b >= 0;
      seam = seam || b > 0;
    }
    for (int p : pieces[k]) {
      if (enclosed && seam) twice[static_cast<std::size_t>(p)] = true;
      if (!twice[static_cast<std::size_t>(p)]) cloth.add(p);
    }
  }
  return twice;
}

// The whole cell at each drape node (its corner (i, j)), or -1.
std::vector<int> OutlineBuilder::whole_cell_at() const {
  std::vector<int> out(r_.nodes.size(), -1);
  for (std::size_t c = 0; c < whole_.cells.size(); ++c)
    out[static_cast<std::size_t>(r_.index->find(
        NodeId::regular(whole_.cells[c].i, whole_.cells[c].j)))] = static_cast<int>(c);
  return out;
}

// The piece of each cloth polygon (the clipped parts, exact_, then the whole cells): the
// polygons joined where they share an edge (a vertex shared alone joins nothing, as the
// outline's loops part there); a piece is named by one of its polygons.
std::vector<int> OutlineBuilder::piece_of_polygon() const {
  const std::size_t ne = exact_.size(), n = ne + whole_.cells.size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  auto join = [&](int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  };
  // The clipped parts' edges and the whole cells' edges towards them, by their ends.
  std::unordered_map<std::uint64_t, int> first;
  auto edge = [&](int a, int b, int poly) {
    const auto key =
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
        static_cast<std::uint32_t>(std::max(a, b));
    const auto [it, fresh] = first.emplace(key, poly);
    if (!fresh) join(it->second, poly);
  };
  for (std::size_t k = 0; k < ne; ++k)
    for (std::size_t q = 0; q < exact_[k].size(); ++q)
      edge(exact_[k][q], exact_[k][(q + 1) % exact_[k].size()], static_cast<int>(k));
  for (std::size_t e = 0; e < edges_.size(); ++e)
    edge(edges_[e].first, edges_[e].second, static_cast<int>(ne) + edge_owner_[e]);
  // Whole cells side by side.
  const std::vector<int> whole_at = whole_cell_at();
  for (std::size_t c = 0; c < whole_.cells.size(); ++c)
    for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}}) {
      const auto nb =
          r_.index->find(NodeId::regular(whole_.cells[c].i + di, whole_.cells[c].j + dj));
      if (nb >= 0 && whole_at[static_cast<std::size_t>(nb)] >= 0)
        join(static_cast<int>(ne + c),
             static_cast<int>(ne) + whole_at[static_cast<std::size_t>(nb)]);
    }
  std::vector<int> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = find(static_cast<int>(k));
  return out;
}

// The cloth polygons by piece, larger pieces first (ply area; ties in the order of their
// first polygon).
std::vector<std::vector<int>> OutlineBuilder::pieces_by_area() const {
  const std::vector<int> piece = piece_of_polygon();
  const std::size_t ne = exact_.size();
  auto p2 = [&](int v) { return verts_[static_cast<std::size_t>(v)].p2; };
  std::unordered_map<int, std::size_t> slot;
  std::vector<std::vector<int>> pieces;
  std::vector<double> area;
  for (std::size_t k = 0; k < piece.size(); ++k) {
    const auto [it, fresh] = slot.emplace(piece[k], pieces.size());
    if (fresh) {
      pieces.emplace_back();
      area.push_back(0.0);
    }
    pieces[it->second].push_back(static_cast<int>(k));
    area[it->second] += k < ne ? ring_area(exact_[k].data(), exact_[k].size(), p2)
                               : ring_area(whole_.cells[k - ne].node, 4, [this](std::int32_t node) {
                                   return drape_node_p2(node);
                                 });
  }
  std::vector<std::size_t> order(pieces.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
  std::vector<std::vector<int>> sorted;
  for (std::size_t k : order) sorted.push_back(std::move(pieces[k]));
  return sorted;
}

// The corners of cloth polygon k (piece_of_polygon's numbering).
void OutlineBuilder::polygon_corners(int k, std::vector<ClothCorner>& out) const {
  out.clear();
  auto push = [&](int v) {
    const Vertex& x = verts_[static_cast<std::size_t>(v)];
    out.push_back({x.p3, x.p2, x.node && x.in});
  };
  const std::size_t ne = exact_.size();
  if (static_cast<std::size_t>(k) < ne) {
    for (int v : exact_[static_cast<std::size_t>(k)]) push(v);
  } else {
    for (std::int32_t node : whole_.cells[static_cast<std::size_t>(k) - ne].node)
      out.push_back({r_.nodes[static_cast<std::size_t>(node)].point, drape_node_p2(node), true});
  }
}

// The edges of the whole cells not laid twice towards cells that are not whole or are laid
// twice (cloth polygon k is laid twice when twice[k]; the whole cells follow exact_).
std::vector<std::pair<int, int>> OutlineBuilder::whole_cell_edges(const std::vector<bool>& twice) {
  const std::size_t ne = exact_.size();
  std::vector<std::pair<int, int>> out;
  for (std::size_t e = 0; e < edges_.size(); ++e)
    if (!twice[ne + static_cast<std::size_t>(edge_owner_[e])]) out.push_back(edges_[e]);
  const std::vector<int> whole_at = whole_cell_at();
  for (std::size_t c = 0; c < whole_.cells.size(); ++c) {
    if (twice[ne + c]) continue;
    const Whole& w = whole_.cells[c];
    for (int k = 0; k < 4; ++k) {
      const auto nb = r_.index->find(NodeId::regular(w.i + kCellSide[k][0], w.j + kCellSide[k][1]));
      if (nb >= 0 && whole_at[static_cast<std::size_t>(nb)] >= 0 &&
          twice[ne + static_cast<std::size_t>(whole_at[static_cast<std::size_t>(nb)])])
        out.push_back({drape_node_vertex(w.node[k]), drape_node_vertex(w.node[(k + 1) % 4])});
    }
  }
  return out;
}

// What stops the cloth round cloth polygon k (piece_of_polygon's numbering), seen from the
// cells at its node corners (SeamBorder): the drape nodes there that are not mapped. `node_at`
// gives the drape node of each vertex (-1 for none).
int OutlineBuilder::seam_border(int k, const std::vector<std::int32_t>& node_at) const {
  int out = 0;
  auto look = [&](std::int32_t node) {
    const NodeId& id = r_.nodes[static_cast<std::size_t>(node)].id;
    if (id.is_path_only()) return;
    for (std::int32_t di = -1; di <= 1; ++di)
      for (std::int32_t dj = -1; dj <= 1; ++dj) {
        const DrapeNode* n = r_.find(NodeId::regular(id.i + di, id.j + dj));
        if (!n || n->mapped() || n->status == NodeStatus::kOutside ||
            n->status == NodeStatus::kOffPly)
          continue;
        const bool seam = n->status == NodeStatus::kOverlap || n->status == NodeStatus::kConflict;
        out = seam && out >= 0 ? 1 : -1;
      }
  };
  const std::size_t ne = exact_.size();
  if (static_cast<std::size_t>(k) >= ne) {
    for (std::int32_t node : whole_.cells[static_cast<std::size_t>(k) - ne].node) look(node);
  } else {
    for (int v : exact_[static_cast<std::size_t>(k)])
      if (node_at[static_cast<std::size_t>(v)] >= 0) look(node_at[static_cast<std::size_t>(v)]);
  }
  return out;
}

OutlineBuilder::LaidOnce OutlineBuilder::laid_once(const std::vector<OutlineLoop>& outline) {
  LaidOnce out;
  out.loops = outline;
  if (std::count_if(outline.begin(), outline.end(), [](const auto& l) { return !l.hole; }) < 2)
    return out;
  const std::size_t ne = exact_.size();
  std::vector<std::int32_t> node_at(verts_.size(), -1);
  for (std::size_t n = 0; n < drape_vertices_.size(); ++n)
    if (drape_vertices_[n] >= 0 && r_.nodes[n].mapped())
      node_at[static_cast<std::size_t>(drape_vertices_[n])] = static_cast<std::int32_t>(n);
  const std::vector<bool> twice = polygons_laid_twice(
      pieces_by_area(), ne + whole_.cells.size(),
      [this](int k, std::vector<ClothCorner>& c) { polygon_corners(k, c); }, kOverlapRel * ply_.d(),
      kOverlapSeparation * ply_.d(), [&](int k) { return seam_border(k, node_at); });
  out.polygons = static_cast<int>(std::count(twice.begin(), twice.end(), true));
  if (out.polygons == 0) return out;
  std::vector<Polygon> kept;
  for (std::size_t k = 0; k < ne; ++k)
    if (!twice[k]) kept.push_back(exact_[k]);
  out.loops = assemble(kept, whole_cell_edges(twice));
  notch_darts(out.loops);
  out.area = net_area(outline) - net_area(out.loops);
  return out;
}

}  // namespace plyfit::detail
