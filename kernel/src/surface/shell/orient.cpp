// Shell::create's steps along the shared edges: the faces oriented consistently, and the
// crease angle of every edge.
#include "surface/shell/topology.hpp"

#include <cmath>

namespace plyfit {

namespace {

// Points sampled along a shared edge for its crease angle.
constexpr int kEdgeSamples = 17;

}  // namespace

// Orientation: across every shared edge the two faces' outward normals must agree. Faces are
// flipped, face by face from face 0 through its neighbours, until every edge agrees; an
// error where one cannot (a Moebius band).
Status Shell::orient() {
  const std::size_t n = faces_.size();
  std::vector<std::vector<std::pair<std::int32_t, double>>> adj(n);  // (other face, sign)
  for (std::int32_t e = 0; e < edge_count(); ++e) {
    const Edge& E = edges_[static_cast<std::size_t>(e)];
    const double sign = agreement(e);
    adj[static_cast<std::size_t>(E.face[0])].push_back({E.face[1], sign});
    adj[static_cast<std::size_t>(E.face[1])].push_back({E.face[0], sign});
  }
  std::vector<int> state(n, 0);  // 0 unvisited, +1 kept, -1 flipped
  for (std::size_t root = 0; root < n; ++root) {
    if (state[root]) continue;
    state[root] = 1;
    std::vector<std::size_t> stack{root};
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (const auto& [g, sign] : adj[f]) {
        const int want = state[f] * static_cast<int>(sign);
        const auto gi = static_cast<std::size_t>(g);
        if (!state[gi]) {
          state[gi] = want;
          stack.push_back(gi);
        } else if (state[gi] != want) {
          return Error{ErrorCode::kShellOrientation, {}, {std::int64_t{source_[gi]}}};
        }
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    if (state[k] < 0) *faces_[k] = faces_[k]->flipped();
  return ok_status();
}

// +1 when the two faces of shared edge e agree in orientation as they are, -1 when one must
// be flipped. For a consistently oriented pair, (n x inward) . t has opposite signs on the two
// sides (unfold one face onto the other: the inward directions oppose, the normals agree);
// sampled at the middle of the edge.
double Shell::agreement(std::int32_t e) const {
  const Edge& E = edges_[static_cast<std::size_t>(e)];
  const std::size_t mid = E.uv[0].size() / 2;
  const Vec2 x0 = E.uv[0][mid > 0 ? mid - 1 : 0], x1 = E.uv[0][std::min(mid, E.uv[0].size() - 1)];
  const Vec2 xa = 0.5 * (x0 + x1);
  const Face& F0 = *faces_[static_cast<std::size_t>(E.face[0])];
  const Face& F1 = *faces_[static_cast<std::size_t>(E.face[1])];
  const SurfaceEval1 e0 = F0.eval1(xa);
  const Projection p1 = F1.project_from(e0.p, E.uv[1][E.uv[1].size() / 2], false);
  const SurfaceEval1 e1 = F1.eval1(p1.at.uv);
  const Vec3 t = (E.xyz[0].back() - E.xyz[0].front()).normalized();
  const Vec3 n0 = F0.normal(xa).n, n1 = F1.normal(p1.at.uv).n;
  const double s0 = n0.cross(inward_3d(E.face[0], e, xa, e0)).dot(t);
  const double s1 = n1.cross(inward_3d(E.face[1], e, p1.at.uv, e1)).dot(t);
  return (s0 * s1 < 0.0) ? 1.0 : -1.0;
}

// The inward direction (3D, through the derivatives ev at uv) of the segment of shared edge e
// on `face` nearest uv.
Vec3 Shell::inward_3d(std::int32_t face, std::int32_t e, const Vec2& uv,
                      const SurfaceEval1& ev) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(face)];
  double best = INFINITY;
  Vec3 out = Vec3::Zero();
  for (const auto& s : T.segs) {
    if (s.edge != e) continue;
    const Vec2 d = s.b - s.a;
    const double t = detail::nearest_on_segment(uv, s.a, s.b);
    const double dist = (s.a + t * d - uv).norm();
    if (dist < best) {
      best = dist;
      const Vec2 w = s.inward * perp(d);
      out = ev.du * w.x() + ev.dv * w.y();
    }
  }
  return out;
}

// Crease angles: the largest angle between the two faces' normals sampled along each edge.
void Shell::measure_creases() {
  for (Edge& E : edges_) {
    const Face& F0 = *faces_[static_cast<std::size_t>(E.face[0])];
    const Face& F1 = *faces_[static_cast<std::size_t>(E.face[1])];
    const std::size_t m = E.uv[0].size();
    for (int q = 0; q < kEdgeSamples; ++q) {
      const std::size_t i =
          std::min(m - 1, static_cast<std::size_t>(q) * (m - 1) / (kEdgeSamples - 1));
      const Vec2 uv0 = E.uv[0][i];
      const SurfaceNormal a = F0.normal(uv0);
      // Seed on the other side: its polyline point nearest in 3D.
      std::size_t best = 0;
      for (std::size_t j = 1; j < E.xyz[1].size(); ++j)
        if ((E.xyz[1][j] - E.xyz[0][i]).squaredNorm() <
            (E.xyz[1][best] - E.xyz[0][i]).squaredNorm())
          best = j;
      const Projection p1 = F1.project_from(E.xyz[0][i], E.uv[1][best], false);
      if (!p1.ok) continue;
      const SurfaceNormal b = F1.normal(p1.at.uv);
      if (!a.ok || !b.ok || a.degenerate || b.degenerate) continue;
      E.crease = std::max(E.crease, std::atan2(a.n.cross(b.n).norm(), a.n.dot(b.n)));
    }
  }
}

// The crease angle of every shared edge between faces f and g, at its largest.
double Shell::crease_angle(std::int32_t f, std::int32_t g) const {
  double out = 0.0;
  for (const Edge& E : edges_)
    if ((E.face[0] == f && E.face[1] == g) || (E.face[0] == g && E.face[1] == f))
      out = std::max(out, E.crease);
  return out;
}

std::pair<std::int32_t, std::int32_t> Shell::edge_faces(std::int32_t e) const {
  const Edge& E = edges_[static_cast<std::size_t>(e)];
  return {E.face[0], E.face[1]};
}

}  // namespace plyfit
