// Moving on a shell: the in/out test with the sewing gap, paths in a face's parameters that
// cross shared edges onto the neighbouring faces, settling points past an edge or a pole,
// differences between faces and projection.
#include "surface/shell/topology.hpp"

#include <cmath>

namespace plyfit {

namespace {

// A path that leaves its face's domain through a pole shared by several faces goes on on the
// face that holds its 3D point (the face extended past the pole) within this fraction of the
// step's 3D length (the extension of a surface of revolution past its pole is the surface).
constexpr double kPoleReachRel = 1e-3;
// A path in a face's parameters crosses at most this many shared edges in one locate().
constexpr int kMaxEdgeCrossings = 8;

}  // namespace

bool Shell::contains(const SurfaceLocation& at) const {
  const Face& F = *faces_[static_cast<std::size_t>(at.face)];
  if (F.contains(at.uv)) return true;
  return near_shared_edge(at.face, F.wrap(at.uv), nullptr);
}

// True when uv (outside its face's polylines) lies within the gap of a shared segment of
// the face (3D distance, measured with the face's parametric speeds); the segment in *segment.
bool Shell::near_shared_edge(std::int32_t face, const Vec2& uv, int* segment) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(face)];
  if (!T.shared) return false;
  const Vec2 sp = faces_[static_cast<std::size_t>(face)]->speeds();
  const Vec2 h = detail::param_reach(T.near, sp);
  double best = INFINITY;
  int found = -1;
  T.index.for_candidates(uv - h, uv + h, [&](int k) {
    const int si = T.index.seg(k).id;
    const auto& s = T.segs[static_cast<std::size_t>(si)];
    if (s.edge < 0) return;
    const double t = detail::nearest_on_segment(uv, s.a, s.b);
    const double dist = (s.a + t * (s.b - s.a) - uv).cwiseProduct(sp).norm();
    if (dist <= T.near && dist < best) {
      best = dist;
      found = si;
    }
  });
  if (segment) *segment = found;
  return found >= 0;
}

SurfaceLocation Shell::settle(const SurfaceLocation& at, const Vec3& p, double reach) const {
  if (contains(at)) return at;
  // Past a pole of at's own face: the face itself holds p there.
  const SurfaceLocation own = faces_[static_cast<std::size_t>(at.face)]->settle(at, p, reach);
  if (own != at && contains(own)) return own;
  // The neighbour that holds p nearest: a projection from each of its seeds.
  SurfaceLocation best = at;
  double best_d = reach;
  for (const Neighbour& nb : neighbours_[static_cast<std::size_t>(at.face)]) {
    const Face& G = *faces_[static_cast<std::size_t>(nb.face)];
    // The seed nearest p in 3D first.
    const Vec2* seed = &nb.seeds.front();
    double sd = INFINITY;
    for (const Vec2& q : nb.seeds) {
      const SurfaceEval1 e = G.eval1(q);
      if (e.ok && (e.p - p).norm() < sd) {
        sd = (e.p - p).norm();
        seed = &q;
      }
    }
    const Projection pr = G.project_from(p, *seed, false);
    const SurfaceLocation g(pr.at.uv, nb.face);
    if (pr.ok && pr.distance <= best_d && contains(g)) {
      best = g;
      best_d = pr.distance;
    }
  }
  return best;
}

SurfaceLocation Shell::locate(const SurfaceLocation& from, const Vec2& uv) const {
  return locate_from(from, uv, TrimLoop::kFreeEdge, 0);
}

SurfaceLocation Shell::locate_from(const SurfaceLocation& from, const Vec2& uv, std::int32_t except,
                                   int depth) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(from.face)];
  if (!T.shared || depth >= kMaxEdgeCrossings) return {uv, from.face};
  const Face& F = *faces_[static_cast<std::size_t>(from.face)];
  if (F.contains(uv)) return {uv, from.face};
  // The path from -> uv ends off the face. It goes on to a neighbour where it first crosses a
  // shared edge outwards.
  const Vec2 p = F.wrap(from.uv);
  const Vec2 q = p + F.delta(from.uv, uv);
  double t = INFINITY;
  int seg = first_crossing(from.face, p, q, except, t);
  if (seg < 0) {
    // No shared edge crossed: `from` may lie past one already, within the sewing gap (then
    // cross it here, if the path goes on outwards); a path that leaves the face's domain
    // through a pole several faces share goes on where its 3D point lies; else the path
    // stays on this face.
    if (near_shared_edge(from.face, p, &seg) && outward(from.face, seg, q - p)) {
      t = 0.0;
    } else {
      if (T.pole && !F.domain().contains(q.x(), q.y())) {
        const SurfaceEval1 eq = F.eval1(q), ep = F.eval1(p);
        if (eq.ok && ep.ok) {
          const double reach = T.near + kPoleReachRel * (eq.p - ep.p).norm();
          const SurfaceLocation g = settle(SurfaceLocation(q, from.face), eq.p, reach);
          if (g.face != from.face) return g;
        }
      }
      return {uv, from.face};
    }
  }
  const auto& s = T.segs[static_cast<std::size_t>(seg)];
  if (s.edge < 0 || s.edge == except) return {uv, from.face};
  const Vec2 x = p + t * (q - p);
  Vec2 rest;
  const SurfaceLocation g = cross_edge(from.face, seg, x, q - x, &rest);
  if (g.face < 0) return {uv, from.face};
  return locate_from(g, g.uv + rest, s.edge, depth + 1);
}

// True when a step r in face's (u, v) leaves the face across its segment si.
bool Shell::outward(std::int32_t face, int si, const Vec2& r) const {
  const auto& sg = topo_->faces[static_cast<std::size_t>(face)].segs[static_cast<std::size_t>(si)];
  return r.dot(sg.inward * perp(sg.b - sg.a)) < 0.0;
}

// The first shared segment (other than edge `except`) the path p -> q in face's (u, v) crosses
// outwards, and the path's parameter there in t; -1 if none. Free edges are passed over:
// where a free and a shared edge meet, rounding may let a path that leaves across the shared
// edge graze the free one first. A shared segment's ends are widened by the near distance:
// at such a corner rounding may pass the path a hair beyond the segment's end.
int Shell::first_crossing(std::int32_t face, const Vec2& p, const Vec2& q, std::int32_t except,
                          double& t) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(face)];
  const Vec2 sp = faces_[static_cast<std::size_t>(face)]->speeds();
  const Vec2 pad = detail::param_reach(T.near, sp);
  int seg = -1;
  const Vec2 r = q - p;
  T.index.for_candidates(p.cwiseMin(q) - pad, p.cwiseMax(q) + pad, [&](int k) {
    const int si = T.index.seg(k).id;
    const auto& sg = T.segs[static_cast<std::size_t>(si)];
    if (sg.edge < 0 || sg.edge == except || !outward(face, si, r)) return;
    const Vec2 e = sg.b - sg.a;
    const double den = cross2(r, e);
    if (den == 0.0) return;
    const double tc = cross2(sg.a - p, e) / den;
    const double sc = cross2(sg.a - p, r) / den;
    const double slack = T.near / std::max(e.cwiseProduct(sp).norm(), detail::kDivisionFloor);
    if (tc > 0.0 && tc <= 1.0 && sc >= -slack && sc <= 1.0 + slack && tc < t) {
      t = tc;
      seg = si;
    }
  });
  return seg;
}

// The location across shared segment `segment` of face `face` at its point x (face's (u, v)),
// and the step `rest` (face's (u, v)) unfolded about the edge into the neighbour's (u, v).
// face = -1 if the neighbour cannot be evaluated.
SurfaceLocation Shell::cross_edge(std::int32_t face, int segment, const Vec2& x, const Vec2& rest,
                                  Vec2* rest_out) const {
  const auto& s =
      topo_->faces[static_cast<std::size_t>(face)].segs[static_cast<std::size_t>(segment)];
  const Edge& E = edges_[static_cast<std::size_t>(s.edge)];
  const int other = E.face[0] == face ? 1 : 0;
  const std::int32_t g = E.face[other];
  const SurfaceEval1 ef = faces_[static_cast<std::size_t>(face)]->eval1(x);
  if (!ef.ok) return {x, -1};
  // The neighbour's side: nearest point of its polyline of the edge, then its surface.
  const auto& xyz = E.xyz[other];
  const auto& uvs = E.uv[other];
  double best = INFINITY, bt = 0.0;
  std::size_t bi = 0;
  for (std::size_t i = 0; i + 1 < xyz.size(); ++i) {
    double tt;
    const double dd = detail::segment_distance(ef.p, xyz[i], xyz[i + 1], tt);
    if (dd < best) {
      best = dd;
      bi = i;
      bt = tt;
    }
  }
  const Face& G = *faces_[static_cast<std::size_t>(g)];
  const Vec2 seed = uvs[bi] + bt * (uvs[bi + 1] - uvs[bi]);
  const Projection pg = G.project_from(ef.p, seed, false);
  const Vec2 ug = pg.ok ? pg.at.uv : seed;
  const SurfaceEval1 eg = G.eval1(ug);
  if (!eg.ok) return {x, -1};
  const Vec3 vg = unfold(s.b - s.a, s.inward, ef, g, E.seg[other][bi], eg, rest);
  *rest_out = detail::metric_solve(eg, vg);
  return {ug, g};
}

// The step `rest` (through ef, face's (u, v)) unfolded about an edge of direction df (inward
// side `inward`) into neighbour g (its segment gs at the crossing, derivatives eg), in 3D:
// along the edge it is kept; across it, the direction out of this face becomes the direction
// into the neighbour.
Vec3 Shell::unfold(const Vec2& df, double inward, const SurfaceEval1& ef, std::int32_t g, int gs,
                   const SurfaceEval1& eg, const Vec2& rest) const {
  Vec3 t = ef.du * df.x() + ef.dv * df.y();
  const Vec2 wout = -inward * perp(df);
  Vec3 aout = ef.du * wout.x() + ef.dv * wout.y();
  const Vec3 v = ef.du * rest.x() + ef.dv * rest.y();
  if (gs < 0 || !(t.norm() > 0.0)) return v;
  const auto& sg = topo_->faces[static_cast<std::size_t>(g)].segs[static_cast<std::size_t>(gs)];
  const Vec2 dg = sg.b - sg.a;
  Vec3 tg = eg.du * dg.x() + eg.dv * dg.y();
  const Vec2 win = sg.inward * perp(dg);
  Vec3 ain = eg.du * win.x() + eg.dv * win.y();
  t.normalize();
  if (tg.norm() > 0.0) {
    tg.normalize();
    if (tg.dot(t) < 0.0) tg = -tg;
  } else {
    tg = t;
  }
  aout -= aout.dot(t) * t;
  ain -= ain.dot(tg) * tg;
  if (!(aout.norm() > 0.0 && ain.norm() > 0.0)) return v;
  aout.normalize();
  ain.normalize();
  return v.dot(t) * tg + v.dot(aout) * ain;
}

Vec2 Shell::delta_between_faces(const SurfaceLocation& from, const SurfaceLocation& to) const {
  const Face& F = *faces_[static_cast<std::size_t>(from.face)];
  // Between two faces: the 3D difference through the tangent plane at `from`.
  const SurfaceEval1 ef = F.eval1(from.uv);
  const SurfaceEval1 et = eval1(to);
  if (!ef.ok || !et.ok) return Vec2::Zero();
  return detail::metric_solve(ef, et.p - ef.p);
}

Projection Shell::project(const Vec3& p) const {
  // Faces in order of their boxes' distance from p; a face whose box is farther than the
  // best distance found cannot hold a nearer point.
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < faces_.size(); ++k) {
    const BBox3& b = faces_[k]->bbox();
    const Vec3 c = p.cwiseMax(b.min).cwiseMin(b.max);
    order.push_back({(c - p).norm(), k});
  }
  std::sort(order.begin(), order.end());
  Projection best;
  for (const auto& [bound, k] : order) {
    if (best.ok && bound > best.distance) break;
    Projection q = faces_[k]->project(p);
    if (q.ok && (!best.ok || q.distance < best.distance)) {
      q.at.face = static_cast<std::int32_t>(k);
      best = q;
    }
  }
  return best;
}

}  // namespace plyfit
