#include "pattern/flat_pattern.hpp"

#include "pattern/cells.hpp"
#include "pattern/outline_builder.hpp"
#include "pattern/outline_cleanup.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace detail {

namespace {

// Corners the drape never reached are solved on the surface extended this many steps past
// the face.
constexpr double kVirtualExtensionSteps = 4.0;

}  // namespace

OutlineBuilder::OutlineBuilder(const DrapeSurface& s, const DrapeResult& r)
    : s_(s),
      r_(r),
      ply_(*r.ply),
      boundary_(s.boundary()),
      index_(s, boundary_),
      drape_vertices_(r.nodes.size(), -1),
      cells_(touched_cells(r, 1)) {
  st_.spacing = ply_.d();
  st_.gamma_min = 0.0;
  st_.tol.extension_steps = kVirtualExtensionSteps;
  dmax_ = std::max(ply_.spec().d_weft, ply_.spec().d_warp);
  find_poles();
  loop_directions();
}

// Known position of a node: mapped, extended by the drape, or virtual.
std::optional<OutlineBuilder::Position> OutlineBuilder::position(const NodeId& id) const {
  if (const DrapeNode* n = r_.find(id)) {
    if (n->mapped()) return Position{n->at(), n->point, true};
    if (n->has(DrapeNode::kExtended)) return Position{n->at(), n->point, false};
  }
  const auto it = virtual_.find(id.key());
  if (it != virtual_.end()) return it->second;
  return std::nullopt;
}

// Vertex index of a node (creating it).
int OutlineBuilder::node_vertex(const NodeId& id) {
  // A node of the drape has its slot by index (most of them: no hashing); others by key.
  const DrapeNode* n = r_.find(id);
  int* slot = nullptr;
  if (n) {
    slot = &drape_vertices_[static_cast<std::size_t>(n - r_.nodes.data())];
  } else {
    slot = &node_vertices_.try_emplace(id.key(), -1).first->second;
  }
  if (*slot >= 0) return *slot;
  Vertex v;
  v.node = true;
  v.p2 = ply_.pos(id);
  if (const auto p = n && (n->mapped() || n->has(DrapeNode::kExtended))
                         ? std::optional<Position>(Position{n->at(), n->point, n->mapped()})
                         : position(id)) {
    v.has_uv = true;
    v.at = p->at;
    v.p3 = p->point;
    v.in = p->in;
    v.placed = p->placed > 0;
    v.cut_out = p->cut_out;
    // A pole is a collapsed edge of the boundary (find_poles): nodes away from those are
    // none (no evaluation).
    SurfaceEval1 e;
    e.ok = false;
    if (near_pole(v.p3)) e = s_.eval1(v.at);
    v.pole = e.ok && s_.degenerate(v.at, e);
    if (v.pole) {  // the collapsed direction is the one whose derivative vanishes
      const Vec2 sp = s_.speeds(v.at);
      v.free = e.dv.norm() * sp.x() <= e.du.norm() * sp.y() ? 1 : 0;
    }
  }
  *slot = static_cast<int>(verts_.size());
  verts_.push_back(v);
  return *slot;
}

// Vertex index of drape node `node` (creating it).
int OutlineBuilder::drape_node_vertex(std::int32_t node) {
  const int v = drape_vertices_[static_cast<std::size_t>(node)];
  return v >= 0 ? v : node_vertex(r_.nodes[static_cast<std::size_t>(node)].id);
}

// Ply point of drape node `node` (as its vertex would have it).
Vec2 OutlineBuilder::drape_node_p2(std::int32_t node) const {
  return ply_.pos(r_.nodes[static_cast<std::size_t>(node)].id);
}

// A vertex on the surface at `at` (its 3D point evaluated), at ply point p2.
int OutlineBuilder::surface_vertex(const SurfaceLocation& at, const Vec2& p2, int bloop, int bseg,
                                   double bs, const Vec3* p3) {
  Vertex x;
  x.p2 = p2;
  x.at = s_.wrap(at);
  if (p3) {
    x.p3 = *p3;
  } else {
    const SurfaceEval1 e = s_.eval1(x.at);
    x.p3 = e.ok ? e.p : Vec3::Zero();
  }
  x.has_uv = x.in = true;
  x.bloop = bloop;
  x.bseg = bseg;
  x.bs = bs;
  verts_.push_back(x);
  return static_cast<int>(verts_.size()) - 1;
}

// Whole cells inside the face (one part, four corners on the surface, no boundary crossing
// on their edges) are not clipped: of their edges only those towards a cell that is not
// whole go to the union; the others cancel there against the whole neighbour's, so the
// outline is the same, vertex for vertex, as if every cell were clipped.
void OutlineBuilder::add_cells() {
  whole_.at.assign(r_.nodes.size(), 0);  // by the drape index of corner (i, j)
  whole_.cells.reserve(cells_.size());   // most cells are whole: no copy while growing
  std::vector<NodeId> ring(4);
  for (const auto [i, j] : cells_) add_cell(i, j, ring);
  cells_ = {};
  add_whole_cell_edges();
}

// Cell (i, j): recorded as whole, or its parts clipped.
void OutlineBuilder::add_cell(std::int32_t i, std::int32_t j, std::vector<NodeId>& ring) {
  const NodeId corner[4] = {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                            NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)};
  Whole w{i, j, {}};
  bool mapped = true;
  for (int k = 0; mapped && k < 4; ++k) {
    const DrapeNode* n = r_.find(corner[k]);
    mapped = n && n->mapped();
    w.node[k] = mapped ? static_cast<std::int32_t>(n - r_.nodes.data()) : -1;
  }
  // Cells farther than this from the base path's line are never split by it (their parts
  // are the four corners: see visit_mapped_cells).
  const double dx = ply_.spec().d_weft, dy = ply_.spec().d_warp;
  const Vec2 o = ply_.spec().start, dir = ply_.base_dir();
  const double strip = 2.5 * std::hypot(dx, dy);
  const Vec2 c((i + 0.5) * dx, (j + 0.5) * dy);
  if (!(mapped && std::abs(cross2(dir, c - o)) > strip)) {
    for (const auto& part : cell_parts(ply_, i, j)) add_part(part);
    return;
  }
  if (!cell_clear(w.node)) {
    int v[4];
    for (int k = 0; k < 4; ++k) v[k] = drape_node_vertex(w.node[k]);
    if (cell_crossed(v)) {
      ring.assign(corner, corner + 4);
      add_part(ring);
      return;
    }
  }
  whole_.cells.push_back(w);
  whole_.at[static_cast<std::size_t>(w.node[0])] = 1;
}

// The edges of whole cells towards cells that are not whole go to the union.
void OutlineBuilder::add_whole_cell_edges() {
  for (std::size_t c = 0; c < whole_.cells.size(); ++c) {
    const Whole& w = whole_.cells[c];
    for (int k = 0; k < 4; ++k) {
      const auto nb = r_.index->find(NodeId::regular(w.i + kCellSide[k][0], w.j + kCellSide[k][1]));
      if (nb < 0 || !whole_.at[static_cast<std::size_t>(nb)]) {
        edges_.push_back({drape_node_vertex(w.node[k]), drape_node_vertex(w.node[(k + 1) % 4])});
        edge_owner_.push_back(static_cast<int>(c));
      }
    }
  }
}

FlatPattern OutlineBuilder::outlines() {
  FlatPattern fp;
  drop_unreached(exact_);
  fp.outline = assemble(exact_, edges_);
  notch_darts(fp.outline);
  fp.staircase = assemble(stair_, edges_);
  for (const auto& l : fp.outline) {
    fp.area += l.hole ? -l.area : l.area;
    fp.perimeter += l.perimeter;
  }
  return fp;
}

}  // namespace detail

namespace {

// The cut outline: the exact outline without the cloth laid twice (pieces.hpp) and without
// its features narrower than the minimum width (outline_cleanup.hpp).
void cut_outline(FlatPattern& fp, detail::OutlineBuilder::LaidOnce laid_once, const PlySpec& spec,
                 const FlatPatternOptions& options) {
  fp.min_width = options.width_for(spec);
  OutlineCleanupResult cut = outline_cleanup(laid_once.loops, {fp.min_width});
  fp.cut = std::move(cut.loops);
  for (const auto& l : fp.cut) {
    fp.cut_area += l.hole ? -l.area : l.area;
    fp.cut_perimeter += l.perimeter;
  }
  fp.cut_removed_area = cut.removed_area;
  fp.laid_twice_area = laid_once.area;
  fp.cells_laid_twice = laid_once.polygons;
  fp.cut_added_area = cut.added_area;
  fp.slivers = cut.slivers;
}

}  // namespace

FlatPattern flat_pattern(const DrapeSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options) {
  if (!result.ply || result.nodes.empty()) return {};
  detail::OutlineBuilder builder(surface, result);
  builder.place_cut_out_nodes();
  builder.solve_virtual_corners();
  builder.add_cells();
  FlatPattern fp = builder.outlines();
  cut_outline(fp, builder.laid_once(fp.outline), result.ply->spec(), options);
  return fp;
}

FlatPattern flat_pattern(const MoldSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options) {
  return flat_pattern(surface.impl(), result, options);
}

}  // namespace plyfit
