// How the faces of a mold surface join: its shared edges and their creases, each face's free
// boundary, the faces reached from one across edges no sharper than a crease angle, and the
// shell of some of a shell's faces.
#include "surface/shell/shell.hpp"

#include <plyfit/kernel/mold.hpp>

#include <algorithm>
#include <deque>

namespace plyfit {

std::vector<SharedEdge> MoldSurface::shared_edges() const {
  std::vector<SharedEdge> out;
  const auto* shell = dynamic_cast<const Shell*>(&impl());
  if (!shell) return out;
  for (std::int32_t e = 0; e < shell->edge_count(); ++e) {
    const auto [a, b] = shell->edge_faces(e);
    out.push_back({a, b, shell->crease_angle(e)});
  }
  return out;
}

FreeBoundary MoldSurface::free_boundary(std::int32_t k) const {
  FreeBoundary out;
  for (const BoundaryLoop& loop : boundary()) {
    const std::size_t n = loop.points.size();
    // Segment i is free on face k: a real edge with both ends on the face.
    auto on_face = [&](std::size_t i) {
      return loop.kinds[i] == BoundaryLoop::kEdge && loop.points[i].face == k &&
             loop.points[(i + 1) % n].face == k;
    };
    int free = 0, starts = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!on_face(i)) continue;
      ++free;
      if (!on_face((i + n - 1) % n)) ++starts;
      out.length += (eval1(loop.points[(i + 1) % n]).p - eval1(loop.points[i]).p).norm();
    }
    out.runs += free > 0 && starts == 0 ? 1 : starts;  // a loop free all round is one run
  }
  return out;
}

std::vector<std::int32_t> connected_faces(const MoldSurface& surface, std::int32_t seed,
                                          double max_crease) {
  const std::vector<SharedEdge> edges = surface.shared_edges();
  std::vector<bool> reached(static_cast<std::size_t>(surface.face_count()), false);
  std::vector<std::int32_t> out;
  std::deque<std::int32_t> queue{seed};
  reached[static_cast<std::size_t>(seed)] = true;
  while (!queue.empty()) {
    const std::int32_t f = queue.front();
    queue.pop_front();
    out.push_back(f);
    for (const SharedEdge& e : edges) {
      if (!(e.crease <= max_crease) || (e.face_a != f && e.face_b != f)) continue;
      const std::int32_t g = e.face_a == f ? e.face_b : e.face_a;
      if (reached[static_cast<std::size_t>(g)]) continue;
      reached[static_cast<std::size_t>(g)] = true;
      queue.push_back(g);
    }
  }
  return out;
}

ShellData sub_shell(const ShellData& data, const std::vector<std::int32_t>& faces) {
  // How many of the kept faces use each edge: an edge stays shared when two do.
  std::vector<int> uses(static_cast<std::size_t>(std::max(data.edge_count, 0)), 0);
  for (std::int32_t f : faces) {
    std::vector<std::int32_t> seen;
    for (const TrimLoop& loop : data.faces[static_cast<std::size_t>(f)].loops)
      for (std::int32_t e : loop.edges)
        if (e != TrimLoop::kFreeEdge && std::find(seen.begin(), seen.end(), e) == seen.end())
          seen.push_back(e);
    for (std::int32_t e : seen) ++uses[static_cast<std::size_t>(e)];
  }
  std::vector<std::int32_t> renumber(uses.size(), TrimLoop::kFreeEdge);
  ShellData out;
  for (std::size_t e = 0; e < uses.size(); ++e)
    if (uses[e] == 2) renumber[e] = out.edge_count++;
  out.tolerance = data.tolerance;
  for (std::int32_t f : faces) {
    const auto k = static_cast<std::size_t>(f);
    FaceData face = data.faces[k];
    for (TrimLoop& loop : face.loops)
      for (std::int32_t& e : loop.edges)
        if (e != TrimLoop::kFreeEdge) e = renumber[static_cast<std::size_t>(e)];
    out.faces.push_back(std::move(face));
    out.source_faces.push_back(data.source_faces.empty() ? f : data.source_faces[k]);
  }
  return out;
}

}  // namespace plyfit
