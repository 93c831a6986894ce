// Where the edges of the cells cross the face's free boundary: in the (u, v) of a chart,
// or near a pole in the edge's tangent plane against the boundary's 3D pieces (poles.cpp).

#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// An edge near a pole whose (u, v) segment's middle lies further than this many spacings
// (along the surface) off its 3D chord is clipped in its tangent plane.
constexpr double kBentEdge = 1e-3;
// A crossing taken from the piece nearest an edge (the chords missed it) is kept this far
// (of the edge) from the edge's ends.
constexpr double kNearestEndMargin = 1e-9;
// Bisection steps for where a thread followed from a node on the face leaves it (2^-30 of
// the link: far below the outline's other errors).
constexpr int kSectionBisections = 30;

}  // namespace

// Where segment pu -> qu of the chart of `chart` crosses the free boundary, sorted by t.
// The boundary of the chart's face is taken as it is; that of another face `other` (the
// far end's, across a shared edge) is carried into the chart through DrapeSurface::delta.
std::vector<OutlineBuilder::Crossing> OutlineBuilder::boundary_crossings(
    const SurfaceLocation& chart, const Vec2& pu, const Vec2& qu,
    const SurfaceLocation& other) const {
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
bool OutlineBuilder::contains_in_chart(const SurfaceLocation& chart, const Vec2& uv) const {
  return s_.contains(s_.locate(chart, uv));
}

// The plane of edge P -> Q (see EdgePlane), or none for an edge of no length or whose
// normals cancel. The two ends' normals are turned to agree first: a corner solved past a
// pole, on the surface extended beyond it, has its parameters' normal turned over (u < 0 on
// a surface of revolution), and the plain sum nearly cancels, so that the plane would stand
// on edge and the chord meet no piece.
std::optional<OutlineBuilder::EdgePlane> OutlineBuilder::edge_plane(const Vertex& P,
                                                                    const Vertex& Q) const {
  EdgePlane E;
  const Vec3 d3 = Q.p3 - P.p3;
  E.len = d3.norm();
  if (!(E.len > 0.0)) return std::nullopt;
  Vec3 n = normal_at(P), nq = normal_at(Q);
  n += n.dot(nq) < 0.0 ? -nq : nq;
  Vec3 e1 = d3 - n * (n.dot(d3) / std::max(n.squaredNorm(), 1e-300));
  if (!(n.norm() > 0.0) || !(e1.norm() > 0.0)) return std::nullopt;
  n.normalize();
  e1.normalize();
  E.n = n;
  E.e1 = e1;
  E.e2 = n.cross(e1);
  E.m = 0.5 * (P.p3 + Q.p3);
  E.p = E.in2(P.p3);
  E.r = E.in2(Q.p3) - E.p;
  const Vec3 margin = Vec3::Constant(E.len);
  E.lo = P.p3.cwiseMin(Q.p3) - margin;
  E.hi = P.p3.cwiseMax(Q.p3) + margin;
  return E;
}

// The boundary pieces that may cross edge P -> Q: near a pole, and across faces those of
// both ends' faces; each once.
std::vector<const OutlineBuilder::Piece*> OutlineBuilder::tangent_candidates(const Vertex& P,
                                                                             const Vertex& Q,
                                                                             const EdgePlane& E) {
  std::vector<const Piece*> cand;
  if (near_pole(P.p3) || near_pole(Q.p3)) cand = polar_pieces(E.lo, E.hi);
  if (!s_.same_chart(P.at, Q.at))
    for (const Piece* pc : face_pieces(P, Q)) cand.push_back(pc);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  return cand;
}

// Where the chord a -> a + e of piece pc (in E's plane) crosses the edge, refined on the
// boundary curve itself (bisection of the piece's span on the side of the edge's line); none
// when the chords do not cross.
std::optional<OutlineBuilder::Crossing> OutlineBuilder::chord_crossing(const EdgePlane& E,
                                                                       const Piece& pc,
                                                                       const Vec2& a,
                                                                       const Vec2& e) const {
  const Vec2 &p = E.p, &r = E.r;
  const double den = cross2(r, e);
  if (den == 0.0) return std::nullopt;
  const double t = cross2(a - p, e) / den;
  const double u = cross2(a - p, r) / den;
  if (!(t > 0.0 && t < 1.0 && u >= 0.0 && u < 1.0)) return std::nullopt;
  auto side = [&](double sv) {
    const SurfaceEval1 ev = s_.eval1(s_.wrap(segment_point(pc.loop, pc.seg, sv)));
    return ev.ok ? cross2(r, E.in2(ev.p) - p) : NAN;
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
  const double tx = ex.ok ? (E.in2(ex.p) - p).dot(r) / r.squaredNorm() : t;
  return Crossing{std::clamp(tx, 0.0, 1.0), pc.loop, pc.seg, sx};
}

// Boundary crossings of the edge P -> Q in its tangent plane (EdgePlane): the chord against
// the boundary's 3D pieces. Used near poles, where the (u, v) chart bends straight lines
// round the pole, and across faces. Their count is made to agree with the ends' sides: a
// crossing too many is the one nearest an end (the chords put it on the wrong side of it);
// one missing is taken at the end of the piece nearest the edge (an end on the boundary).
std::vector<OutlineBuilder::Crossing> OutlineBuilder::tangent_crossings(const Vertex& P,
                                                                        const Vertex& Q) {
  std::vector<Crossing> out;
  const auto plane = edge_plane(P, Q);
  if (!plane) return out;
  const EdgePlane& E = *plane;
  double best_gap = INFINITY;
  Crossing nearest{0.5, -1, -1, 0.0};
  for (const Piece* pp : tangent_candidates(P, Q, E)) {
    const Piece& pc = *pp;
    if ((pc.a.cwiseMax(pc.b) - E.lo).minCoeff() < 0.0 ||
        (E.hi - pc.a.cwiseMin(pc.b)).minCoeff() < 0.0)
      continue;
    if (std::abs(E.n.dot(pc.a - E.m)) > E.len && std::abs(E.n.dot(pc.b - E.m)) > E.len) continue;
    const Vec2 a = E.in2(pc.a), e = E.in2(pc.b) - a;
    if (const auto c = chord_crossing(E, pc, a, e)) {
      out.push_back(*c);
      continue;
    }
    for (double u : {0.0, 1.0}) {
      const Vec2 x = a + u * e;
      const double t = std::clamp((x - E.p).dot(E.r) / E.r.squaredNorm(), 0.0, 1.0);
      const double gap = (E.p + t * E.r - x).norm();
      if (gap < best_gap) {
        best_gap = gap;
        nearest = {std::clamp(t, kNearestEndMargin, 1.0 - kNearestEndMargin), pc.loop, pc.seg,
                   pc.s0 + u * (pc.s1 - pc.s0)};
      }
    }
  }
  std::sort(out.begin(), out.end());
  const bool odd = out.size() % 2 == 1;
  if (odd != (P.in != Q.in)) {
    if (!out.empty()) {
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

// Boundary crossings of the edge P -> Q as (u, v) segment pu -> qu in P's chart: the
// intersections with the free boundary, their count checked against the ends' sides (one
// crossing by bisection on contains() where they disagree: a node on the boundary itself).
std::vector<OutlineBuilder::Crossing> OutlineBuilder::chart_crossings(const Vertex& P,
                                                                      const Vertex& Q,
                                                                      const Vec2& pu,
                                                                      const Vec2& qu) const {
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
  return ts;
}

// Boundary crossings on the edge between vertices a and b, in order from a to b, as
// vertices: in the chart (chart_crossings) or near a pole and across faces in the edge's
// tangent plane. Computed once per edge, in the chart of its lower-numbered vertex, so that
// both cells sharing it get the same points (an edge with none, most of them, is not stored:
// recomputing it gives none again).
std::vector<int> OutlineBuilder::crossings(int a, int b) {
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
        ids.push_back(surface_vertex(segment_point(c.loop, c.seg, c.s), P.p2 + c.t * (Q.p2 - P.p2),
                                     c.loop, c.seg, c.s));
    } else {
      const std::vector<Crossing> cs = chart_crossings(P, Q, pu, qu);
      for (const Crossing& c : cs) {
        const SurfaceLocation at = s_.locate(P.at, pu + c.t * (qu - pu));
        const Vec2 p2 = cs.size() == 1 ? crossing_p2(P, Q, c.t, at) : P.p2 + c.t * (Q.p2 - P.p2);
        const int v = surface_vertex(at, p2, c.loop, c.seg, c.s);
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

// The ply point of the one crossing of edge P -> Q, at t along it and `at` on the surface:
// where the edge's corners are the drape's or solved, t along the edge (their map). Where
// one was placed (virtual_by_extrapolation: no point of the surface, its (u, v) only first
// order), the link from the other corner, on the face, is followed as the drape follows a
// thread (solver 3: the surface's section by the plane of the link and the normal there):
// the crossing lies at the distance where that section leaves the face, bisected; at the
// chord's length to `at` where the section does not leave within the link.
Vec2 OutlineBuilder::crossing_p2(const Vertex& P, const Vertex& Q, double t,
                                 const SurfaceLocation& at) const {
  const Vec2 lin = P.p2 + t * (Q.p2 - P.p2);
  if (P.placed == Q.placed || !(P.in || Q.in)) return lin;
  const Vertex& on = P.in ? P : Q;
  const Vertex& off = P.in ? Q : P;
  const double link = (off.p2 - on.p2).norm();
  if (!(link > 0.0)) return lin;
  auto on_face = [&](double r) {
    const SolveResult res = solve_plane_sphere(s_, {on.p3, on.at, r, off.p3 - on.p3, true}, st_);
    return res.status == SolveStatus::kConverged;
  };
  double f = 1.0;
  if (!on_face(link)) {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < kSectionBisections; ++k) {
      const double mid = 0.5 * (lo + hi);
      (on_face(mid * link) ? lo : hi) = mid;
    }
    f = 0.5 * (lo + hi);
  } else if (const SurfaceEval1 e = s_.eval1(at); e.ok) {
    f = std::min((e.p - on.p3).norm() / link, 1.0);
  }
  return on.p2 + f * (off.p2 - on.p2);
}

// True when the (u, v) segment pu -> qu of edge P -> Q, near a pole, is no straight edge
// on the surface: its middle lies off the 3D chord, along the surface, by more than
// kBentEdge spacings (near a pole a straight (u, v) segment is an arc about it). An edge
// along a meridian (a thread on a boundary through the pole) stays straight and is taken
// in (u, v), exactly.
bool OutlineBuilder::bent(const Vertex& P, const Vertex& Q, const Vec2& pu, const Vec2& qu) const {
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
bool OutlineBuilder::cell_crossed(const int* v) {
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

// True when the cell with mapped drape nodes `node[0..3]` as corners is certainly not crossed:
// cell_crossed()'s quick test on the nodes themselves (no vertex made); false means "make the
// vertices and ask cell_crossed()". A node's vertex is a pole only near a pole, so the test is
// the same.
bool OutlineBuilder::cell_clear(const std::int32_t* node) const {
  const DrapeNode& c0 = r_.nodes[static_cast<std::size_t>(node[0])];
  const SurfaceLocation a0 = c0.at();
  Vec2 lo = a0.uv, hi = a0.uv;
  for (int k = 0; k < 4; ++k) {
    const DrapeNode& x = r_.nodes[static_cast<std::size_t>(node[k])];
    const SurfaceLocation a = x.at();
    if (!s_.same_chart(a0, a) || near_pole(x.point)) return false;
    const Vec2 p = a0.uv + s_.delta(a0, a);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool any = false;
  index_.near(a0.face, lo, hi,
              [&](const Vec2&, const Vec2&, const BoundaryIndex::Ref&) { any = true; });
  return !any;
}

// Sets the boundary segment and parameter of a crossing found by bisection: the nearest
// segment in its face's parameters.
void OutlineBuilder::locate_on_boundary(Vertex& x) const {
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

}  // namespace plyfit::detail
