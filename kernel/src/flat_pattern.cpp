#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/solvers.hpp>

#include <plyfit/kernel/cells.hpp>

#include "segment_index.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

namespace plyfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Bisection steps for a boundary crossing along a cell edge (2^-60 of the edge), used where
// the segment intersections disagree with contains() (a node on the boundary itself).
constexpr int kCrossingBisections = 60;
// Barycentric slack when locating a (u, v) point in a cell's triangles (rounding only).
constexpr double kBarycentricSlack = 1e-12;
// Corners the drape never reached are solved on the surface extended this many steps past
// the face.
constexpr double kVirtualExtensionSteps = 4.0;

// Per boundary-loop vertex: does it lie on a collapsed edge (a segment of no 3D length, as a
// pole's domain edge)? Such edges are no boundary of the face: crossings with them are
// artefacts of the parametrisation and their vertices are no corners.
std::vector<std::vector<bool>> collapsed_vertices(const std::vector<BoundaryLoop>& boundary) {
  std::vector<std::vector<bool>> out;
  for (const auto& b : boundary) {
    const std::size_t n = b.points.size();
    std::vector<bool> v(n, false);
    for (std::size_t k = 0; k < n; ++k)
      if (b.kinds[k] == BoundaryLoop::kCollapsed) v[k] = v[(k + 1) % n] = true;
    out.push_back(std::move(v));
  }
  return out;
}

// A vertex of the outline polygons: a node, an edge crossing or a boundary vertex.
struct Vertex {
  Vec2 p2 = Vec2::Zero();  // ply coordinates
  SurfaceLocation at;      // where it lies on the surface (if has_uv)
  Vec3 p3 = Vec3::Zero();  // its 3D point (if has_uv)
  bool has_uv = false;
  bool in = false;            // on the surface
  bool pole = false;          // at a degenerate point (a collapsed edge): its free parameter means
                              // nothing and is taken from its neighbours when interpolating
  int free = 1;               // at a pole: 0 if u is the free parameter, 1 if v
  int bloop = -1, bseg = -1;  // for a boundary crossing: the boundary segment it lies on
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
        collapsed_(collapsed_vertices(boundary_)),
        index_(s, boundary_),
        drape_vertices_(r.nodes.size(), -1) {
    st_.spacing = ply_.d();
    st_.gamma_min = 0.0;
    st_.tol.extension_steps = kVirtualExtensionSteps;
  }

  FlatPattern run() {
    solve_virtual_corners();
    for_each_touched_cell(
        r_,
        [&](std::int32_t i, std::int32_t j) {
          for (const auto& part : cell_parts(ply_, i, j)) add_part(part);
        },
        1);
    FlatPattern fp;
    fp.outline = assemble(exact_);
    fp.staircase = assemble(stair_);
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
  // node is a path node, known, or in an unswept half-plane (the outline stays on the mapped
  // side there).
  std::vector<Nb> virtual_neighbours(const NodeId& id) const {
    std::vector<Nb> nbs;
    if (id.is_path_only() || virtual_.count(id.key())) return nbs;
    if (const DrapeNode* n = r_.find(id); n && (n->mapped() || n->has(DrapeNode::kExtended)))
      return nbs;
    const Vec2 q2 = ply_.pos(id);
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

  // A virtual corner from a weft and a warp neighbour with positions.
  bool virtual_by_spheres(const NodeId& id) {
    const std::vector<Nb> nbs = virtual_neighbours(id);
    const Vec2 q2 = ply_.pos(id);
    for (const Nb& a : nbs)
      for (const Nb& b : nbs) {
        if (!is_weft(a.dir) || is_weft(b.dir)) continue;
        const double side =
            cross2(ply_.pos(b.id) - ply_.pos(a.id), q2 - ply_.pos(a.id)) > 0 ? 1.0 : -1.0;
        if (accept_virtual(id, solve_two_spheres(s_,
                                                 {a.p.point, a.p.at, a.rest, b.p.point, b.p.at,
                                                  b.rest, side, std::nullopt},
                                                 st_)))
          return true;
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
    v.p2 = ply_.pos(id);
    if (const auto p = n && (n->mapped() || n->has(DrapeNode::kExtended))
                           ? std::optional<Position>(Position{n->at(), n->point, n->mapped()})
                           : position(id)) {
      v.has_uv = true;
      v.at = p->at;
      v.p3 = p->point;
      v.in = p->in;
      const SurfaceEval1 e = s_.eval1(v.at);
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
  int surface_vertex(const SurfaceLocation& at, const Vec2& p2, int bloop = -1, int bseg = -1) {
    Vertex x;
    x.p2 = p2;
    x.at = s_.wrap(at);
    const SurfaceEval1 e = s_.eval1(x.at);
    x.p3 = e.ok ? e.p : Vec3::Zero();
    x.has_uv = x.in = true;
    x.bloop = bloop;
    x.bseg = bseg;
    verts_.push_back(x);
    return static_cast<int>(verts_.size()) - 1;
  }

  // Where segment pu -> qu of the chart of `chart` crosses the free boundary: (t, loop,
  // segment) sorted by t. The boundary of the chart's face is taken as it is; that of
  // another face `other` (the far end's, across a shared edge) is carried into the chart
  // through DrapeSurface::delta.
  std::vector<std::tuple<double, int, int>> boundary_crossings(const SurfaceLocation& chart,
                                                               const Vec2& pu, const Vec2& qu,
                                                               const SurfaceLocation& other) const {
    std::vector<std::tuple<double, int, int>> out;
    const Vec2 r = qu - pu;
    auto test = [&](const Vec2& a, const Vec2& b, const BoundaryIndex::Ref& ref) {
      const Vec2 e = b - a;
      const double den = cross2(r, e);
      if (den == 0.0) return;  // parallel
      const double t = cross2(a - pu, e) / den;
      const double u = cross2(a - pu, r) / den;
      if (t > 0.0 && t < 1.0 && u >= 0.0 && u < 1.0) out.emplace_back(t, ref.loop, ref.index);
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

  // Boundary crossings on the edge between vertices a and b, in order from a to b: the
  // intersections of the edge's (u, v) segment with the free boundary, their count checked
  // against contains() at the ends (bisection when a node sits on the boundary itself).
  // Computed once per edge, in the chart of its lower-numbered vertex, so that both cells
  // sharing it get the same points (an edge with none, most of them, is not stored:
  // recomputing it gives none again).
  std::vector<int> crossings(int a, int b) {
    const bool flip = b < a;
    const std::pair<int, int> key = flip ? std::pair{b, a} : std::pair{a, b};
    auto it = crossings_.find(key);
    if (it == crossings_.end()) {
      const Vertex P = verts_[key.first];
      const Vertex Q = verts_[key.second];
      Vec2 pu = P.at.uv, qu = P.at.uv + s_.delta(P.at, Q.at);
      // From a pole the edge runs along the other end's meridian: the pole takes its free
      // parameter from the other end (an edge to a node beyond a boundary through the pole
      // then crosses at the pole itself).
      if (s_.same_chart(P.at, Q.at)) {
        if (P.pole && !Q.pole) pu[P.free] = qu[P.free];
        if (Q.pole && !P.pole) qu[Q.free] = pu[Q.free];
      }
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
          ts.emplace_back(0.5 * (lo + hi), -1, -1);
        }
      }
      std::vector<int> ids;
      for (const auto& [t, loop, seg] : ts)
        ids.push_back(surface_vertex(s_.locate(P.at, pu + t * (qu - pu)), P.p2 + t * (Q.p2 - P.p2),
                                     loop, seg));
      if (ids.empty()) return ids;
      it = crossings_.emplace(key, std::move(ids)).first;
    }
    std::vector<int> out = it->second;
    if (flip) std::reverse(out.begin(), out.end());
    return out;
  }

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
    Polygon c = clip(poly);
    if (c.size() >= 3) exact_.push_back(std::move(c));
  }

  // The part of a polygon on the surface: its vertices on the surface, the boundary
  // crossings on its edges, and between an exit and the next entry the free boundary itself,
  // carried into ply coordinates by the part's own piecewise-affine interpolation in the
  // chart of its first corner.
  Polygon clip(const Polygon& poly) {
    const std::size_t m = poly.size();
    const SurfaceLocation chart = verts_[poly[0]].at;
    std::vector<Vec2> uvw(m);  // unwrapped relative to the first corner, in its chart
    for (std::size_t k = 0; k < m; ++k) uvw[k] = chart.uv + s_.delta(chart, verts_[poly[k]].at);
    // A pole corner takes the mean free parameter of its two neighbours in the part.
    for (std::size_t k = 0; k < m; ++k) {
      const Vertex& v = verts_[poly[k]];
      if (!v.pole || !s_.same_chart(chart, v.at)) continue;
      const Vec2& a = uvw[(k + m - 1) % m];
      const Vec2& b = uvw[(k + 1) % m];
      uvw[k][v.free] = 0.5 * (a[v.free] + b[v.free]);
    }
    struct Item {
      int v;
      int kind;  // 0 vertex, 1 exit crossing, 2 entry crossing
    };
    std::vector<Item> items;
    for (std::size_t k = 0; k < m; ++k) {
      const int a = poly[k], b = poly[(k + 1) % m];
      bool in = verts_[a].in;
      if (in) items.push_back({a, 0});
      for (int x : crossings(a, b)) {
        items.push_back({x, in ? 1 : 2});
        in = !in;
      }
    }
    if (items.empty()) return {};
    Polygon out;
    const std::size_t n = items.size();
    for (std::size_t k = 0; k < n; ++k) {
      out.push_back(items[k].v);
      if (items[k].kind != 1) continue;
      for (std::size_t q = 1; q < n; ++q) {
        const Item& e = items[(k + q) % n];
        if (e.kind == 2) {
          for (int w : boundary_walk(items[k].v, e.v, poly, uvw)) out.push_back(w);
          break;
        }
        if (e.kind == 1) break;
      }
    }
    return out;
  }

  // The free-boundary segment (loop, index) a crossing lies on: the one it was found on, or
  // (for a crossing found by bisection) the nearest one in its face's parameters.
  std::pair<int, int> segment_of(const Vertex& x) const {
    if (x.bloop >= 0) return {x.bloop, x.bseg};
    std::pair<int, int> best{-1, -1};
    double bd = INFINITY;
    for (std::size_t l = 0; l < boundary_.size(); ++l) {
      const auto& L = boundary_[l].points;
      for (std::size_t k = 0; k < L.size(); ++k) {
        if (boundary_[l].kinds[k] != BoundaryLoop::kEdge || L[k].face != x.at.face) continue;
        const Vec2 a = x.at.uv + s_.delta(x.at, L[k]);
        const Vec2 b = a + s_.delta(L[k], L[(k + 1) % L.size()]);
        const Vec2 ab = b - a;
        const double t = ab.squaredNorm() > 0
                             ? std::clamp((x.at.uv - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                             : 0.0;
        const double d = (a + t * ab - x.at.uv).norm();
        if (d < bd) {
          bd = d;
          best = {static_cast<int>(l), static_cast<int>(k)};
        }
      }
    }
    return best;
  }

  static bool in_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
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

  // Ply coordinates of a (u, v) point of the part: the fan triangles (0, k, k + 1) map
  // affinely between (u, v) and the ply.
  Vec2 to_ply(const Polygon& poly, const std::vector<Vec2>& uvw, const Vec2& uv) const {
    Vec2 best = verts_[poly[0]].p2;
    double best_min = -INFINITY;
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      const Vec2 a = uvw[0], b = uvw[k], c = uvw[k + 1];
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

  // Free-boundary vertices between crossings x (exit) and y (entry) that lie inside the
  // part, as new vertices in ply coordinates; the way round the loop that stays inside. The
  // loop may pass from face to face (a corner of a shell); its vertices are carried into the
  // part's chart.
  std::vector<int> boundary_walk(int x, int y, const Polygon& poly, const std::vector<Vec2>& uvw) {
    if (boundary_.empty()) return {};
    const auto sx = segment_of(verts_[x]), sy = segment_of(verts_[y]);
    if (sx.first < 0 || sx.first != sy.first || sx.second == sy.second) return {};
    const auto& L = boundary_[static_cast<std::size_t>(sx.first)].points;
    const int n = static_cast<int>(L.size());
    const SurfaceLocation chart = verts_[poly[0]].at;
    std::vector<std::pair<Vec2, int>> best;  // (chart uv, loop vertex)
    bool found = false;
    for (int dir : {1, -1}) {
      // Forward: loop vertices sx+1 .. sy; backward: sx .. sy+1; all inside the part.
      std::vector<std::pair<Vec2, int>> walk;
      bool ok = true;
      int k = dir > 0 ? (sx.second + 1) % n : sx.second;
      const int stop = dir > 0 ? (sy.second + 1) % n : sy.second;
      for (int guard = 0; guard <= n && k != stop; ++guard, k = (k + dir + n) % n) {
        if (collapsed_[static_cast<std::size_t>(sx.first)][static_cast<std::size_t>(k)]) continue;
        const Vec2 p = chart.uv + s_.delta(chart, L[static_cast<std::size_t>(k)]);
        if (!in_polygon(uvw, p)) {
          ok = false;
          break;
        }
        walk.push_back({p, k});
      }
      if (k != stop) ok = false;
      if (ok && (!found || walk.size() < best.size())) {
        best = walk;
        found = true;
      }
    }
    std::vector<int> out;
    for (const auto& [p, k] : best)
      out.push_back(surface_vertex(L[static_cast<std::size_t>(k)], to_ply(poly, uvw, p)));
    return out;
  }

  // Boundary of the union of counter-clockwise polygons: edges shared by two polygons (in
  // opposite directions) cancel; the rest chain into loops, outer ones counter-clockwise.
  std::vector<OutlineLoop> assemble(const std::vector<Polygon>& polys) const {
    const double merge = st_.tol.outline_merge_rel * ply_.d();
    std::map<std::pair<int, int>, int> edges;  // ordered: deterministic output
    for (const auto& p : polys) {
      for (std::size_t k = 0; k < p.size(); ++k) {
        const int a = p[k], b = p[(k + 1) % p.size()];
        if (a == b) continue;
        auto rev = edges.find({b, a});
        if (rev != edges.end()) {
          if (--rev->second == 0) edges.erase(rev);
        } else {
          ++edges[{a, b}];
        }
      }
    }
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
  std::vector<std::vector<bool>> collapsed_;  // per loop vertex: on a collapsed edge
  BoundaryIndex index_;
  SolverSettings st_;
  std::vector<Vertex> verts_;
  std::vector<int> drape_vertices_;  // vertex of each drape node (by index), or -1
  std::unordered_map<std::uint64_t, int> node_vertices_;  // vertex of other nodes (by key)
  std::unordered_map<std::uint64_t, Position> virtual_;
  std::map<std::pair<int, int>, std::vector<int>> crossings_;
  std::vector<Polygon> exact_, stair_;
};

}  // namespace

FlatPattern flat_pattern(const DrapeSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions&) {
  if (!result.ply || result.nodes.empty()) return {};
  return Builder(surface, result).run();
}

}  // namespace plyfit
