#include "pattern/flat_pattern.hpp"
#include "drape/solvers/solvers.hpp"
#include "pattern/outline_cleanup.hpp"

#include "pattern/cells.hpp"

#include "geometry/segment_index.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace plyfit {

namespace {

// Bisection steps for a boundary crossing along a cell edge (2^-60 of the edge), used where
// the segment intersections disagree with contains() (a node on the boundary itself).
constexpr int kCrossingBisections = 60;
// Barycentric slack when locating a (u, v) point in a cell's triangles (rounding only).
constexpr double kBarycentricSlack = 1e-12;
// Corners the drape never reached are solved on the surface extended this many steps past
// the face.
constexpr double kVirtualExtensionSteps = 4.0;
// Cells with a corner within this many spacings (3D) of a pole are clipped in their tangent
// plane, not in (u, v): near a pole a straight segment in (u, v) is a circle arc about the
// pole, off the cell's straight edge by about d^2 / (8 r) at distance r (0.01 d at 12.5 d).
constexpr double kPolarSpacings = 4.0;
// An edge near a pole whose (u, v) segment's middle lies further than this many spacings
// (along the surface) off its 3D chord is clipped in its tangent plane.
constexpr double kBentEdge = 1e-3;
// Near a pole the boundary is taken as 3D pieces: each boundary segment is split until its
// pieces are at most kPieceLength spacings long and their chords within kPieceSagitta
// spacings of the curve in the middle, up to kPieceMaxDepth halvings.
constexpr double kPieceLength = 0.5;
constexpr double kPieceSagitta = 1e-4;
constexpr int kPieceMaxDepth = 40;
// Boundary loops' direction: the kDirectionVotes longest segments of a loop are probed on
// both sides at kDirectionProbe times their (u, v) length.
constexpr int kDirectionVotes = 9;
constexpr double kDirectionProbe = 1e-3;

// A vertex of the outline polygons: a node, an edge crossing or a boundary vertex.
struct Vertex {
  Vec2 p2 = Vec2::Zero();  // ply coordinates
  SurfaceLocation at;      // where it lies on the surface (if has_uv)
  Vec3 p3 = Vec3::Zero();  // its 3D point (if has_uv)
  bool has_uv = false;
  bool in = false;            // on the surface
  bool node = false;          // a node of the ply (not a crossing or boundary vertex)
  bool pole = false;          // at a degenerate point (a collapsed edge): its free parameter means
                              // nothing and is taken from its neighbours when interpolating
  int free = 1;               // at a pole: 0 if u is the free parameter, 1 if v
  int bloop = -1, bseg = -1;  // for a boundary crossing: the boundary segment it lies on
  double bs = 0.0;            // and the parameter along it (0 at its start, 1 at its end)
};

// The free boundary's segments (kind kEdge, both ends on one face) indexed per face in that
// face's (u, v), with copies shifted by a period across closed seams.
class BoundaryIndex {
 public:
  struct Ref {
    int loop, index;  // segment `index` of boundary loop `loop`
    Vec2 shift;       // the period the copy is shifted by
  };

  BoundaryIndex(const DrapeSurface& s, const std::vector<BoundaryLoop>& boundary)
      : faces_(static_cast<std::size_t>(s.face_count())) {
    std::vector<std::vector<detail::SegmentIndex::Seg>> segs(faces_.size());
    for (int l = 0; l < static_cast<int>(boundary.size()); ++l) {
      const auto& L = boundary[static_cast<std::size_t>(l)].points;
      for (int k = 0; k < static_cast<int>(L.size()); ++k) {
        if (boundary[static_cast<std::size_t>(l)].kinds[static_cast<std::size_t>(k)] !=
            BoundaryLoop::kEdge)
          continue;
        const SurfaceLocation& A = L[static_cast<std::size_t>(k)];
        const SurfaceLocation& B = L[(static_cast<std::size_t>(k) + 1) % L.size()];
        if (A.face != B.face) continue;
        const auto& d = s.domain(A);
        const bool cu = s.wrap(A.with_uv(Vec2(d.u1 + 0.5 * d.width_u(), d.v0))).uv.x() <= d.u1;
        const bool cv = s.wrap(A.with_uv(Vec2(d.u0, d.v1 + 0.5 * d.width_v()))).uv.y() <= d.v1;
        auto& F = faces_[static_cast<std::size_t>(A.face)];
        for (int su = cu ? -1 : 0; su <= (cu ? 1 : 0); ++su)
          for (int sv = cv ? -1 : 0; sv <= (cv ? 1 : 0); ++sv) {
            const Vec2 sh(su * d.width_u(), sv * d.width_v());
            segs[static_cast<std::size_t>(A.face)].push_back(
                {A.uv + sh, B.uv + sh, static_cast<int>(F.refs.size())});
            F.refs.push_back({l, k, sh});
          }
      }
    }
    for (std::size_t f = 0; f < faces_.size(); ++f)
      faces_[f].index = detail::SegmentIndex(std::move(segs[f]));
  }

  // The free-boundary segments of `face` whose boxes meet [lo, hi] (face's (u, v)), as
  // (segment a, segment b, ref) in that face's parameters.
  template <class F>
  void near(std::int32_t face, const Vec2& lo, const Vec2& hi, F&& f) const {
    const auto& Fi = faces_[static_cast<std::size_t>(face)];
    Fi.index.for_candidates(lo, hi, [&](int k) {
      const auto& g = Fi.index.seg(k);
      f(g.a, g.b, Fi.refs[static_cast<std::size_t>(g.id)]);
    });
  }

 private:
  struct FaceIndex {
    detail::SegmentIndex index;
    std::vector<Ref> refs;
  };
  std::vector<FaceIndex> faces_;
};

class Builder {
 public:
  Builder(const DrapeSurface& s, const DrapeResult& r)
      : s_(s),
        r_(r),
        ply_(*r.ply),
        boundary_(s.boundary()),
        index_(s, boundary_),
        drape_vertices_(r.nodes.size(), -1) {
    st_.spacing = ply_.d();
    st_.gamma_min = 0.0;
    st_.tol.extension_steps = kVirtualExtensionSteps;
    dmax_ = std::max(ply_.spec().d_weft, ply_.spec().d_warp);
    find_poles();
    loop_directions();
  }

  FlatPattern run() {
    solve_virtual_corners();
    // Whole cells inside the face (one part, four corners on the surface, no boundary
    // crossing on their edges) are not clipped: of their edges only those towards a cell that
    // is not whole go to the union; the others cancel there against the whole neighbour's,
    // so the outline is the same, vertex for vertex (issue 14: the boundary cells alone).
    struct Whole {
      std::int32_t i, j;
      int v[4];
    };
    std::vector<Whole> whole;
    std::vector<char> whole_at(r_.nodes.size(), 0);  // by the drape index of corner (i, j)
    // Cells farther than this from the base path's line are never split by it (their parts
    // are the four corners: see visit_mapped_cells).
    const double dx = ply_.spec().d_weft, dy = ply_.spec().d_warp;
    const Vec2 o = ply_.spec().start, dir = ply_.base_dir();
    const double strip = 2.5 * std::hypot(dx, dy);
    std::vector<NodeId> ring(4);
    for_each_touched_cell(
        r_,
        [&](std::int32_t i, std::int32_t j) {
          const NodeId corner[4] = {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                                    NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)};
          const DrapeNode* n0 = r_.find(corner[0]);
          bool mapped = n0 && n0->mapped();
          for (int k = 1; mapped && k < 4; ++k) {
            const DrapeNode* n = r_.find(corner[k]);
            mapped = n && n->mapped();
          }
          const Vec2 c((i + 0.5) * dx, (j + 0.5) * dy);
          if (mapped && std::abs(cross2(dir, c - o)) > strip) {
            Whole w{i, j, {}};
            bool in = true;
            for (int k = 0; k < 4; ++k) {
              w.v[k] = node_vertex(corner[k]);
              const Vertex& x = verts_[static_cast<std::size_t>(w.v[k])];
              in = in && x.in && x.has_uv;
            }
            if (in && !cell_crossed(w.v)) {
              whole.push_back(w);
              whole_at[static_cast<std::size_t>(n0 - r_.nodes.data())] = 1;
              return;
            }
            ring.assign(corner, corner + 4);
            add_part(ring);
            return;
          }
          for (const auto& part : cell_parts(ply_, i, j)) add_part(part);
        },
        1);
    // Edge k of a whole cell (from corner k to k + 1, counter-clockwise: (i, j), (i + 1, j),
    // (i + 1, j + 1), (i, j + 1)) borders the cell offset by kSide[k].
    static constexpr int kSide[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (const Whole& w : whole)
      for (int k = 0; k < 4; ++k) {
        const auto nb = r_.index->find(NodeId::regular(w.i + kSide[k][0], w.j + kSide[k][1]));
        if (nb < 0 || !whole_at[static_cast<std::size_t>(nb)])
          edges_.push_back({w.v[k], w.v[(k + 1) % 4]});
      }
    FlatPattern fp;
    drop_unreached(exact_);
    fp.outline = assemble(exact_, edges_);
    fp.staircase = assemble(stair_, edges_);
    for (const auto& l : fp.outline) {
      fp.area += l.hole ? -l.area : l.area;
      fp.perimeter += l.perimeter;
    }
    return fp;
  }

 private:
  using Polygon = std::vector<int>;  // vertex indices, counter-clockwise
  struct Position {
    SurfaceLocation at;
    Vec3 point;
    bool in;
  };

  // Known position of a node: mapped, extended by the drape, or virtual.
  std::optional<Position> position(const NodeId& id) const {
    if (const DrapeNode* n = r_.find(id)) {
      if (n->mapped()) return Position{n->at(), n->point, true};
      if (n->has(DrapeNode::kExtended)) return Position{n->at(), n->point, false};
    }
    const auto it = virtual_.find(id.key());
    if (it != virtual_.end()) return it->second;
    return std::nullopt;
  }

  // Positions of the corners of the touched cells that the drape did not reach, beyond the
  // face. They are solved the way the drape would have: from a weft and a warp neighbour
  // (two spheres) wherever two are known, which propagates no error; a thread is continued
  // through a neighbour (solver 3) only where no two-sphere solve is left, first along
  // segments of the drape's own nodes, and only as a last resort along segments with a
  // virtual end. (Continuing a thread extrapolates its last segment: an error in either end
  // comes out doubled, so chains of continuations through virtual nodes sheared the corner
  // cells of a cone sector by 4.5 degrees at d = L/800 and moved the face corner carried in
  // by them 0.017 d.)
  void solve_virtual_corners() {
    std::vector<NodeId> todo;
    std::unordered_map<std::uint64_t, std::size_t> slot;  // todo index by key
    for_each_touched_cell(
        r_,
        [&](std::int32_t i, std::int32_t j) {
          for (const NodeId& c : {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                                  NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)})
            if (!position(c) && slot.emplace(c.key(), todo.size()).second) todo.push_back(c);
        },
        1);
    // Work lists, so that every node is tried again only when a neighbour gains a position:
    // `queue` for two spheres; `retry` (ordered: deterministic) for a continuation along any
    // segment. Whether a node continues along the drape's own segments depends on the drape
    // alone, so one pass in order (`next`) tries each node once.
    std::vector<std::size_t> queue;
    std::set<std::size_t> retry;
    for (std::size_t k = todo.size(); k-- > 0;) {
      queue.push_back(k);
      retry.insert(k);
    }
    auto solved = [&](const NodeId& id) {
      for (int d = 0; d < 4; ++d)
        if (const auto n = ply_.neighbour(id.i, id.j, static_cast<ThreadDir>(d)))
          if (const auto it = slot.find(n->id.key());
              it != slot.end() && !virtual_.count(n->id.key())) {
            queue.push_back(it->second);
            retry.insert(it->second);
          }
    };
    auto known = [&](std::size_t k) { return virtual_.count(todo[k].key()) > 0; };
    std::size_t next = 0;
    for (;;) {  // each round solves a node or ends: at most todo.size() rounds
      while (!queue.empty()) {
        const std::size_t k = queue.back();
        queue.pop_back();
        if (!known(k) && virtual_by_spheres(todo[k])) solved(todo[k]);
      }
      bool progress = false;
      for (; next < todo.size() && !progress; ++next)
        if (!known(next) && virtual_by_continuation(todo[next], true)) {
          solved(todo[next]);
          progress = true;
        }
      while (!progress && !retry.empty()) {
        const std::size_t k = *retry.begin();
        retry.erase(retry.begin());
        if (!known(k) && virtual_by_continuation(todo[k], false)) {
          solved(todo[k]);
          progress = true;
        }
      }
      if (!progress) break;
    }
  }

  // A known neighbour of a node to be solved.
  struct Nb {
    NodeId id;
    double rest;
    Position p;
    ThreadDir dir;
  };

  // The known neighbours of a node the drape never reached, beyond the face, or none if the
  // node is a path node, known, off the ply, in an unswept half-plane (the outline stays on
  // the mapped side there), or one the drape reached and stopped for another reason than
  // leaving the face (a shear limit, an overlap, a failure, a conflict: the cloth goes no
  // further there, and a corner solved past such a node can fold its cell).
  std::vector<Nb> virtual_neighbours(const NodeId& id) const {
    std::vector<Nb> nbs;
    if (id.is_path_only() || virtual_.count(id.key())) return nbs;
    if (const DrapeNode* n = r_.find(id);
        n && (n->mapped() || n->has(DrapeNode::kExtended) || n->status != NodeStatus::kOutside))
      return nbs;
    const Vec2 q2 = ply_.pos(id);
    if (!ply_.on_ply(q2)) return nbs;
    if (ply_.side(q2) != 0 && ply_.sweep_for_side(ply_.side(q2)) < 0) return nbs;
    for (int d = 0; d < 4; ++d) {
      const auto dir = static_cast<ThreadDir>(d);
      const auto n = ply_.neighbour(id.i, id.j, dir);
      if (!n) continue;
      if (auto p = position(n->id)) nbs.push_back({n->id, n->rest, *p, dir});
    }
    return nbs;
  }

  // Keeps a virtual corner only if it lands outside the face (inside, the drape stopped for
  // another reason).
  bool accept_virtual(const NodeId& id, const SolveResult& res) {
    if (!(res.status == SolveStatus::kLeftFace && res.extended)) return false;
    virtual_[id.key()] = Position{res.at, res.point, false};
    return true;
  }

  // False when p lies on the wrong side of the line a -> b (side > 0: to its left about the
  // outward normal) near a pole, seen about the pole's normal; true elsewhere (the solver's
  // own side test holds there).
  bool on_side(const Vec3& a, const Vec3& b, const Vec3& p, double side) const {
    const int q = nearest_pole(0.5 * (a + b));
    if (q < 0) return true;
    return pole_normals_[static_cast<std::size_t>(q)].dot((b - a).cross(p - a)) * side > 0.0;
  }

  // A virtual corner from a weft and a warp neighbour with positions.
  bool virtual_by_spheres(const NodeId& id) {
    const std::vector<Nb> nbs = virtual_neighbours(id);
    const Vec2 q2 = ply_.pos(id);
    for (const Nb& a : nbs)
      for (const Nb& b : nbs) {
        if (!is_weft(a.dir) || is_weft(b.dir)) continue;
        const double side =
            cross2(ply_.pos(b.id) - ply_.pos(a.id), q2 - ply_.pos(a.id)) > 0 ? 1.0 : -1.0;
        auto solve = [&](double sd) {
          return solve_two_spheres(
              s_, {a.p.point, a.p.at, a.rest, b.p.point, b.p.at, b.rest, sd, std::nullopt}, st_);
        };
        SolveResult res = solve(side);
        // Past a pole (u < 0 on a surface of revolution) the surface's own normal is turned
        // over and the solver's branch with it: the corner came out mirrored across the line
        // a-b, on the point of the cell's opposite corner (sphere-octant, issue 13: the outline
        // ran out and back along the wedge at the pole). The other branch is then the one.
        if (res.status == SolveStatus::kLeftFace && res.extended &&
            !on_side(a.p.point, b.p.point, res.point, side))
          res = solve(-side);
        if (res.status == SolveStatus::kLeftFace && res.extended &&
            !on_side(a.p.point, b.p.point, res.point, side))
          continue;
        if (accept_virtual(id, res)) return true;
      }
    return false;
  }

  // A virtual corner continuing a thread through a neighbour: the neighbour's predecessor
  // beyond it, away from the node, gives the thread's last segment. With `drape_only`, both
  // ends of that segment must be the drape's own nodes.
  bool virtual_by_continuation(const NodeId& id, bool drape_only) {
    for (const Nb& a : virtual_neighbours(id)) {
      std::optional<PlyNeighbour> before;
      if (!a.id.is_path_only()) {
        before = ply_.neighbour(a.id.i, a.id.j, a.dir);
      } else {
        for (const auto& tn : ply_.thread_neighbours(a.id))
          if (tn.dir == a.dir) before = tn.n;
      }
      if (!before) continue;
      if (drape_only && (virtual_.count(a.id.key()) || virtual_.count(before->id.key()))) continue;
      const auto pb = position(before->id);
      if (!pb) continue;
      if (accept_virtual(
              id, solve_plane_sphere(s_, {a.p.point, a.p.at, a.rest, a.p.point - pb->point}, st_)))
        return true;
    }
    return false;
  }

  // Vertex index of a node (creating it).
  int node_vertex(const NodeId& id) {
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

  // A vertex on the surface at `at` (its 3D point evaluated), at ply point p2.
  int surface_vertex(const SurfaceLocation& at, const Vec2& p2, int bloop = -1, int bseg = -1,
                     double bs = 0.0, const Vec3* p3 = nullptr) {
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

  // A boundary crossing found on a cell edge: at parameter t along the edge, on segment `seg`
  // of boundary loop `loop` at parameter `s` along that segment.
  struct Crossing {
    double t;
    int loop, seg;
    double s;
    bool operator<(const Crossing& o) const { return t < o.t; }
  };

  // Where segment pu -> qu of the chart of `chart` crosses the free boundary, sorted by t.
  // The boundary of the chart's face is taken as it is; that of another face `other` (the
  // far end's, across a shared edge) is carried into the chart through DrapeSurface::delta.
  std::vector<Crossing> boundary_crossings(const SurfaceLocation& chart, const Vec2& pu,
                                           const Vec2& qu, const SurfaceLocation& other) const {
    std::vector<Crossing> out;
    const Vec2 r = qu - pu;
    auto test = [&](const Vec2& a, const Vec2& b, const BoundaryIndex::Ref& ref) {
      const Vec2 e = b - a;
      const double den = cross2(r, e);
      if (den == 0.0) return;  // parallel
      const double t = cross2(a - pu, e) / den;
      const double u = cross2(a - pu, r) / den;
      if (t > 0.0 && t < 1.0 && u >= 0.0 && u < 1.0) out.push_back({t, ref.loop, ref.index, u});
    };
    index_.near(chart.face, pu.cwiseMin(qu), pu.cwiseMax(qu), test);
    if (!s_.same_chart(chart, other)) {
      // The other face's segments near the far end, in its own (u, v) first.
      const Vec2 ou = other.uv, span = (s_.delta(other, chart)).cwiseAbs();
      index_.near(other.face, ou - span, ou + span,
                  [&](const Vec2& a, const Vec2& b, const BoundaryIndex::Ref& ref) {
                    if (ref.shift != Vec2::Zero()) return;  // delta takes seams the short way
                    const Vec2 ac = chart.uv + s_.delta(chart, other.with_uv(a - ref.shift));
                    const Vec2 bc = chart.uv + s_.delta(chart, other.with_uv(b - ref.shift));
                    test(ac, bc, ref);
                  });
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  // True when the point of the chart's parameters uv lies on the surface (reached from the
  // chart's location, across shared edges where the path crosses them).
  bool contains_in_chart(const SurfaceLocation& chart, const Vec2& uv) const {
    return s_.contains(s_.locate(chart, uv));
  }

  // ---- Poles: tangent-plane charts -------------------------------------------------------

  // The poles of the boundary (its collapsed segments' points, 3D).
  void find_poles() {
    const double same = st_.tol.roundoff_rel * s_.size() * 16;
    for (const auto& b : boundary_)
      for (std::size_t k = 0; k < b.points.size(); ++k) {
        if (b.kinds[k] != BoundaryLoop::kCollapsed) continue;
        const SurfaceEval1 e = s_.eval1(b.points[k]);
        if (!e.ok) continue;
        bool known = false;
        for (const Vec3& p : poles_) known = known || (p - e.p).norm() <= same;
        if (known) continue;
        poles_.push_back(e.p);
        const SurfaceNormal nn = s_.normal(s_.wrap(b.points[k]));
        pole_normals_.push_back(nn.ok ? nn.n : Vec3::Zero());
      }
  }

  // The pole nearest p within kPolarSpacings spacings whose normal is known, or -1.
  int nearest_pole(const Vec3& p) const {
    double best = kPolarSpacings * dmax_;
    int out = -1;
    for (std::size_t q = 0; q < poles_.size(); ++q)
      if (const double dq = (poles_[q] - p).norm();
          dq <= best && pole_normals_[q].squaredNorm() > 0.0) {
        best = dq;
        out = static_cast<int>(q);
      }
    return out;
  }

  // True when p lies within kPolarSpacings spacings of a pole.
  bool near_pole(const Vec3& p) const {
    const double r = kPolarSpacings * dmax_;
    for (const Vec3& q : poles_)
      if ((p - q).squaredNorm() <= r * r) return true;
    return false;
  }

  // 3D point of vertex k of boundary loop l (evaluated once).
  const Vec3& loop_point(int l, int k) {
    if (loop3d_.empty()) {
      loop3d_.resize(boundary_.size());
      for (std::size_t i = 0; i < boundary_.size(); ++i)
        loop3d_[i].assign(boundary_[i].points.size(), Vec3::Constant(NAN));
    }
    Vec3& p = loop3d_[static_cast<std::size_t>(l)][static_cast<std::size_t>(k)];
    if (std::isnan(p.x())) {
      const SurfaceEval1 e = s_.eval1(
          s_.wrap(boundary_[static_cast<std::size_t>(l)].points[static_cast<std::size_t>(k)]));
      p = e.ok ? e.p : Vec3::Zero();
    }
    return p;
  }

  // Location at parameter s of boundary segment (l, k) (both ends on one face).
  SurfaceLocation segment_point(int l, int k, double s) const {
    const auto& L = boundary_[static_cast<std::size_t>(l)].points;
    const SurfaceLocation& a = L[static_cast<std::size_t>(k)];
    const SurfaceLocation& b = L[(static_cast<std::size_t>(k) + 1) % L.size()];
    return a.with_uv(a.uv + s * s_.delta(a, b));
  }

  // A piece of a boundary segment near a pole, as a 3D chord: segment (loop, seg) from
  // parameter s0 to s1.
  struct Piece {
    Vec3 a, b;
    int loop, seg;
    double s0, s1;
  };

  // Splits boundary segment (l, k) into 3D pieces (see kPieceLength, kPieceSagitta) and
  // appends them to `out`; spans for which keep(centre, radius) is false are dropped unsplit.
  template <class Keep>
  void subdivide(int l, int k, Keep&& keep, std::vector<Piece>& out) const {
    const double max_len = kPieceLength * dmax_, max_sag = kPieceSagitta * dmax_;
    auto point = [&](double s) {
      const SurfaceEval1 e = s_.eval1(s_.wrap(segment_point(l, k, s)));
      return e.ok ? e.p : Vec3(NAN, NAN, NAN);
    };
    struct Span {
      double s0, s1;
      Vec3 a, b;
      int depth;
    };
    std::vector<Span> stack{{0.0, 1.0, point(0.0), point(1.0), 0}};
    while (!stack.empty()) {
      const Span sp = stack.back();
      stack.pop_back();
      const double sm = 0.5 * (sp.s0 + sp.s1);
      const Vec3 m = point(sm);
      if (!sp.a.allFinite() || !sp.b.allFinite() || !m.allFinite()) continue;
      const double len = (sp.b - sp.a).norm(), sag = (m - 0.5 * (sp.a + sp.b)).norm();
      if (!keep(m, 0.5 * len + sag)) continue;
      if ((len <= max_len && sag <= max_sag) || sp.depth >= kPieceMaxDepth) {
        out.push_back({sp.a, sp.b, l, k, sp.s0, sp.s1});
        continue;
      }
      stack.push_back({sm, sp.s1, m, sp.b, sp.depth + 1});
      stack.push_back({sp.s0, sm, sp.a, m, sp.depth + 1});
    }
  }

  // True when boundary segment k of loop l is a free edge on one face.
  bool real_segment(int l, int k) const {
    const auto& B = boundary_[static_cast<std::size_t>(l)];
    return B.kinds[static_cast<std::size_t>(k)] == BoundaryLoop::kEdge &&
           B.points[static_cast<std::size_t>(k)].face ==
               B.points[(static_cast<std::size_t>(k) + 1) % B.points.size()].face;
  }

  // The boundary near the poles as short 3D pieces, in a uniform grid of cells of
  // kPolarSpacings spacings (built on first use).
  void build_pieces() {
    if (pieces_built_) return;
    pieces_built_ = true;
    const double reach = (kPolarSpacings + 2.0) * dmax_;
    auto near = [&](const Vec3& c, double rad) {
      for (const Vec3& q : poles_)
        if ((c - q).norm() - rad <= reach) return true;
      return false;
    };
    for (int l = 0; l < static_cast<int>(boundary_.size()); ++l)
      for (int k = 0; k < static_cast<int>(boundary_[static_cast<std::size_t>(l)].points.size());
           ++k)
        if (real_segment(l, k)) subdivide(l, k, near, pieces_);
    grid_cell_ = kPolarSpacings * dmax_;
    for (int k = 0; k < static_cast<int>(pieces_.size()); ++k) {
      const Piece& pc = pieces_[static_cast<std::size_t>(k)];
      for_grid_cells(pc.a.cwiseMin(pc.b), pc.a.cwiseMax(pc.b),
                     [&](std::uint64_t key) { piece_grid_[key].push_back(k); });
    }
  }

  // The pieces of boundary segment (l, k), all of it (split on first use).
  const std::vector<Piece>& segment_pieces(int l, int k) {
    const std::uint64_t key = (static_cast<std::uint64_t>(l) << 32) | static_cast<std::uint32_t>(k);
    auto it = segment_pieces_.find(key);
    if (it == segment_pieces_.end()) {
      std::vector<Piece> v;
      subdivide(
          l, k, [](const Vec3&, double) { return true; }, v);
      it = segment_pieces_.emplace(key, std::move(v)).first;
    }
    return it->second;
  }

  template <class F>
  void for_grid_cells(const Vec3& lo, const Vec3& hi, F&& f) const {
    auto idx = [&](double x) { return static_cast<std::int64_t>(std::floor(x / grid_cell_)); };
    for (std::int64_t i = idx(lo.x()); i <= idx(hi.x()); ++i)
      for (std::int64_t j = idx(lo.y()); j <= idx(hi.y()); ++j)
        for (std::int64_t k = idx(lo.z()); k <= idx(hi.z()); ++k)
          f((static_cast<std::uint64_t>(i & 0x1fffff) << 42) |
            (static_cast<std::uint64_t>(j & 0x1fffff) << 21) |
            static_cast<std::uint64_t>(k & 0x1fffff));
  }

  // The pieces near the poles whose boxes meet [lo, hi], each once.
  std::vector<const Piece*> polar_pieces(const Vec3& lo, const Vec3& hi) {
    build_pieces();
    std::vector<int> ks;
    for_grid_cells(lo, hi, [&](std::uint64_t key) {
      const auto it = piece_grid_.find(key);
      if (it != piece_grid_.end()) ks.insert(ks.end(), it->second.begin(), it->second.end());
    });
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    std::vector<const Piece*> out;
    for (int k : ks) out.push_back(&pieces_[static_cast<std::size_t>(k)]);
    return out;
  }

  // The pieces of the free-boundary segments near the ends of an edge between two faces:
  // those near each end in its own face's (u, v), the span of the edge carried there.
  std::vector<const Piece*> face_pieces(const Vertex& P, const Vertex& Q) {
    std::vector<std::pair<int, int>> segs;
    for (const Vertex* A : {&P, &Q}) {
      const Vertex& B = A == &P ? Q : P;
      const Vec2 span = s_.delta(A->at, B.at).cwiseAbs();
      index_.near(A->at.face, A->at.uv - span, A->at.uv + span,
                  [&](const Vec2&, const Vec2&, const BoundaryIndex::Ref& ref) {
                    segs.push_back({ref.loop, ref.index});
                  });
    }
    std::sort(segs.begin(), segs.end());
    segs.erase(std::unique(segs.begin(), segs.end()), segs.end());
    std::vector<const Piece*> out;
    for (const auto& [l, k] : segs)
      for (const Piece& pc : segment_pieces(l, k)) out.push_back(&pc);
    return out;
  }

  // Unit outward normal at a vertex (its limit at a pole).
  Vec3 normal_at(const Vertex& v) const {
    const SurfaceNormal n = s_.normal(v.at);
    return n.ok ? n.n : Vec3::Zero();
  }

  // Boundary crossings of the edge P -> Q in the plane through the edge and the mean of the
  // normals at its ends: the chord against the boundary's 3D pieces. Used near poles, where
  // the (u, v) chart bends straight lines round the pole.
  std::vector<Crossing> tangent_crossings(const Vertex& P, const Vertex& Q) {
    std::vector<Crossing> out;
    const Vec3 d3 = Q.p3 - P.p3;
    const double len = d3.norm();
    if (!(len > 0.0)) return out;
    // The two ends' normals turned to agree first: a corner solved past a pole, on the surface
    // extended beyond it, has its parameters' normal turned over (u < 0 on a surface of
    // revolution), and the plain sum nearly cancelled, so the plane stood on edge and the
    // chord met no piece (revolution-third, issue 13: a slit out to the pole and back).
    Vec3 n = normal_at(P), nq = normal_at(Q);
    n += n.dot(nq) < 0.0 ? -nq : nq;
    Vec3 e1 = d3 - n * (n.dot(d3) / std::max(n.squaredNorm(), 1e-300));
    if (!(n.norm() > 0.0) || !(e1.norm() > 0.0)) return out;
    n.normalize();
    e1.normalize();
    const Vec3 e2 = n.cross(e1);
    const Vec3 m = 0.5 * (P.p3 + Q.p3);
    auto in2 = [&](const Vec3& x) { return Vec2((x - m).dot(e1), (x - m).dot(e2)); };
    const Vec2 p = in2(P.p3), r = in2(Q.p3) - p;
    const Vec3 margin = Vec3::Constant(len);
    const Vec3 lo = P.p3.cwiseMin(Q.p3) - margin, hi = P.p3.cwiseMax(Q.p3) + margin;
    std::vector<const Piece*> cand;
    if (near_pole(P.p3) || near_pole(Q.p3)) cand = polar_pieces(lo, hi);
    if (!s_.same_chart(P.at, Q.at))
      for (const Piece* pc : face_pieces(P, Q)) cand.push_back(pc);
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    double best_gap = INFINITY;
    Crossing nearest{0.5, -1, -1, 0.0};
    for (const Piece* pp : cand) {
      const Piece& pc = *pp;
      if ((pc.a.cwiseMax(pc.b) - lo).minCoeff() < 0.0 ||
          (hi - pc.a.cwiseMin(pc.b)).minCoeff() < 0.0)
        continue;
      if (std::abs(n.dot(pc.a - m)) > len && std::abs(n.dot(pc.b - m)) > len) continue;
      const Vec2 a = in2(pc.a), e = in2(pc.b) - a;
      const double den = cross2(r, e);
      if (den != 0.0) {
        const double t = cross2(a - p, e) / den;
        const double u = cross2(a - p, r) / den;
        if (t > 0.0 && t < 1.0 && u >= 0.0 && u < 1.0) {
          // The chord's crossing refined on the boundary curve itself (bisection of the
          // piece's span on the side of the edge's line).
          auto side = [&](double sv) {
            const SurfaceEval1 ev = s_.eval1(s_.wrap(segment_point(pc.loop, pc.seg, sv)));
            return ev.ok ? cross2(r, in2(ev.p) - p) : NAN;
          };
          double s_lo = pc.s0, s_hi = pc.s1, flo = cross2(r, a - p);
          const double fhi = cross2(r, a + e - p);
          double sx = pc.s0 + u * (pc.s1 - pc.s0);
          if (flo * fhi < 0.0) {
            for (int k = 0; k < kCrossingBisections; ++k) {
              const double mid = 0.5 * (s_lo + s_hi), fm = side(mid);
              if (!std::isfinite(fm)) break;
              if ((fm < 0.0) == (flo < 0.0)) {
                s_lo = mid;
                flo = fm;
              } else {
                s_hi = mid;
              }
            }
            sx = 0.5 * (s_lo + s_hi);
          }
          const SurfaceEval1 ex = s_.eval1(s_.wrap(segment_point(pc.loop, pc.seg, sx)));
          const double tx = ex.ok ? (in2(ex.p) - p).dot(r) / r.squaredNorm() : t;
          out.push_back({std::clamp(tx, 0.0, 1.0), pc.loop, pc.seg, sx});
          continue;
        }
      }
      // The piece nearest the edge, for a crossing the chords miss (an end on the boundary).
      for (double u : {0.0, 1.0}) {
        const Vec2 x = a + u * e;
        const double t = std::clamp((x - p).dot(r) / r.squaredNorm(), 0.0, 1.0);
        const double gap = (p + t * r - x).norm();
        if (gap < best_gap) {
          best_gap = gap;
          nearest = {std::clamp(t, 1e-9, 1.0 - 1e-9), pc.loop, pc.seg, pc.s0 + u * (pc.s1 - pc.s0)};
        }
      }
    }
    std::sort(out.begin(), out.end());
    const bool odd = out.size() % 2 == 1;
    if (odd != (P.in != Q.in)) {
      if (!out.empty()) {
        // The crossing nearest an end is the one the chords put on the wrong side of it.
        auto worst =
            std::min_element(out.begin(), out.end(), [](const Crossing& x, const Crossing& y) {
              return std::min(x.t, 1.0 - x.t) < std::min(y.t, 1.0 - y.t);
            });
        out.erase(worst);
      } else if (nearest.loop >= 0) {
        out.push_back(nearest);
      }
    }
    return out;
  }

  // ---- Edge crossings ---------------------------------------------------------------------

  // Boundary crossings on the edge between vertices a and b, in order from a to b: the
  // intersections of the edge's (u, v) segment with the free boundary, their count checked
  // against contains() at the ends (bisection when a node sits on the boundary itself); near
  // a pole, in the edge's tangent plane. Computed once per edge, in the chart of its
  // lower-numbered vertex, so that both cells sharing it get the same points (an edge with
  // none, most of them, is not stored: recomputing it gives none again).
  std::vector<int> crossings(int a, int b) {
    const bool flip = b < a;
    const std::pair<int, int> key = flip ? std::pair{b, a} : std::pair{a, b};
    auto it = crossings_.find(key);
    if (it == crossings_.end()) {
      const Vertex P = verts_[key.first];
      const Vertex Q = verts_[key.second];
      std::vector<int> ids;
      Vec2 pu = P.at.uv, qu = P.at.uv + s_.delta(P.at, Q.at);
      // From a pole the edge runs along the other end's meridian: the pole takes its free
      // parameter from the other end (an edge to a node beyond a boundary through the pole
      // then crosses at the pole itself).
      if (s_.same_chart(P.at, Q.at)) {
        if (P.pole && !Q.pole) pu[P.free] = qu[P.free];
        if (Q.pole && !P.pole) qu[Q.free] = pu[Q.free];
      }
      if (!s_.same_chart(P.at, Q.at) || bent(P, Q, pu, qu)) {
        for (const Crossing& c : tangent_crossings(P, Q))
          ids.push_back(surface_vertex(segment_point(c.loop, c.seg, c.s),
                                       P.p2 + c.t * (Q.p2 - P.p2), c.loop, c.seg, c.s));
      } else {
        auto ts = boundary_crossings(P.at, pu, qu, Q.at);
        const bool odd = ts.size() % 2 == 1;
        if (odd != (P.in != Q.in)) {
          ts.clear();
          if (P.in != Q.in) {
            double lo = 0.0, hi = 1.0;
            for (int k = 0; k < kCrossingBisections; ++k) {
              const double mid = 0.5 * (lo + hi);
              ((contains_in_chart(P.at, pu + mid * (qu - pu)) == P.in) ? lo : hi) = mid;
            }
            ts.push_back({0.5 * (lo + hi), -1, -1, 0.0});
          }
        }
        for (const Crossing& c : ts) {
          const int v = surface_vertex(s_.locate(P.at, pu + c.t * (qu - pu)),
                                       P.p2 + c.t * (Q.p2 - P.p2), c.loop, c.seg, c.s);
          if (c.loop < 0) locate_on_boundary(verts_[static_cast<std::size_t>(v)]);
          ids.push_back(v);
        }
      }
      if (ids.empty()) return ids;
      it = crossings_.emplace(key, std::move(ids)).first;
    }
    std::vector<int> out = it->second;
    if (flip) std::reverse(out.begin(), out.end());
    return out;
  }

  // True when the (u, v) segment pu -> qu of edge P -> Q, near a pole, is no straight edge
  // on the surface: its middle lies off the 3D chord, along the surface, by more than
  // kBentEdge spacings (near a pole a straight (u, v) segment is an arc about it). An edge
  // along a meridian (a thread on a boundary through the pole) stays straight and is taken
  // in (u, v), exactly.
  bool bent(const Vertex& P, const Vertex& Q, const Vec2& pu, const Vec2& qu) const {
    if (!near_pole(P.p3) && !near_pole(Q.p3)) return false;
    const SurfaceLocation mid = s_.wrap(s_.locate(P.at, 0.5 * (pu + qu)));
    const SurfaceEval1 e = s_.eval1(mid);
    const SurfaceNormal n = s_.normal(mid);
    if (!e.ok || !n.ok) return true;
    Vec3 off = e.p - 0.5 * (P.p3 + Q.p3);
    off -= n.n * n.n.dot(off);
    return off.norm() > kBentEdge * dmax_;
  }

  // True when an edge of the cell with corners v[0..3] (all on the surface) may cross the
  // boundary: its crossings, computed (and kept) when the cell's box in (u, v) meets a
  // boundary segment, or near a pole, or across faces; false at once otherwise (the edges'
  // own queries, within that box, would find none).
  bool cell_crossed(const int* v) {
    const Vertex& c0 = verts_[static_cast<std::size_t>(v[0])];
    bool quick = true;
    Vec2 lo = c0.at.uv, hi = c0.at.uv;
    for (int k = 0; quick && k < 4; ++k) {
      const Vertex& x = verts_[static_cast<std::size_t>(v[k])];
      quick = !x.pole && s_.same_chart(c0.at, x.at) && !near_pole(x.p3);
      const Vec2 p = c0.at.uv + s_.delta(c0.at, x.at);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    if (quick) {
      bool any = false;
      index_.near(c0.at.face, lo, hi,
                  [&](const Vec2&, const Vec2&, const BoundaryIndex::Ref&) { any = true; });
      if (!any) return false;
    }
    bool crossed = false;
    for (int k = 0; k < 4; ++k) crossed = !crossings(v[k], v[(k + 1) % 4]).empty() || crossed;
    return crossed;
  }

  // Sets the boundary segment and parameter of a crossing found by bisection: the nearest
  // segment in its face's parameters.
  void locate_on_boundary(Vertex& x) const {
    double bd = INFINITY;
    for (std::size_t l = 0; l < boundary_.size(); ++l) {
      const auto& L = boundary_[l].points;
      for (std::size_t k = 0; k < L.size(); ++k) {
        if (boundary_[l].kinds[k] != BoundaryLoop::kEdge || L[k].face != x.at.face) continue;
        const Vec2 a = x.at.uv + s_.delta(x.at, L[k]);
        const Vec2 ab = s_.delta(L[k], L[(k + 1) % L.size()]);
        const double t = ab.squaredNorm() > 0
                             ? std::clamp((x.at.uv - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                             : 0.0;
        const double d = (a + t * ab - x.at.uv).norm();
        if (d < bd) {
          bd = d;
          x.bloop = static_cast<int>(l);
          x.bseg = static_cast<int>(k);
          x.bs = t;
        }
      }
    }
  }

  // ---- Cell parts ---------------------------------------------------------------------------

  void add_part(const std::vector<NodeId>& part) {
    Polygon poly;
    int nin = 0;
    bool all_uv = true;
    for (const NodeId& id : part) {
      const int v = node_vertex(id);
      poly.push_back(v);
      nin += verts_[v].in ? 1 : 0;
      all_uv = all_uv && verts_[v].has_uv;
    }
    if (nin == static_cast<int>(poly.size())) {
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

  // The chart a part is clipped in: the (u, v) of its first corner (other corners carried
  // in through DrapeSurface::delta), or near a pole the tangent plane through the corners'
  // centroid (origin o, axes e1, e2 about the outward normal).
  struct Chart {
    bool tangent = false;
    SurfaceLocation base;
    Vec3 o = Vec3::Zero(), e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
  };

  Chart part_chart(const Polygon& poly) const {
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
  Vec2 chart_point(const Chart& c, const SurfaceLocation& at, const Vec3& p) const {
    if (c.tangent) return Vec2((p - c.o).dot(c.e1), (p - c.o).dot(c.e2));
    return c.base.uv + s_.delta(c.base, at);
  }

  struct Item {
    int v;
    int kind;  // 0 vertex, 1 exit crossing, 2 entry crossing
  };

  // The part of a polygon on the surface, as polygons: its vertices on the surface, the
  // boundary crossings on its edges, and from each exit the free boundary itself, walked
  // with the surface on its left to the next crossing of the part's edges (an entry), its
  // vertices carried into ply coordinates by the part's own piecewise-affine interpolation
  // in its chart.
  std::vector<Polygon> clip(const Polygon& poly) {
    const std::size_t m = poly.size();
    const Chart chart = part_chart(poly);
    std::vector<Vec2> cw(m);  // corners in the chart
    for (std::size_t k = 0; k < m; ++k) {
      const Vertex& v = verts_[static_cast<std::size_t>(poly[k])];
      cw[k] = chart_point(chart, v.at, v.p3);
    }
    if (!chart.tangent) {
      // A pole corner takes the mean free parameter of its two neighbours in the part.
      for (std::size_t k = 0; k < m; ++k) {
        const Vertex& v = verts_[static_cast<std::size_t>(poly[k])];
        if (!v.pole || !s_.same_chart(chart.base, v.at)) continue;
        const Vec2& a = cw[(k + m - 1) % m];
        const Vec2& b = cw[(k + 1) % m];
        cw[k][v.free] = 0.5 * (a[v.free] + b[v.free]);
      }
    }
    std::vector<Item> items;
    bool crossed = false;
    for (std::size_t k = 0; k < m; ++k) {
      const int a = poly[k], b = poly[(k + 1) % m];
      bool in = verts_[static_cast<std::size_t>(a)].in;
      if (in) items.push_back({a, 0});
      for (int x : crossings(a, b)) {
        items.push_back({x, in ? 1 : 2});
        in = !in;
        crossed = true;
      }
    }
    if (!crossed) {
      if (items.size() == m) return {poly};
      return {};
    }
    const std::size_t n = items.size();
    // A part whose chart image runs clockwise about the outward normal (a cell the drape
    // folded over) sees the boundary the other way round.
    double area = 0.0;
    for (std::size_t k = 0; k < m; ++k) area += cross2(cw[k], cw[(k + 1) % m]);
    if (!chart.tangent) area *= s_.orientation(chart.base);
    const int turn = area < 0.0 ? -1 : 1;
    // Each exit's entry: along the boundary, or (where the walks disagree with the ring) the
    // next entry round the part.
    std::vector<int> pair(n, -1);
    std::vector<std::vector<int>> path(n);
    auto ring_next_entry = [&](std::size_t k) {
      for (std::size_t q = 1; q < n; ++q)
        if (items[(k + q) % n].kind == 2) return static_cast<int>((k + q) % n);
      return -1;
    };
    std::vector<int> taken(n, 0);
    bool bijective = true;
    for (std::size_t k = 0; k < n; ++k) {
      if (items[k].kind != 1) continue;
      pair[k] = walk(items, k, turn, path[k]);
      if (pair[k] < 0 || taken[static_cast<std::size_t>(pair[k])]++) bijective = false;
      // The boundary between an exit and its entry lies in the part: a walk that leaves it
      // went round the loop the wrong way (an exit and entry at one boundary point, as a
      // node on a corner of the boundary, whose order along the loop is rounding).
      const int bl = verts_[static_cast<std::size_t>(items[k].v)].bloop;
      for (int lv : path[k]) {
        const SurfaceLocation& at =
            boundary_[static_cast<std::size_t>(bl)].points[static_cast<std::size_t>(lv)];
        if (!inside_polygon(cw, chart_point(chart, at, loop_point(bl, lv)))) {
          bijective = false;
          pair[k] = -1;
          path[k].clear();
          break;
        }
      }
    }
    if (!bijective)
      for (std::size_t k = 0; k < n; ++k) {
        if (items[k].kind != 1) continue;
        const int e = ring_next_entry(k);
        if (pair[k] != e) {
          pair[k] = e;
          path[k].clear();
        }
      }
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
        for (int lv : path[k]) {
          const SurfaceLocation& at =
              boundary_[static_cast<std::size_t>(bloop)].points[static_cast<std::size_t>(lv)];
          const Vec3 p3 = loop_point(bloop, lv);
          p.push_back(
              surface_vertex(at, to_ply(poly, cw, chart_point(chart, at, p3)), -1, -1, 0.0, &p3));
        }
        if (pair[k] < 0) break;
        k = static_cast<std::size_t>(pair[k]);
        if (k == start || done[k]) break;
      }
      if (p.size() >= 3) out.push_back(std::move(p));
    }
    return out;
  }

  // From exit item x, walks its boundary loop in the direction that keeps the surface on the
  // left (into the part; `turn` -1: on the right, in a folded part) to the first crossing of
  // the part's edges, and returns it (its item
  // index, -1 if it is no entry or none is found). The loop vertices passed go to `path`,
  // each 3D point once: across a junction of two faces, a collapsed edge (a pole) or a seam
  // (the walk goes on from the seam's other side) the vertex is not repeated.
  int walk(const std::vector<Item>& items, std::size_t x, int turn, std::vector<int>& path) const {
    const Vertex& X = verts_[static_cast<std::size_t>(items[x].v)];
    if (X.bloop < 0) return -1;
    const int dir = turn * dirs_[static_cast<std::size_t>(X.bloop)];
    if (dir == 0) return -1;
    const auto& B = boundary_[static_cast<std::size_t>(X.bloop)];
    const int n = static_cast<int>(B.points.size());
    int seg = X.bseg;
    double s = X.bs;
    for (int guard = 0; guard <= 2 * n; ++guard) {
      int best = -1;
      double bs = 0.0;
      for (std::size_t k = 0; k < items.size(); ++k) {
        if (k == x || items[k].kind == 0) continue;
        const Vertex& V = verts_[static_cast<std::size_t>(items[k].v)];
        if (V.bloop != X.bloop || V.bseg != seg) continue;
        if (dir > 0 ? !(V.bs > s) : !(V.bs < s)) continue;
        if (best < 0 || (dir > 0 ? V.bs < bs : V.bs > bs)) {
          best = static_cast<int>(k);
          bs = V.bs;
        }
      }
      if (best >= 0) return items[static_cast<std::size_t>(best)].kind == 2 ? best : -1;
      // On to the vertex at the segment's end, then past segments that are no boundary: a
      // seam (on from its twin), a junction or a collapsed edge (no 3D length).
      int v = dir > 0 ? (seg + 1) % n : seg;
      path.push_back(v);
      int next = dir > 0 ? v : (v + n - 1) % n;
      for (int hop = 0; hop <= n && B.kinds[static_cast<std::size_t>(next)] != BoundaryLoop::kEdge;
           ++hop) {
        if (B.kinds[static_cast<std::size_t>(next)] == BoundaryLoop::kSeam) {
          v = seam_twin(X.bloop, v, dir);
          if (v < 0) return -1;
        } else {
          v = dir > 0 ? (next + 1) % n : next;
        }
        next = dir > 0 ? v : (v + n - 1) % n;
      }
      seg = next;
      s = dir > 0 ? -1.0 : 2.0;  // any crossing on the new segment is beyond
    }
    return -1;
  }

  // Loop vertex of loop l at the same point as vertex v across a seam, from which a segment
  // other than a seam goes on in direction dir; -1 if none.
  int seam_twin(int l, int v, int dir) const {
    const auto& B = boundary_[static_cast<std::size_t>(l)];
    const int n = static_cast<int>(B.points.size());
    const auto& d = s_.domain(B.points[static_cast<std::size_t>(v)]);
    const double same = st_.tol.param_rel * std::max(d.width_u(), d.width_v()) * 16;
    for (int k = 0; k < n; ++k) {
      if (k == v ||
          B.points[static_cast<std::size_t>(k)].face != B.points[static_cast<std::size_t>(v)].face)
        continue;
      const int next = dir > 0 ? k : (k + n - 1) % n;
      if (B.kinds[static_cast<std::size_t>(next)] == BoundaryLoop::kSeam) continue;
      if (s_.delta(B.points[static_cast<std::size_t>(v)], B.points[static_cast<std::size_t>(k)])
              .norm() <= same)
        return k;
    }
    return -1;
  }

  // Per boundary loop, the direction (+1 forward, -1 backward, 0 unknown) in which it runs
  // with the surface on its left seen from the outward normal: the longest segments vote,
  // each probing contains() just left and right of its middle.
  void loop_directions() {
    for (const auto& b : boundary_) {
      const std::size_t n = b.points.size();
      std::vector<std::pair<double, std::size_t>> segs;
      for (std::size_t k = 0; k < n; ++k) {
        const SurfaceLocation& a = b.points[k];
        const SurfaceLocation& c = b.points[(k + 1) % n];
        if (b.kinds[k] != BoundaryLoop::kEdge || a.face != c.face) continue;
        const Vec2 sp = s_.speeds(a);
        const Vec2 d = s_.delta(a, c);
        segs.push_back({-std::hypot(d.x() * sp.x(), d.y() * sp.y()), k});
      }
      const std::size_t votes = std::min<std::size_t>(kDirectionVotes, segs.size());
      std::partial_sort(segs.begin(), segs.begin() + static_cast<std::ptrdiff_t>(votes),
                        segs.end());
      int vote = 0;
      for (std::size_t q = 0; q < votes; ++q) {
        const std::size_t k = segs[q].second;
        const SurfaceLocation& a = b.points[k];
        const Vec2 d = s_.delta(a, b.points[(k + 1) % n]);
        const Vec2 mid = a.uv + 0.5 * d, off = kDirectionProbe * perp(d);
        const bool left = s_.contains(s_.wrap(a.with_uv(mid + off)));
        const bool right = s_.contains(s_.wrap(a.with_uv(mid - off)));
        if (left != right) vote += (left ? 1 : -1) * (s_.orientation(a) > 0 ? 1 : -1);
      }
      dirs_.push_back(vote > 0 ? 1 : vote < 0 ? -1 : 0);
    }
  }

  // Ply coordinates of a chart point of the part: the fan triangles (0, k, k + 1) map
  // affinely between the chart and the ply.
  Vec2 to_ply(const Polygon& poly, const std::vector<Vec2>& cw, const Vec2& uv) const {
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

  // Drops the clipped pieces the cloth does not reach: those joined to no piece with a
  // mapped corner through a chain of shared edges. (A piece of a cell all of whose corners
  // lie beyond the face, where a face corner pokes into it, whose neighbour towards the face
  // the drape stopped short of, as at a lock: the cloth never gets there, but the piece made
  // a loop of its own with no mapped node, issue 13.) Pieces with a mapped corner, and so
  // every whole cell, are reached.
  void drop_unreached(std::vector<Polygon>& polys) const {
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
  // opposite directions) cancel; the rest chain into loops, outer ones counter-clockwise.
  std::vector<OutlineLoop> assemble(const std::vector<Polygon>& polys,
                                    const std::vector<std::pair<int, int>>& extra) const {
    const double merge = st_.tol.outline_merge_rel * ply_.d();
    std::map<std::pair<int, int>, int> edges;  // ordered: deterministic output
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
    std::multimap<int, int> out;  // from -> to
    for (const auto& [e, c] : edges)
      for (int k = 0; k < c; ++k) out.emplace(e.first, e.second);
    std::vector<OutlineLoop> loops;
    while (!out.empty()) {
      auto it = out.begin();
      const int start = it->first;
      int prev = start, cur = it->second;
      out.erase(it);
      std::vector<int> ids{start};
      for (std::size_t guard = 0; cur != start && guard <= edges.size() + 1; ++guard) {
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
      // Vertices closer than outline_merge_rel * d are one (a crossing computed on a cell
      // edge and the same boundary corner carried in by the cell's map, 1e-11 d apart, or a
      // corner a hair from the edge that rounding puts on the wrong side of a crossing).
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
      if (l.points.size() < 3) continue;
      double a = 0.0, per = 0.0;
      for (std::size_t k = 0; k < l.points.size(); ++k) {
        const Vec2& p = l.points[k];
        const Vec2& q = l.points[(k + 1) % l.points.size()];
        a += cross2(p, q);
        per += (q - p).norm();
      }
      if (a == 0.0) continue;
      l.area = std::abs(a) / 2;
      l.hole = a < 0;
      l.perimeter = per;
      loops.push_back(std::move(l));
    }
    std::stable_sort(loops.begin(), loops.end(), [](const OutlineLoop& a, const OutlineLoop& b) {
      if (a.hole != b.hole) return !a.hole;
      return a.area > b.area;
    });
    return loops;
  }

  const DrapeSurface& s_;
  const DrapeResult& r_;
  const Ply& ply_;
  std::vector<BoundaryLoop> boundary_;
  BoundaryIndex index_;
  SolverSettings st_;
  std::vector<Vertex> verts_;
  std::vector<int> drape_vertices_;  // vertex of each drape node (by index), or -1
  std::unordered_map<std::uint64_t, int> node_vertices_;  // vertex of other nodes (by key)
  std::unordered_map<std::uint64_t, Position> virtual_;
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
  // Edges of whole cells towards cells that are not whole: in both the outline and the
  // staircase.
  std::vector<std::pair<int, int>> edges_;
};

}  // namespace

FlatPattern flat_pattern(const DrapeSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options) {
  if (!result.ply || result.nodes.empty()) return {};
  FlatPattern fp = Builder(surface, result).run();
  const PlySpec& spec = result.ply->spec();
  fp.min_width = options.width_for(spec);
  OutlineCleanupResult cut = outline_cleanup(fp.outline, {fp.min_width});
  fp.cut = std::move(cut.loops);
  for (const auto& l : fp.cut) {
    fp.cut_area += l.hole ? -l.area : l.area;
    fp.cut_perimeter += l.perimeter;
  }
  fp.cut_removed_area = cut.removed_area;
  fp.cut_added_area = cut.added_area;
  fp.slivers = cut.slivers;
  return fp;
}

}  // namespace plyfit

namespace plyfit {

FlatPattern flat_pattern(const MoldSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options) {
  return flat_pattern(surface.impl(), result, options);
}

}  // namespace plyfit
