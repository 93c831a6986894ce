// Darts in the outline: the ply nodes a dart cuts out are placed through the cloth beside them,
// so that the cells across the V are cloth like any other (clipped at the face's boundary as
// theirs are), and the V between each dart's cut lines is then taken out of the exact outline.
// Beside a dart each side's cloth ends at its cut line: the outline's notch is the V, bounded
// by the two cut lines, and nothing else is lost.

#include "drape/darts.hpp"
#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plyfit::detail {

namespace {

// A node cut out is placed through the nearest mapped node within this many cells of it (a V
// is a few cells wide: its nodes lie within a few cells of each side's cloth).
constexpr int kCarryCells = 4;
// The polygon boolean that takes the V out (Boost.Geometry) moves the points it keeps by
// rounding, about 1e-6 of the region's extent at most: an output point within kNotchSnapRel of
// the extent of an input point is that point (its exact ply and 3D position kept).
constexpr double kNotchSnapRel = 1e-5;

// Points with a payload, found by position within a tolerance (sorted by x).
struct SnapIndex {
  struct Item {
    Vec2 p;
    Vec3 p3;
  };
  std::vector<Item> items;
  void sort() {
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
      return a.p.x() < b.p.x() || (a.p.x() == b.p.x() && a.p.y() < b.p.y());
    });
  }
  // The item nearest p within tol (nullptr: none).
  const Item* near(const Vec2& p, double tol) const {
    auto it = std::lower_bound(items.begin(), items.end(), p.x() - tol,
                               [](const Item& a, double x) { return a.p.x() < x; });
    const Item* best = nullptr;
    double best_d = tol;
    for (; it != items.end() && it->p.x() <= p.x() + tol; ++it)
      if (const double dist = (it->p - p).norm(); dist <= best_d) best = &*it, best_d = dist;
    return best;
  }
};

// The region's extent: the diagonal of its bounding box.
double extent(const Region2& r) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& loop : r)
    for (const Vec2& p : loop) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return lo.allFinite() && hi.allFinite() ? (hi - lo).norm() : 0.0;
}

// A loop of the boolean's output (clockwise outer loops) as an outline loop (counter-clockwise
// outer loops): points of the loops before (`kept`) and of the cut lines (`cut`) as they were,
// the others (where a cut line crosses the outline) carried onto the surface by `place`.
template <class Place>
OutlineLoop notched_loop(const std::vector<Vec2>& pts, const SnapIndex& kept, const SnapIndex& cut,
                         double snap, Place&& place) {
  OutlineLoop l;
  for (auto it = pts.rbegin(); it != pts.rend(); ++it) {
    if (const auto* k = kept.near(*it, snap)) {
      l.points.push_back(k->p);
      l.points3d.push_back(k->p3);
      continue;
    }
    const auto* c = cut.near(*it, snap);
    const Vec2 p = c ? c->p : *it;
    l.points.push_back(p);
    l.points3d.push_back(place(p));
  }
  return l;
}

}  // namespace

// Ply point q2 where the cloth of the nearest mapped node (within kCarryCells cells) puts it:
// that node's cell map in (u, v) (the node and its linked weft and warp neighbours), carried
// on its face, past the face's edge where q2 lies beyond it (then not `in`).
std::optional<OutlineBuilder::Position> OutlineBuilder::cloth_position(const Vec2& q2) const {
  const double dx = ply_.spec().d_weft, dy = ply_.spec().d_warp;
  const auto i0 = static_cast<std::int32_t>(std::floor(q2.x() / dx));
  const auto j0 = static_cast<std::int32_t>(std::floor(q2.y() / dy));
  // A mapped regular node linked to n along a thread, either way (a base-path node splits
  // a link: its ply offset is no thread step).
  auto thread_neighbour = [this](const DrapeNode& n, ThreadDir a, ThreadDir b) {
    for (const ThreadDir dir : {a, b})
      if (const DrapeNode* m = r_.linked(n, dir); m && m->mapped() && !m->id.is_path_only())
        return m;
    return static_cast<const DrapeNode*>(nullptr);
  };
  const DrapeNode* best[3] = {nullptr, nullptr, nullptr};
  double best_d = std::numeric_limits<double>::infinity();
  for (std::int32_t a = -kCarryCells; a <= kCarryCells + 1; ++a)
    for (std::int32_t b = -kCarryCells; b <= kCarryCells + 1; ++b) {
      const DrapeNode* n = r_.find(NodeId::regular(i0 + a, j0 + b));
      if (!n || !n->mapped()) continue;
      const double dist = (n->ply - q2).norm();
      if (dist >= best_d) continue;
      const DrapeNode* x = thread_neighbour(*n, ThreadDir::kPlusX, ThreadDir::kMinusX);
      const DrapeNode* y = thread_neighbour(*n, ThreadDir::kPlusY, ThreadDir::kMinusY);
      if (!x || !y) continue;
      best[0] = n, best[1] = x, best[2] = y, best_d = dist;
    }
  if (!best[0]) return std::nullopt;
  const DrapeNode &n = *best[0], &x = *best[1], &y = *best[2];
  // q2 - n = s (x - n) + t (y - n) in the ply: the threads are straight there (x - n is
  // along the weft, y - n along the warp), so s and t are its coordinates along them.
  const Vec2 ex = x.ply - n.ply, ey = y.ply - n.ply, r = q2 - n.ply;
  const double s = r.x() / ex.x(), t = r.y() / ey.y();
  const SurfaceLocation from = n.at();
  const Vec2 uv = from.uv + s * s_.delta(from, x.at()) + t * s_.delta(from, y.at());
  if (!uv.allFinite()) return std::nullopt;
  const SurfaceLocation at = s_.locate(from, uv);
  const SurfaceEval1 e = s_.eval1(at);
  if (!e.ok || !e.p.allFinite()) return std::nullopt;
  Position p{s_.wrap(at), e.p, s_.contains(at)};
  p.cut_out = true;
  return p;
}

// The ply nodes of the darts' V: those the scan left off_ply (no side of a dart holds them), and
// from them the ply nodes no front reached (a V wider than a cell) as far as the cloth beside
// them puts them on the face.
void OutlineBuilder::place_cut_out_nodes() {
  if (r_.darts.empty()) return;
  std::vector<NodeId> todo;
  for (const DrapeNode& n : r_.nodes)
    if (n.status == NodeStatus::kOffPly && !n.id.is_path_only() && ply_.on_ply(ply_.pos(n.id)))
      todo.push_back(n.id);
  std::reverse(todo.begin(), todo.end());
  while (!todo.empty()) {  // each node is placed once: at most the nodes within reach of cloth
    const NodeId id = todo.back();
    todo.pop_back();
    if (virtual_.count(id.key())) continue;
    const auto p = cloth_position(ply_.pos(id));
    if (!p) continue;
    virtual_[id.key()] = *p;
    if (!p->in) continue;
    for (int d = 0; d < 4; ++d)
      if (const auto nb = ply_.neighbour(id.i, id.j, static_cast<ThreadDir>(d));
          nb && !nb->id.is_path_only() && !r_.find(nb->id) && !virtual_.count(nb->id.key()) &&
          ply_.on_ply(ply_.pos(nb->id)))
        todo.push_back(nb->id);
  }
}

// Each dart's V in `region` (the outline's loops) where its cut lines bound cloth cut out
// (removed_area, the sides overlapping on the part; where they leave a gap on the part, no
// cloth is missing): the left line out to the tip and the right one back, united. Not a
// seam's.
Region2 OutlineBuilder::dart_notches(const Region2& region) const {
  const auto in_region = [&](const Vec2& p) {
    bool in = false;
    for (const auto& loop : region) in = in != inside_polygon(loop, p);
    return in;
  };
  std::vector<Region2> vs;
  for (const DartResult& d : r_.darts) {
    // A seam cuts nothing out: each front keeps its cloth up to the line where they met.
    if (d.seam || !(d.removed_area > d.opening_area) || d.line_left.size() < 2) continue;
    // The lines start where both sides have cloth near the curve, short of the ply's edge
    // that the curve starts from: each is continued that far along its first segment when
    // that leaves the outline (a curve that starts inside the cloth is not continued).
    const auto mouth = [&](const std::vector<Vec2>& line) {
      const Vec2 e = (line[0] - line[1]).normalized();
      return e.allFinite() ? Vec2(line[0] + kDartNearRel * ply_.d() * e) : line[0];
    };
    const Vec2 ml = mouth(d.line_left), mr = mouth(d.line_right);
    const bool open = !in_region(ml) && !in_region(mr);
    std::vector<Vec2> v;
    if (open) v.push_back(ml);
    v.insert(v.end(), d.line_left.begin(), d.line_left.end());
    v.insert(v.end(), d.line_right.rbegin(), d.line_right.rend());
    if (open) v.push_back(mr);
    vs.push_back({std::move(v)});
  }
  return unite_all(vs);
}

// The loops without the darts' V.
void OutlineBuilder::notch_darts(std::vector<OutlineLoop>& loops) const {
  if (r_.darts.empty() || loops.empty()) return;
  Region2 region;
  for (const auto& l : loops) region.push_back(l.points);
  const Region2 notches = dart_notches(region);
  if (notches.empty()) return;
  const std::optional<Region2> notched = subtract_regions(region, notches);
  if (!notched) return;
  SnapIndex kept, cut;
  for (const auto& l : loops)
    for (std::size_t k = 0; k < l.points.size(); ++k)
      kept.items.push_back({l.points[k], l.points3d[k]});
  for (const DartResult& d : r_.darts) {
    for (const Vec2& p : d.line_left) cut.items.push_back({p, Vec3::Zero()});
    for (const Vec2& p : d.line_right) cut.items.push_back({p, Vec3::Zero()});
  }
  kept.sort();
  cut.sort();
  auto place = [this](const Vec2& p) {
    const auto at = cloth_position(p);
    return at ? at->point : Vec3::Zero();
  };
  const double snap = kNotchSnapRel * extent(region);
  std::vector<OutlineLoop> out;
  for (const auto& pts : *notched) {
    OutlineLoop l = notched_loop(pts, kept, cut, snap, place);
    // Where the V's edge runs along the outline's, the boolean's two roundings of it leave
    // loops no wider than the snap: one of less area than the snap times the spacing is such
    // a sliver.
    if (measure_loop(l) && l.area > snap * ply_.d()) out.push_back(std::move(l));
  }
  loops = std::move(out);
}

}  // namespace plyfit::detail
