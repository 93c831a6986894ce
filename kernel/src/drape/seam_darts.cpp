// Seam darts: where two fronts of cloth meet (conflict nodes, and overlaps on the other's
// cloth), typically where the cloth wraps round a closed shell and comes back to itself, a
// dart along the line where they meet lets each front end at it (docs/decisions/darts.md,
// "Closed shells").
#include "drape/darts.hpp"
#include "drape/scan/scanner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

namespace plyfit::detail {

namespace {

// Nodes where fronts met within this many spacings (3D) of each other lie on one meeting line
// (the nodes of a staircase along a diagonal line lie a cell diagonal apart).
constexpr double kSeamGapRel = 3.0;
// A seam dart runs on this many spacings beyond the meeting line's last nodes: the fronts
// meet a little farther than where they first disagree or overlap.
constexpr double kSeamExtendRel = 3.0;
// At most this many new seam darts per drape.
constexpr std::size_t kSeamDartsPerDrape = 64;

// A node where two fronts of cloth met: in conflict (they disagree), or an overlap that landed
// on the cloth the other front laid (a front that came round onto the other).
bool meets(const DrapeNode& n, const char* why) {
  return n.status == NodeStatus::kConflict ||
         (n.status == NodeStatus::kOverlap && why && std::string_view(why) == kOnLaidCloth);
}

// Where two fronts meet at such a node: the mean of its mapped neighbours (of the two fronts
// at a conflict; of its own front, beside the other's cloth, at an overlap), projected;
// `along` the line where they meet (across the thread between two opposite neighbours), or
// zero where no thread has both.
struct Meeting {
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ(), along = Vec3::Zero();
};

std::optional<Meeting> meeting_at(const DrapeSurface& s, const DrapeResult& r, const DrapeNode& n) {
  const DrapeNode* nb[4];
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (int d = 0; d < 4; ++d) {
    nb[d] = r.neighbour(n, static_cast<ThreadDir>(d));
    if (nb[d] && !nb[d]->mapped()) nb[d] = nullptr;
    if (nb[d]) sum += nb[d]->point, ++count;
  }
  if (count == 0) return std::nullopt;
  const Projection pr = s.project(sum / count);
  const SurfaceNormal normal = pr.ok ? s.normal(pr.at) : SurfaceNormal{};
  if (!pr.ok || !normal.ok) return std::nullopt;
  Meeting m{pr.point, normal.n, Vec3::Zero()};
  Vec3 across = Vec3::Zero();
  for (int a = 0; a < 2; ++a)  // ThreadDir: +x, -x, +y, -y
    if (nb[2 * a] && nb[2 * a + 1] &&
        (nb[2 * a]->point - nb[2 * a + 1]->point).norm() > across.norm())
      across = nb[2 * a]->point - nb[2 * a + 1]->point;
  // An overlap has a point of its own: its front came to it from its mapped neighbours.
  if (!(across.norm() > 0.0) && n.status == NodeStatus::kOverlap) across = n.point - sum / count;
  const Vec3 along = normal.n.cross(across);
  if (along.norm() > 0.0) m.along = along.normalized();
  return m;
}

// The meetings in chains: from a meeting not yet taken, the nearest untaken one within `gap`
// is taken next, one way until none is left, then the other way from the first.
std::vector<std::vector<const Meeting*>> chains(const std::vector<Meeting>& m, double gap) {
  NodeGrid grid;
  grid.cell = gap;
  for (std::uint32_t k = 0; k < m.size(); ++k) grid.add(m[k].point, k);
  std::vector<bool> taken(m.size(), false);
  auto next_to = [&](const Vec3& p) {
    std::int64_t best = -1;
    double best_d = gap;
    grid.around(p, [&](std::uint32_t k) {
      const double dist = (m[k].point - p).norm();
      if (!taken[k] && dist <= best_d) best = k, best_d = dist;
    });
    return best;
  };
  std::vector<std::vector<const Meeting*>> out;
  for (std::uint32_t first = 0; first < m.size(); ++first) {
    if (taken[first]) continue;
    taken[first] = true;
    std::vector<const Meeting*> way[2] = {{&m[first]}, {}};
    for (int w = 0; w < 2; ++w)
      for (std::int64_t k = next_to(m[first].point); k >= 0;
           k = next_to(way[w].empty() ? m[first].point : way[w].back()->point)) {
        taken[static_cast<std::size_t>(k)] = true;
        way[w].push_back(&m[static_cast<std::size_t>(k)]);
      }
    std::vector<const Meeting*> chain(way[1].rbegin(), way[1].rend());
    chain.insert(chain.end(), way[0].begin(), way[0].end());
    out.push_back(std::move(chain));
  }
  return out;
}

// The dart along a chain: its meetings joined on the surface (points added between them at
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
    c.add(chain[k]->point, chain[k]->normal);
  }
  walk_on_surface(s, b.point, out_b, h, extend, c);
  return c;
}

}  // namespace

std::size_t propose_seam_darts(const DrapeSurface& s, const DrapeResult& r,
                               std::vector<DartCurve>& darts) {
  std::vector<Meeting> meetings;
  for (const auto& [k, why] : r.failures)
    if (meets(r.nodes[k], why))
      if (auto m = meeting_at(s, r, r.nodes[k])) meetings.push_back(*m);
  const double d = r.ply->d();
  std::size_t added = 0;
  for (const auto& chain : chains(meetings, kSeamGapRel * d)) {
    if (added == kSeamDartsPerDrape) break;
    DartCurve c = seam_curve(s, chain, d);
    if (c.points.size() < 2) continue;
    darts.push_back(std::move(c));
    ++added;
  }
  return added;
}

}  // namespace plyfit::detail
