// Seams: the links the scan cut where two fronts of cloth met and disagreed (Scanner's seams,
// typically where the cloth wraps round a closed shell and comes back to itself), as curves
// on the part along the line where they met: darts, with their cut lines
// (docs/decisions/darts.md, "Seams in the scan").
#include "drape/darts.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace plyfit::detail {

namespace {

// Seam links whose midpoints lie within this many spacings (3D) of each other lie on one
// seam (along a thread the midpoints of the cut links lie a spacing apart, along a staircase
// half a cell diagonal; sheared cells a little more).
constexpr double kSeamGapRel = 2.0;
// A seam's curve runs on this many spacings beyond its end links' midpoints, so that it
// crosses the end links as it does the others.
constexpr double kSeamExtendRel = 0.5;

// Where two fronts met across a cut link: its midpoint on the surface, the normal there and
// the direction of the line where they met (across the link).
struct Meeting {
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ(), along = Vec3::Zero();
  Vec2 ply = Vec2::Zero();  // the link's midpoint in the ply
  std::uint64_t link = DartCurve::kNoLink;
};

std::optional<Meeting> meeting_at(const DrapeSurface& s, const DrapeResult& r, std::uint64_t link) {
  const DrapeNode& a = r.nodes[link >> 32];
  const DrapeNode& b = r.nodes[link & 0xffffffffu];
  if (!a.mapped() || !b.mapped()) return std::nullopt;
  const Projection pr = s.project(0.5 * (a.point + b.point));
  const SurfaceNormal normal = pr.ok ? s.normal(pr.at) : SurfaceNormal{};
  if (!pr.ok || !normal.ok) return std::nullopt;
  const Vec3 along = normal.n.cross(b.point - a.point);
  if (!(along.norm() > 0.0)) return std::nullopt;
  return Meeting{pr.point, normal.n, along.normalized(), 0.5 * (a.ply + b.ply), link};
}

// The meetings in chains: from a meeting not yet taken, the nearest untaken one within `gap`
// on the part and in the ply is taken next (meetings of two lines where fronts met that pass
// near each other on the part lie far apart in the ply), one way until none is left, then the
// other way from the first.
std::vector<std::vector<const Meeting*>> chains(const std::vector<Meeting>& m, double gap) {
  const FrozenGrid grid(
      gap, static_cast<std::uint32_t>(m.size()), [](std::uint32_t) { return true; },
      [&](std::uint32_t k) { return m[k].point; });
  std::vector<bool> taken(m.size(), false);
  auto next_to = [&](const Meeting& from) {
    std::int64_t best = -1;
    double best_d = gap;
    grid.around(from.point, [&](std::uint32_t k) {
      const double dist = (m[k].point - from.point).norm();
      if (!taken[k] && dist <= best_d && (m[k].ply - from.ply).norm() <= gap)
        best = k, best_d = dist;
    });
    return best;
  };
  std::vector<std::vector<const Meeting*>> out;
  for (std::uint32_t first = 0; first < m.size(); ++first) {
    if (taken[first]) continue;
    taken[first] = true;
    std::vector<const Meeting*> way[2] = {{&m[first]}, {}};
    for (int w = 0; w < 2; ++w)
      for (std::int64_t k = next_to(m[first]); k >= 0;
           k = next_to(way[w].empty() ? m[first] : *way[w].back())) {
        taken[static_cast<std::size_t>(k)] = true;
        way[w].push_back(&m[static_cast<std::size_t>(k)]);
      }
    std::vector<const Meeting*> chain(way[1].rbegin(), way[1].rend());
    chain.insert(chain.end(), way[0].begin(), way[0].end());
    out.push_back(std::move(chain));
  }
  return out;
}

// The seam along a chain: its meetings joined on the surface (points added between them at
// kDartStepRel * d, projected), walked on kSeamExtendRel * d beyond both ends, along the
// chain (or, for one meeting, along the line where its fronts meet).
DartCurve seam_curve(const DrapeSurface& s, const std::vector<const Meeting*>& chain, double d) {
  const double h = kDartStepRel * d, extend = kSeamExtendRel * d;
  const Meeting& a = *chain.front();
  const Meeting& b = *chain.back();
  // Outward at each end: from the nearest meeting at another point (meetings of nodes with
  // the same mapped neighbours coincide), or along the line where its fronts meet.
  auto outward = [](auto first, auto last, const Vec3& along) -> Vec3 {
    for (auto m = first; m != last; ++m)
      if (((*first)->point - (*m)->point).norm() > 0.0) return (*first)->point - (*m)->point;
    return along;
  };
  const Vec3 out_a = outward(chain.begin(), chain.end(), -a.along);
  const Vec3 out_b = outward(chain.rbegin(), chain.rend(), b.along);
  DartCurve c;
  if (!(out_a.norm() > 0.0) || !(out_b.norm() > 0.0)) return c;
  DartCurve head;
  walk_on_surface(s, a.point, out_a, h, extend, head);
  for (std::size_t k = head.points.size(); k-- > 0;) c.add(head.points[k], head.normals[k]);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    if (k > 0) {
      const Vec3 p = chain[k - 1]->point, q = chain[k]->point;
      const int pieces = static_cast<int>(std::ceil((q - p).norm() / h));
      for (int i = 1; i < pieces; ++i) {
        const Projection pr = s.project(p + (q - p) * (double(i) / pieces));
        const SurfaceNormal n = pr.ok ? s.normal(pr.at) : SurfaceNormal{};
        if (pr.ok && n.ok && pr.distance <= h) c.add(pr.point, n.n);
      }
    }
    c.add(chain[k]->point, chain[k]->normal, chain[k]->link);
  }
  walk_on_surface(s, b.point, out_b, h, extend, c);
  return c;
}

}  // namespace

std::vector<DartCurve> seam_curves(const DrapeSurface& s, const DrapeResult& r,
                                   const std::vector<std::uint64_t>& links) {
  std::vector<Meeting> meetings;
  for (std::uint64_t key : links)
    if (auto m = meeting_at(s, r, key)) meetings.push_back(*m);
  const double d = r.ply->d();
  std::vector<DartCurve> out;
  for (const auto& chain : chains(meetings, kSeamGapRel * d)) {
    DartCurve c = seam_curve(s, chain, d);
    if (c.points.size() >= 2) out.push_back(std::move(c));
  }
  return out;
}

}  // namespace plyfit::detail
