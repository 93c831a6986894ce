#pragma once
/// \file The builder of a flat pattern's outlines (internal to pattern/). Its steps, run by
/// flat_pattern() (flat_pattern.cpp):
///  - virtual corners (virtual_corners.cpp): the corners of the touched cells the drape never
///    reached, solved beyond the face, so that every cell crossing the boundary has a map;
///  - cells (flat_pattern.cpp): whole cells inside the face give their edges towards the
///    rest; the other cell parts are clipped at the face boundary (clipping.cpp), where their
///    edges cross it (edge_crossings.cpp; near poles in tangent planes, poles.cpp) and from
///    each exit the boundary is walked to the next entry (boundary_walk.cpp);
///  - loops (outline_loops.cpp): the pieces the cloth does not reach are dropped and the union
///    of the rest is chained into loops, the exact outline and the staircase;
///  - darts (dart_notch.cpp): the ply nodes a dart cuts out are placed through the cloth
///    beside them, so that their cells count as cloth, and the V between each dart's cut lines
///    is then taken out of the exact outline: a notch bounded by the two cut lines.

#include "drape/solvers/solvers.hpp"
#include "pattern/boundary_index.hpp"
#include "pattern/cells.hpp"
#include "pattern/pieces.hpp"
#include "surface/drape_surface.hpp"

#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/polygon2d.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace plyfit::detail {

// Bisection steps for a boundary crossing along a cell edge (2^-60 of the edge), used where
// the segment intersections disagree with contains() (a node on the boundary itself).
inline constexpr int kCrossingBisections = 60;
// Cells with a corner within this many spacings (3D) of a pole are clipped in their tangent
// plane, not in (u, v): near a pole a straight segment in (u, v) is a circle arc about the
// pole, off the cell's straight edge by about d^2 / (8 r) at distance r (0.01 d at 12.5 d).
inline constexpr double kPolarSpacings = 4.0;

// Edge k of a cell (from corner k to k + 1, counter-clockwise: (i, j), (i + 1, j),
// (i + 1, j + 1), (i, j + 1)) borders the cell offset by kCellSide[k].
inline constexpr int kCellSide[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};

/// Sets the loop's area, perimeter and orientation (hole: clockwise) from its points; false
/// when it encloses no area.
bool measure_loop(OutlineLoop& l);

class OutlineBuilder {
 public:
  OutlineBuilder(const DrapeSurface& s, const DrapeResult& r);

  /// Positions of the corners of the touched cells that the drape did not reach, beyond the
  /// face (virtual_corners.cpp).
  void solve_virtual_corners();
  /// Every cell near a mapped node: whole cells inside the face give their edges towards the
  /// cells that are not whole, the others their parts clipped at the face boundary.
  void add_cells();
  /// The exact outline and the staircase: the union of the reached pieces, as loops.
  FlatPattern outlines();

  /// The exact outline without the cloth laid twice (pieces.hpp), what the cut outline is
  /// made from: `polygons` cells or cell parts left out, `area` their area.
  struct LaidOnce {
    std::vector<OutlineLoop> loops;
    int polygons = 0;
    double area = 0.0;
  };
  /// `outline` is the exact outline (outlines()); with one outer loop it is all laid once
  /// and comes back as it is.
  LaidOnce laid_once(const std::vector<OutlineLoop>& outline);
  /// Positions of the ply nodes the darts cut out (dart_notch.cpp): carried from the nearest
  /// mapped node's cell, as the cloth beside the V would lie there. Before the virtual
  /// corners, which may continue from them past the face.
  void place_cut_out_nodes();

 private:
  // A vertex of the outline polygons: a node, an edge crossing or a boundary vertex.
  struct Vertex {
    Vec2 p2 = Vec2::Zero();  // ply coordinates
    SurfaceLocation at;      // where it lies on the surface (if has_uv)
    Vec3 p3 = Vec3::Zero();  // its 3D point (if has_uv)
    bool has_uv = false;
    bool in = false;       // on the surface
    bool node = false;     // a node of the ply (not a crossing or boundary vertex)
    bool placed = false;   // a virtual corner placed, not solved: no point of the surface
    bool pole = false;     // at a degenerate point (a collapsed edge): its free parameter means
                           // nothing and is taken from its neighbours when interpolating
    bool cut_out = false;  // a ply node a dart cuts out: its cells are cloth, not the staircase's
    int free = 1;          // at a pole: 0 if u is the free parameter, 1 if v
    int bloop = -1, bseg = -1;  // for a boundary crossing: the boundary segment it lies on
    double bs = 0.0;            // and the parameter along it (0 at its start, 1 at its end)
  };
  using Polygon = std::vector<int>;  // vertex indices, counter-clockwise
  struct Position {
    SurfaceLocation at;
    Vec3 point;
    bool in;
    // A virtual corner placed, not solved (no point of the surface): how many placed
    // corners it was placed from, plus one; 0 for one solved or mapped.
    int placed = 0;
    bool cut_out = false;  // a ply node a dart cuts out (place_cut_out_nodes)
  };
  // A known neighbour of a node to be solved.
  struct Nb {
    NodeId id;
    double rest;
    Position p;
    ThreadDir dir;
  };
  // A boundary crossing found on a cell edge: at parameter t along the edge, on segment `seg`
  // of boundary loop `loop` at parameter `s` along that segment.
  struct Crossing {
    double t;
    int loop, seg;
    double s;
    bool operator<(const Crossing& o) const { return t < o.t; }
  };
  // A piece of a boundary segment near a pole, as a 3D chord: segment (loop, seg) from
  // parameter s0 to s1.
  struct Piece {
    Vec3 a, b;
    int loop, seg;
    double s0, s1;
  };
  // The plane an edge P -> Q is clipped in near a pole (tangent_crossings): through the
  // edge and the mean of the normals at its ends, origin m its middle, axes e1 along the
  // edge and e2; the edge is p -> p + r in the plane, [lo, hi] its 3D box grown by its
  // length len.
  struct EdgePlane {
    Vec3 n, e1, e2, m, lo, hi;
    double len = 0.0;
    Vec2 p, r;
    Vec2 in2(const Vec3& x) const { return Vec2((x - m).dot(e1), (x - m).dot(e2)); }
  };
  // The chart a part is clipped in: the (u, v) of its first corner (other corners carried
  // in through DrapeSurface::delta), or near a pole the tangent plane through the corners'
  // centroid (origin o, axes e1, e2 about the outward normal).
  struct Chart {
    bool tangent = false;
    SurfaceLocation base;
    Vec3 o = Vec3::Zero(), e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
  };
  struct Item {
    int v;
    int kind;  // 0 vertex, 1 exit crossing, 2 entry crossing
  };
  // Each exit item's entry item (-1: none) and the boundary loop vertices between them.
  struct Pairing {
    std::vector<int> entry;
    std::vector<std::vector<int>> path;
  };
  // Whole cells (inside the face, not crossed): their corners as drape node indices (a
  // corner becomes an outline vertex only when an edge of the cell goes to the union), and a
  // flag per drape node at corner (i, j) of a whole cell.
  struct Whole {
    std::int32_t i, j;
    std::int32_t node[4];
  };
  struct WholeCells {
    std::vector<Whole> cells;
    std::vector<char> at;
  };

  // ---- Vertices (flat_pattern.cpp)
  std::optional<Position> position(const NodeId& id) const;
  int node_vertex(const NodeId& id);
  int drape_node_vertex(std::int32_t node);
  Vec2 drape_node_p2(std::int32_t node) const;
  int surface_vertex(const SurfaceLocation& at, const Vec2& p2, int bloop = -1, int bseg = -1,
                     double bs = 0.0, const Vec3* p3 = nullptr);
  void add_cell(std::int32_t i, std::int32_t j, std::vector<NodeId>& ring);
  void add_whole_cell_edges();

  // ---- Pieces (pieces.cpp)
  std::vector<int> whole_cell_at() const;
  std::vector<int> piece_of_polygon() const;
  std::vector<std::vector<int>> pieces_by_area() const;
  std::vector<std::pair<int, int>> whole_cell_edges(const std::vector<bool>& twice);
  void polygon_corners(int k, std::vector<ClothCorner>& out) const;
  int seam_border(int k, const std::vector<std::int32_t>& node_at) const;

  // ---- Virtual corners (virtual_corners.cpp)
  std::vector<Nb> virtual_neighbours(const NodeId& id, bool solved_only) const;
  bool accept_virtual(const NodeId& id, const SolveResult& res);
  bool on_side(const Vec3& a, const Vec3& b, const Vec3& p, double side) const;
  bool virtual_by_spheres(const NodeId& id);
  std::optional<PlyNeighbour> thread_before(const Nb& a) const;
  bool virtual_by_continuation(const NodeId& id, bool drape_only);
  bool virtual_by_extrapolation(const NodeId& id);

  // ---- Poles and the boundary as 3D pieces (poles.cpp)
  void find_poles();
  int nearest_pole(const Vec3& p) const;
  bool near_pole(const Vec3& p) const;
  const Vec3& loop_point(int l, int k);
  SurfaceLocation segment_point(int l, int k, double s) const;
  template <class Keep>
  void subdivide(int l, int k, Keep&& keep, std::vector<Piece>& out) const;
  bool real_segment(int l, int k) const;
  void build_pieces();
  const std::vector<Piece>& segment_pieces(int l, int k);
  std::vector<const Piece*> polar_pieces(const Vec3& lo, const Vec3& hi);
  std::vector<const Piece*> face_pieces(const Vertex& P, const Vertex& Q);
  Vec3 normal_at(const Vertex& v) const;

  // ---- Edge crossings (edge_crossings.cpp)
  std::vector<Crossing> boundary_crossings(const SurfaceLocation& chart, const Vec2& pu,
                                           const Vec2& qu, const SurfaceLocation& other) const;
  bool contains_in_chart(const SurfaceLocation& chart, const Vec2& uv) const;
  std::optional<EdgePlane> edge_plane(const Vertex& P, const Vertex& Q) const;
  std::vector<Crossing> tangent_crossings(const Vertex& P, const Vertex& Q);
  std::vector<const Piece*> tangent_candidates(const Vertex& P, const Vertex& Q,
                                               const EdgePlane& E);
  std::optional<Crossing> chord_crossing(const EdgePlane& E, const Piece& pc, const Vec2& a,
                                         const Vec2& e) const;
  std::vector<int> crossings(int a, int b);
  Vec2 crossing_p2(const Vertex& P, const Vertex& Q, double t, const SurfaceLocation& at) const;
  std::vector<Crossing> chart_crossings(const Vertex& P, const Vertex& Q, const Vec2& pu,
                                        const Vec2& qu) const;
  bool bent(const Vertex& P, const Vertex& Q, const Vec2& pu, const Vec2& qu) const;
  bool cell_crossed(const int* v);
  bool cell_clear(const std::int32_t* node) const;
  void locate_on_boundary(Vertex& x) const;

  // ---- Clipping of cell parts (clipping.cpp)
  void add_part(const std::vector<NodeId>& part);
  Chart part_chart(const Polygon& poly) const;
  Vec2 chart_point(const Chart& c, const SurfaceLocation& at, const Vec3& p) const;
  std::vector<Vec2> chart_corners(const Polygon& poly, const Chart& chart) const;
  bool ring_items(const Polygon& poly, std::vector<Item>& items);
  Pairing pair_exits(const std::vector<Item>& items, const Chart& chart,
                     const std::vector<Vec2>& cw, int turn);
  std::vector<Polygon> chain_pieces(const Polygon& poly, const Chart& chart,
                                    const std::vector<Vec2>& cw, const std::vector<Item>& items,
                                    const Pairing& pairing);
  std::vector<Polygon> clip(const Polygon& poly);
  Vec2 to_ply(const Polygon& poly, const std::vector<Vec2>& cw, const Vec2& uv) const;

  // ---- The boundary walk (boundary_walk.cpp)
  int walk(const std::vector<Item>& items, std::size_t x, int turn, std::vector<int>& path) const;
  int seam_twin(int l, int v, int dir) const;
  void loop_directions();

  // ---- Darts (dart_notch.cpp)
  std::optional<Position> cloth_position(const Vec2& q2) const;
  Region2 dart_notches(const Region2& region) const;
  void notch_darts(std::vector<OutlineLoop>& loops) const;

  // ---- Loops (outline_loops.cpp)
  void drop_unreached(std::vector<Polygon>& polys) const;
  std::vector<OutlineLoop> assemble(const std::vector<Polygon>& polys,
                                    const std::vector<std::pair<int, int>>& extra) const;
  std::vector<int> chain_loop(std::multimap<int, int>& out, std::size_t guard_limit) const;
  std::optional<OutlineLoop> make_loop(const std::vector<int>& ids) const;

  const DrapeSurface& s_;
  const DrapeResult& r_;
  const Ply& ply_;
  std::vector<BoundaryLoop> boundary_;
  BoundaryIndex index_;
  SolverSettings st_;
  std::vector<Vertex> verts_;
  std::vector<int> drape_vertices_;  // vertex of each drape node (by index), or -1
  // The cells within one cell of a mapped node (touched_cells): the virtual corners' and the
  // outline's, in one order; freed once the cells are added.
  std::vector<CellIndex> cells_;
  std::unordered_map<std::uint64_t, int> node_vertices_;  // vertex of other nodes (by key)
  std::unordered_map<std::uint64_t, Position> virtual_;
  // The solves of virtual corners that did not land: (node, weft neighbour, warp neighbour)
  // for two spheres, (node, neighbour, the node before it) for a continuation. Positions never
  // change once known, so such a solve, asked again when another neighbour gains a position,
  // would fail again.
  std::set<std::array<std::uint64_t, 3>> failed_spheres_, failed_continuations_;
  std::map<std::pair<int, int>, std::vector<int>> crossings_;
  double dmax_ = 1.0;                      // the larger spacing
  std::vector<int> dirs_;                  // per boundary loop: see loop_directions()
  std::vector<Vec3> poles_;                // 3D points of the boundary's collapsed edges
  std::vector<Vec3> pole_normals_;         // and the outward normals there (zero: unknown)
  std::vector<std::vector<Vec3>> loop3d_;  // 3D points of the loop vertices (NaN: not yet)
  bool pieces_built_ = false;
  std::vector<Piece> pieces_;  // the boundary near the poles
  std::unordered_map<std::uint64_t, std::vector<Piece>> segment_pieces_;  // by (loop, segment)
  double grid_cell_ = 1.0;
  std::unordered_map<std::uint64_t, std::vector<int>> piece_grid_;
  std::vector<Polygon> exact_, stair_;
  WholeCells whole_;
  // Edges of whole cells towards cells that are not whole: in both the outline and the
  // staircase; and the whole cell each comes from.
  std::vector<std::pair<int, int>> edges_;
  std::vector<int> edge_owner_;
};

}  // namespace plyfit::detail
