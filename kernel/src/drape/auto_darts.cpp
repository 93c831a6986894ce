// Automatic darts: every drape cuts seams where fronts of cloth meet and disagree (the scan's
// seams: a closed shell's cloth that comes round to itself), and where a drape ends at the
// shear limit darts are proposed from the face's edge into each such zone and the ply is
// draped again with them, at most max_drapes drapes in all (docs/decisions/darts.md).
#include "drape/darts.hpp"
#include "drape/drape.hpp"
#include "drape/scan/solve_memo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string_view>

namespace plyfit {

namespace {

// Darts proposed in one drape lie at least this many spacings apart (3D): a dart relieves the
// shear of the cloth within a few cells of it.
constexpr double kDartSpacingRel = 3.0;
// At most this many new darts per drape.
constexpr std::size_t kDartsPerDrape = 64;
// A dart's tip lies at least this many spacings short of the stop it is for, towards the
// start, and under a lock on until the cloth there is sheared less than the lock by
// kTipShearMargin (radians), at most half-way to the start.
constexpr double kTipInsideRel = 4.0;
constexpr double kTipShearMargin = 10.0 * kDegToRad;
// The walk out of a zone steps this many spacings along the surface.
constexpr double kWalkStepRel = 0.5;

// The nodes where the cloth stops for want of a dart: it reached the shear limit or folded
// onto itself (an overlap by a fold guard: DrapeResult::failures' code). (Fronts that met and
// disagree are parted by the scan's seams.)
std::vector<bool> sheared_stops(const DrapeResult& r) {
  std::vector<bool> out(r.nodes.size(), false);
  for (const auto& [k, why] : r.failures) {
    const NodeStatus s = r.nodes[k].status;
    const std::string_view code = why ? why : "";
    if (s == NodeStatus::kShearLimit ||
        (s == NodeStatus::kOverlap &&
         (code == "fold_angle" || code == "flat_cell" || code == "cell_folds")))
      out[k] = true;
  }
  return out;
}

// The mapped regular nodes next to a stop (sheared_stops(): those have no point).
std::vector<std::uint32_t> front_nodes(const DrapeResult& r) {
  const std::vector<bool> stopped = sheared_stops(r);
  std::vector<std::uint32_t> out;
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    if (!n.mapped() || n.id.is_path_only()) continue;
    bool next_to = false;
    for (int d = 0; d < 4; ++d)
      next_to = next_to || (n.nb[d] >= 0 && stopped[static_cast<std::size_t>(n.nb[d])]);
    if (next_to) out.push_back(k);
  }
  return out;
}

// The unit ply direction from the start to p, turned to the nearest thread or bisector of the
// threads (the 8 directions 45 degrees apart).
Vec2 snapped_direction(const Vec2& from_start) {
  const double step = kPi / 4;
  const double a = std::round(std::atan2(from_start.y(), from_start.x()) / step) * step;
  return Vec2(std::cos(a), std::sin(a));
}

// The 3D directions of the weft and the warp at mapped node n (per unit of ply), through its
// linked neighbours; false where it has none on a thread.
bool threads_at(const DrapeResult& r, const DrapeNode& n, Vec3 e[2]) {
  const ThreadDir dirs[2][2] = {{ThreadDir::kPlusX, ThreadDir::kMinusX},
                                {ThreadDir::kPlusY, ThreadDir::kMinusY}};
  for (int a = 0; a < 2; ++a) {
    const DrapeNode* m = r.linked(n, dirs[a][0]);
    if (!m || !m->mapped()) m = r.linked(n, dirs[a][1]);
    if (!m || !m->mapped()) return false;
    const double dp = (m->ply - n.ply)[a];
    if (dp == 0.0) return false;
    e[a] = (m->point - n.point) / dp;
  }
  return true;
}

// The 3D direction of ply direction u at mapped node n (zero where threads_at finds none).
Vec3 direction_at(const DrapeResult& r, const DrapeNode& n, const Vec2& u) {
  Vec3 e[2];
  return threads_at(r, n, e) ? Vec3(e[0] * u.x() + e[1] * u.y()) : Vec3::Zero();
}

// The mapped nodes by position, and the shear of the cloth near a point: that of the nearest
// mapped node within a spacing (|90 deg - thread angle|; none: -1).
struct ShearMap {
  const DrapeResult& r;
  detail::FrozenGrid grid;
  explicit ShearMap(const DrapeResult& res)
      : r(res),
        grid(
            res.ply->d(), static_cast<std::uint32_t>(res.nodes.size()),
            [&](std::uint32_t k) { return res.nodes[k].mapped(); },
            [&](std::uint32_t k) { return res.nodes[k].point; }) {}
  double at(const Vec3& p) const {
    const DrapeNode* best = nullptr;
    double best_d = grid.cell;
    grid.around(p, [&](std::uint32_t k) {
      const double dist = (r.nodes[k].point - p).norm();
      if (dist < best_d) best_d = dist, best = &r.nodes[k];
    });
    Vec3 e[2];
    if (!best || !threads_at(r, *best, e)) return -1.0;
    return std::abs(0.5 * kPi - std::atan2(e[0].cross(e[1]).norm(), e[0].dot(e[1])));
  }
};

// The dart for the stop next to mapped node n: along the snapped direction from the start to n,
// from the face's edge (or the surface's size away) to its tip short of n towards the start,
// in cloth sheared less: kTipInsideRel spacings at least, and under a lock on until `shear`
// there is kTipShearMargin below the lock, at most half-way to the start. None (no points)
// when the tip would lie farther than `tip_within` from the start (3D): the tip is walked
// first.
detail::DartCurve walk_out(const DrapeSurface& s, const DrapeResult& r, const ShearMap& shear,
                           const DrapeNode& n, double tip_within) {
  const Vec2 from = n.ply - r.ply->spec().start;
  if (!(from.norm() > 0.0)) return {};
  const Vec3 dir = direction_at(r, n, snapped_direction(from));
  const SurfaceNormal at_n = s.normal(n.at());
  if (!(dir.norm() > 0.0) || !at_n.ok) return {};
  const double h = kWalkStepRel * r.ply->d();
  const double least = std::min(kTipInsideRel * r.ply->d(), 0.5 * from.norm());
  const double lock = 0.5 * kPi - r.gamma_min_limit;  // pi/2: no lock
  const bool locked = r.gamma_min_limit > 0.0;
  detail::DartCurve in, out, dart;
  // Under a lock the tip lies where the cloth is sheared less than the lock by the margin.
  auto enough = [&](const Vec3& p) {
    if (in.length < least) return false;
    const double g = shear.at(p);
    return g >= 0.0 && g <= lock - kTipShearMargin;
  };
  if (locked)
    detail::walk_on_surface(s, n.point, -dir, h, 0.5 * from.norm(), in, enough);
  else
    detail::walk_on_surface(s, n.point, -dir, h, least, in);
  const Vec3 tip = in.points.empty() ? n.point : in.points.back();
  if ((tip - r.start_point).norm() > tip_within) return {};
  detail::walk_on_surface(s, n.point, dir, h, s.size(), out);
  for (std::size_t k = out.points.size(); k-- > 0;) dart.add(out.points[k], out.normals[k]);
  dart.add(n.point, at_n.n);
  for (std::size_t k = 0; k < in.points.size(); ++k) dart.add(in.points[k], in.normals[k]);
  return dart;
}

double distance_to_curve(const std::vector<Vec3>& c, const Vec3& p) {
  double best = INFINITY;
  for (const Vec3& q : c) best = std::min(best, (q - p).norm());
  return best;
}

// The darts' points by position in cubes of side `within`: the first dart (in order) with a
// point within `within` of p has a point in the 27 cubes about p. A dart walked again adds its
// new points; its old ones stay listed and are measured against its curve as it is now.
class DartsNear {
 public:
  DartsNear(const std::vector<detail::DartCurve>& darts, double within)
      : darts_(darts), within_(within) {
    grid_.cell = within;
    for (std::uint32_t k = 0; k < darts.size(); ++k) add(k);
  }
  void add(std::uint32_t k) {
    for (const Vec3& p : darts_[k].points) grid_.add(p, k);
  }
  /// The first dart with a point within `within` of p (-1: none).
  std::int64_t first(const Vec3& p) const {
    std::vector<std::uint32_t> ks;
    grid_.around(p, [&](std::uint32_t k) { ks.push_back(k); });
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    for (std::uint32_t k : ks)
      if (distance_to_curve(darts_[k].points, p) <= within_) return k;
    return -1;
  }

 private:
  const std::vector<detail::DartCurve>& darts_;
  double within_;
  detail::NodeGrid grid_;
};

// New or lengthened darts for the drape's stops; false when it proposes none. The nodes next
// to a stop are taken nearest the start first; each starts a dart unless a dart passes within
// kDartSpacingRel * d of it: then that dart is walked again from it if the new tip lies nearer
// the start than the dart's (by a spacing at least), so that darts comb the zone a few cells
// apart and reach into the cloth that is sheared less (each dart once per proposal).
bool propose_darts(const DrapeSurface& s, const DrapeResult& r,
                   std::vector<detail::DartCurve>& darts) {
  std::vector<std::uint32_t> fronts = front_nodes(r);
  const ShearMap shear(r);
  const Vec2 start = r.ply->spec().start;
  auto from_start = [&](std::uint32_t k) { return (r.nodes[k].ply - start).norm(); };
  std::stable_sort(fronts.begin(), fronts.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return from_start(a) < from_start(b); });
  const double d = r.ply->d(), spacing = kDartSpacingRel * d;
  const Vec3& start3 = r.start_point;
  const std::size_t given = darts.size();
  std::vector<bool> walked(darts.size(), false);
  DartsNear near_darts(darts, spacing);
  bool changed = false;
  for (std::uint32_t f : fronts) {
    const DrapeNode& tip = r.nodes[f];
    if (const std::int64_t near = near_darts.first(tip.point); near >= 0) {
      const auto i = static_cast<std::size_t>(near);
      const double tip_now = (darts[i].points.back() - start3).norm();
      // Walked only when its tip (kTipInsideRel spacings in from the node) can lie nearer.
      const double reach = (tip.point - start3).norm() - kTipInsideRel * d;
      if (i >= walked.size() || walked[i] || reach > tip_now - d) continue;
      detail::DartCurve dart = walk_out(s, r, shear, tip, tip_now - d);
      if (dart.points.size() < 2) continue;
      darts[i] = std::move(dart);
      near_darts.add(static_cast<std::uint32_t>(i));
      walked[i] = changed = true;
      continue;
    }
    if (darts.size() - given >= kDartsPerDrape) continue;
    detail::DartCurve dart = walk_out(s, r, shear, tip, INFINITY);
    if (dart.points.size() < 2) continue;
    darts.push_back(std::move(dart));
    near_darts.add(static_cast<std::uint32_t>(darts.size() - 1));
    changed = true;
  }
  return changed;
}

// No conflict and no shear-limit node (counted: the drapes made again are measured only when
// kept).
bool laid(const DrapeResult& r) {
  return detail::count_status(r, NodeStatus::kConflict) == 0 &&
         detail::count_status(r, NodeStatus::kShearLimit) == 0;
}

}  // namespace

Result<DrapeResult> drape_auto_darts(const DrapeSurface& s, const DrapeProblem& problem,
                                     const DrapeOptions& opt, int max_drapes) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::SolveMemo memo[2];  // the last drape's solves, and the next one's
  auto first =
      detail::scan_drape(s, problem, opt, detail::Redrape{nullptr, nullptr, &memo[0], true});
  if (!first) return first.error();
  detail::ScannedDrape cur = std::move(first).value();
  // The given darts as the first drape took them, then the walked ones: each dart is put on
  // the surface once.
  std::vector<detail::DartCurve> darts = cur.darts->curves();
  int drapes = 1;
  std::uint64_t reused = 0;
  while (!laid(cur.res) && drapes < max_drapes && propose_darts(s, cur.res, darts)) {
    auto set =
        std::make_shared<const detail::DartSet>(detail::DartSet::of(darts, cur.res.ply->d()));
    detail::SolveMemo& last = memo[(drapes - 1) % 2];
    detail::SolveMemo& next = memo[drapes % 2];
    next = detail::SolveMemo{};
    auto again = detail::scan_drape(s, problem, opt, detail::Redrape{set, &last, &next, true});
    if (!again) return again.error();
    cur = std::move(again).value();
    reused = next.reused;
    ++drapes;
  }
  DrapeResult r = detail::measure_drape(s, problem, opt, std::move(cur));
  // Every drape made and the proposals between them (measure_drape timed the last one only).
  r.drape_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.solves_reused = reused;
  r.drapes = static_cast<std::uint32_t>(drapes);
  r.darts_auto = true;
  if (!laid(r)) {
    r.partial = true;
    r.warnings.push_back({WarningCode::kDartsNotEnough,
                          {static_cast<std::int64_t>(r.metrics.nodes.conflict),
                           static_cast<std::int64_t>(r.metrics.nodes.shear_limit),
                           static_cast<std::int64_t>(drapes)}});
  }
  return r;
}

Result<DrapeResult> drape_auto_darts(const MoldSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options, int max_drapes) {
  return drape_auto_darts(surface.impl(), problem, options, max_drapes);
}

}  // namespace plyfit
