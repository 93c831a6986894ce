// Automatic darts: where a drape ends in conflict or at the shear limit, darts are proposed
// from the face's edge into each such zone, and the ply is draped again with them, at most
// max_drapes drapes in all (docs/decisions/darts.md).
#include "drape/darts.hpp"
#include "drape/drape.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace plyfit {

namespace {

// Darts proposed in one drape lie at least this many spacings apart (3D): a dart relieves the
// shear of the cloth within a few cells of it.
constexpr double kDartSpacingRel = 3.0;
// At most this many new darts per drape.
constexpr std::size_t kDartsPerDrape = 64;
// A dart's tip lies this many spacings short of the stop it is for, towards the start.
constexpr double kTipInsideRel = 4.0;
// The walk out of a zone steps this many spacings along the surface.
constexpr double kWalkStepRel = 0.5;

// The nodes where the cloth stops for want of a dart: in conflict, at the shear limit, or
// folded onto itself (an overlap by a fold guard: DrapeResult::failures' code).
std::vector<bool> stopped_nodes(const DrapeResult& r) {
  std::vector<bool> out(r.nodes.size(), false);
  for (const auto& [k, why] : r.failures) {
    const NodeStatus s = r.nodes[k].status;
    const std::string_view code = why ? why : "";
    out[k] = s == NodeStatus::kConflict || s == NodeStatus::kShearLimit ||
             (s == NodeStatus::kOverlap &&
              (code == "fold_angle" || code == "flat_cell" || code == "cell_folds"));
  }
  return out;
}

// The mapped regular nodes next to a stopped node (stopped_nodes(): those have no point).
std::vector<std::uint32_t> front_nodes(const DrapeResult& r) {
  const std::vector<bool> stopped = stopped_nodes(r);
  std::vector<std::uint32_t> out;
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    if (!n.mapped() || n.id.is_path_only()) continue;
    for (int d = 0; d < 4; ++d)
      if (n.nb[d] >= 0 && stopped[static_cast<std::size_t>(n.nb[d])]) {
        out.push_back(k);
        break;
      }
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

// The 3D direction of ply direction u at mapped node n, through its linked weft and warp
// neighbours (zero if it has none).
Vec3 direction_at(const DrapeResult& r, const DrapeNode& n, const Vec2& u) {
  Vec3 e[2];
  const ThreadDir dirs[2][2] = {{ThreadDir::kPlusX, ThreadDir::kMinusX},
                                {ThreadDir::kPlusY, ThreadDir::kMinusY}};
  for (int a = 0; a < 2; ++a) {
    const DrapeNode* m = r.linked(n, dirs[a][0]);
    if (!m || !m->mapped()) m = r.linked(n, dirs[a][1]);
    if (!m || !m->mapped()) return Vec3::Zero();
    const double dp = (m->ply - n.ply)[a];
    if (dp == 0.0) return Vec3::Zero();
    e[a] = (m->point - n.point) / dp;
  }
  return e[0] * u.x() + e[1] * u.y();
}

// A dart's points must project back onto the surface (DartSet::create checks them as the
// user's): where the surface's projection finds another face (a thin shell's other side), the
// walk stops.
bool projects_onto(const DrapeSurface& s, const Vec3& p, double on_mold) {
  const Projection back = s.project(p);
  return back.ok && back.distance <= on_mold;
}

// Points of a walk on the surface from p along dir, at most `length` long: each step
// projected, the direction kept along the last step, until the face's edge or a sharp crease
// stops it.
std::vector<Vec3> walk(const DrapeSurface& s, Vec3 p, Vec3 dir, double h, double length,
                       double on_mold) {
  std::vector<Vec3> pts;
  const int steps = static_cast<int>(std::ceil(length / h));
  for (int k = 0; k < steps; ++k) {
    const Projection pr = s.project(p + h * dir.normalized());
    // The face's edge (a step shorter than half its length), or a crease the surface turns
    // away at (the step lands farther than its length from the surface).
    if (!pr.ok || pr.distance > h || !projects_onto(s, pr.point, on_mold)) break;
    const Vec3 step = pr.point - p;
    if (step.norm() < 0.5 * h) break;
    pts.push_back(pr.point);
    dir = step;
    p = pr.point;
  }
  return pts;
}

// The dart for the stop next to mapped node n: along the snapped direction from the start to n,
// from the face's edge (or the surface's size away) to kTipInsideRel spacings short of n
// towards the start (its tip, in cloth sheared less).
std::vector<Vec3> walk_out(const DrapeSurface& s, const DrapeResult& r, const DrapeNode& n,
                           double on_mold) {
  const Vec2 from = n.ply - r.ply->spec().start;
  if (!(from.norm() > 0.0)) return {};
  const Vec3 dir = direction_at(r, n, snapped_direction(from));
  if (!(dir.norm() > 0.0)) return {};
  if (!projects_onto(s, n.point, on_mold)) return {};
  const double h = kWalkStepRel * r.ply->d();
  const double inside = std::min(kTipInsideRel * r.ply->d(), 0.5 * from.norm());
  std::vector<Vec3> pts = walk(s, n.point, dir, h, s.size(), on_mold);
  std::reverse(pts.begin(), pts.end());
  pts.push_back(n.point);
  for (const Vec3& p : walk(s, n.point, -dir, h, inside, on_mold)) pts.push_back(p);
  return pts;
}

double distance_to_curve(const std::vector<Vec3>& c, const Vec3& p) {
  double best = INFINITY;
  for (const Vec3& q : c) best = std::min(best, (q - p).norm());
  return best;
}

// New or lengthened darts for the drape's stops; false when it proposes none. The nodes next
// to a stop are taken nearest the start first; each starts a dart unless a dart passes within
// kDartSpacingRel * d of it: then that dart is walked again from it if the new tip lies nearer
// the start than the dart's (by a spacing at least), so that darts comb the zone a few cells
// apart and reach into the cloth that is sheared less.
bool propose_darts(const DrapeSurface& s, const DrapeResult& r, double on_mold, DrapeProblem& pb) {
  std::vector<std::uint32_t> fronts = front_nodes(r);
  const Vec2 start = r.ply->spec().start;
  auto from_start = [&](std::uint32_t k) { return (r.nodes[k].ply - start).norm(); };
  std::stable_sort(fronts.begin(), fronts.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return from_start(a) < from_start(b); });
  const double d = r.ply->d(), spacing = kDartSpacingRel * d;
  const Vec3& start3 = r.start_point;
  const std::size_t given = pb.darts.size();
  std::vector<bool> walked(pb.darts.size(), false);
  bool changed = false;
  for (std::uint32_t k : fronts) {
    const DrapeNode& tip = r.nodes[k];
    auto near = std::find_if(pb.darts.begin(), pb.darts.end(), [&](const std::vector<Vec3>& c) {
      return distance_to_curve(c, tip.point) <= spacing;
    });
    if (near != pb.darts.end()) {
      const auto i = static_cast<std::size_t>(near - pb.darts.begin());
      // Walked only when its tip (kTipInsideRel spacings in from the node) can lie nearer.
      const double reach = (tip.point - start3).norm() - kTipInsideRel * d;
      if (i >= walked.size() || walked[i] || reach > (near->back() - start3).norm() - d) continue;
      std::vector<Vec3> dart = walk_out(s, r, tip, on_mold);
      if (dart.size() < 2 || (dart.back() - start3).norm() > (near->back() - start3).norm() - d)
        continue;
      *near = std::move(dart);
      walked[i] = changed = true;
      continue;
    }
    if (pb.darts.size() - given >= kDartsPerDrape) continue;
    std::vector<Vec3> dart = walk_out(s, r, tip, on_mold);
    if (dart.size() < 2) continue;
    pb.darts.push_back(std::move(dart));
    changed = true;
  }
  return changed;
}

bool laid(const DrapeResult& r) {
  return r.metrics.nodes.conflict == 0 && r.metrics.nodes.shear_limit == 0;
}

}  // namespace

Result<DrapeResult> drape_auto_darts(const DrapeSurface& s, const DrapeProblem& problem,
                                     const DrapeOptions& opt, int max_drapes) {
  DrapeProblem pb = problem;
  auto r = drape(s, pb, opt);
  if (!r) return r;
  int drapes = 1;
  while (!laid(*r) && drapes < max_drapes &&
         propose_darts(s, *r, opt.tol.boundary_on_mold_rel * s.size(), pb)) {
    auto next = drape(s, pb, opt);
    if (!next) return next;
    r = std::move(next);
    ++drapes;
  }
  r->drapes = static_cast<std::uint32_t>(drapes);
  r->darts_auto = true;
  if (!laid(*r)) {
    r->partial = true;
    r->warnings.push_back({WarningCode::kDartsNotEnough,
                           {static_cast<std::int64_t>(r->metrics.nodes.conflict),
                            static_cast<std::int64_t>(r->metrics.nodes.shear_limit),
                            static_cast<std::int64_t>(drapes)}});
  }
  return r;
}

Result<DrapeResult> drape_auto_darts(const MoldSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options, int max_drapes) {
  return drape_auto_darts(surface.impl(), problem, options, max_drapes);
}

}  // namespace plyfit
