// The drape: validation of the inputs, the 3D initial conditions of §4.2.2 (start projected,
// base plane, sweeps paired with the 2D ones by handedness), then the scan and the metrics.
#include "drape/drape.hpp"

#include "drape/darts.hpp"
#include "drape/metrics.hpp"
#include "drape/scan/scanner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace plyfit {

namespace {

// The base plane must cut the surface at the start: the sine of the angle between the base
// plane and the tangent plane there must exceed this.
constexpr double kMinPlaneCutSin = 1e-3;
// Node-count estimate (expected_nodes): samples per cell width across the face, the grid's
// bounds per direction, a relative margin, boundary-ring nodes per sqrt(nodes), and a floor.
constexpr double kEstimateSamplesPerCell = 0.3;
constexpr int kEstimateGridMin = 8;
constexpr int kEstimateGridMax = 64;
// The margin covers sheared plies: a cell sheared by g covers d^2 cos(g) of the surface, so
// a ply sheared 20 degrees on average holds 6 % more nodes than the area over d^2. Capacity
// reserved and never reached costs address space, not memory (its pages are never touched);
// a reserve too short costs a copy of every node, and for a moment both copies.
constexpr double kEstimateMargin = 1.25;
constexpr double kEstimateRing = 8.0;
constexpr double kEstimateMinNodes = 64.0;
// The mapped cells (flat chords of the surface, inside it) cover at most its area; a little
// more is the trim polylines' chord error. More is cloth lying on cloth: the overlap test
// runs at every mapped node on every face (unless DrapeOptions::overlap_test is off), but it
// stops only a node within kOverlapRel * d of a laid node; cloth that comes back with its
// nodes between the laid ones (all farther than that) overlaps unseen. The coverage shows it.
constexpr double kCoverageSlack = 0.01;

// The area of the surface on the side(s) of the base plane through `start` that `plus` and
// `minus` name, by the midpoint rule on a g x g grid in (u, v) per face.
double swept_area(const DrapeSurface& s, int g, const Vec3& start, const Vec3& base_normal,
                  bool plus, bool minus) {
  double area = 0.0;
  for (std::int32_t f = 0; f < s.face_count(); ++f) {
    const SurfaceLocation chart(Vec2::Zero(), f);
    const ParamDomain& dom = s.domain(chart);
    const double hu = dom.width_u() / g, hv = dom.width_v() / g;
    for (int a = 0; a < g; ++a) {
      for (int b = 0; b < g; ++b) {
        const SurfaceLocation at =
            chart.with_uv(Vec2(dom.u0 + (a + 0.5) * hu, dom.v0 + (b + 0.5) * hv));
        if (!s.contains(at)) continue;
        const SurfaceEval1 e = s.eval1(at);
        if (!e.ok) continue;
        const double side = base_normal.dot(e.p - start);
        if (!((side >= 0 && plus) || (side <= 0 && minus))) continue;
        area += e.du.cross(e.dv).norm() * hu * hv;
      }
    }
  }
  return area;
}

// Number of nodes the scan is expected to reach, to size the node vector once (no
// reallocation copies, no doubled capacity): the face area on the swept side(s) of the base
// plane over the cell area, plus a ring of boundary and path nodes; bounded by the ply
// rectangle and the node cap. Both sides swept, that is the surface's own area; one side, the
// midpoint rule on a grid of about kEstimateSamplesPerCell samples per ply cell across the
// face, from kEstimateGridMin to kEstimateGridMax per direction (a fraction of a percent of a
// large drape's time, a few percent of a small one's).
std::size_t expected_nodes(const DrapeSurface& s, const Ply& ply, const Vec3& start,
                           const Vec3& base_normal, const std::vector<Vec3>& sweeps,
                           std::uint64_t cap) {
  const double dw = ply.spec().d_weft, dp = ply.spec().d_warp;
  const int g = std::clamp(static_cast<int>(kEstimateSamplesPerCell * s.size() / std::min(dw, dp)),
                           kEstimateGridMin, kEstimateGridMax);
  bool plus = false, minus = false;
  for (const Vec3& w : sweeps) (base_normal.dot(w) > 0 ? plus : minus) = true;
  const double area = plus && minus ? s.area() : swept_area(s, g, start, base_normal, plus, minus);
  double n = area / (dw * dp);
  if (ply.spec().rect)
    n = std::min(n, (ply.spec().rect->x() / dw + 2) * (ply.spec().rect->y() / dp + 2));
  n = kEstimateMargin * n + kEstimateRing * std::sqrt(n) + kEstimateMinNodes;
  return static_cast<std::size_t>(std::min(n, static_cast<double>(cap)));
}

// A count as a warning's value.
MessageValue count(std::uint64_t n) {
  return static_cast<std::int64_t>(n);
}

// Warnings of a drape that ran but is not what was asked for: a start far from the surface, no
// cell mapped at all (partial), or a sweep that maps nothing while another does (a note); the
// last two only for a scan that ran to its end (`complete`).
void judge_drape(const DrapeSurface& s, const DrapeProblem& pb, const Tolerances& tol,
                 bool complete, DrapeResult& res) {
  const double far = tol.start_far_rel * s.size();
  if (res.start_moved > far) {
    res.partial = true;
    const Vec3& p = res.start_point;
    res.warnings.push_back({WarningCode::kStartFar,
                            {res.start_moved, tol.start_far_rel, s.size(), p.x(), p.y(), p.z()}});
  }
  if (!complete) return;
  if (!(res.metrics.flat_area > 0.0)) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kNoCellMapped, {}});
    return;
  }
  const Ply& P = *res.ply;
  std::vector<std::uint64_t> per_sweep(pb.sweeps.size(), 0);
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only() || n.has(DrapeNode::kOnPath)) continue;
    const int k = P.sweep_for_side(P.side(n.ply));
    if (k >= 0 && static_cast<std::size_t>(k) < per_sweep.size()) ++per_sweep[k];
  }
  for (std::size_t k = 0; k < per_sweep.size(); ++k)
    if (per_sweep[k] == 0) res.warnings.push_back({WarningCode::kSweepMapsNoNode, {count(k + 1)}});
}

// Length of the surface's free boundary: its loops' segments in 3D, each followed in its
// face's parameters by up to kBoundaryPieces chords (a domain rectangle's side can be a whole
// circle), kBoundaryChords chords per loop at least; collapsed edges, seams and junctions left
// out.
constexpr int kBoundaryPieces = 16;
constexpr std::size_t kBoundaryChords = 256;
double boundary_length(const DrapeSurface& s) {
  double len = 0.0;
  for (const BoundaryLoop& l : s.boundary()) {
    const std::size_t n = std::min(l.points.size(), l.kinds.size());
    const int pieces = static_cast<int>(
        std::clamp<std::size_t>(kBoundaryChords / std::max<std::size_t>(n, 1), 1, kBoundaryPieces));
    for (std::size_t k = 0; k < n; ++k) {
      const SurfaceLocation& a = l.points[k];
      const SurfaceLocation& b = l.points[(k + 1) % l.points.size()];
      if (l.kinds[k] != BoundaryLoop::kEdge || a.face != b.face) continue;
      Vec3 prev = Vec3::Zero();
      for (int i = 0; i <= pieces; ++i) {
        const SurfaceEval1 e = s.eval1(a.with_uv(a.uv + (b.uv - a.uv) * (double(i) / pieces)));
        if (!e.ok) break;
        if (i > 0) len += (e.p - prev).norm();
        prev = e.p;
      }
    }
  }
  return len;
}

// A drape that ends without stopping early may still leave part of the surface uncovered: a
// lock, the fold guards, or sweeps that cannot reach round a concave outline (the paper's
// uncalculated regions, Fig. 3). The mapped cells always miss a band along the boundary, at
// most a cell's diagonal wide (cells that cross it are not counted); more uncovered area than
// that band is worth a warning, with the stops inside the surface that bound the cloth.
void warn_uncovered(const DrapeSurface& s, DrapeResult& res) {
  const DrapeMetrics& m = res.metrics;
  const PlySpec& spec = res.ply->spec();
  const double band = std::hypot(spec.d_weft, spec.d_warp) * boundary_length(s);
  const double uncovered = s.area() * (1.0 - std::min(m.coverage, 1.0));
  if (!(uncovered > band) || spec.rect) return;  // a ply rectangle covers what it covers
  const NodeCounts& c = m.nodes;
  res.warnings.push_back({WarningCode::kUncoveredArea,
                          {m.coverage, count(c.shear_limit), count(c.overlap), count(c.failed),
                           count(c.conflict), count(c.path_end)}});
}

// A warning for each end of the base path (one for a path of one point) where the base
// plane's section turned back or ended within one link (NodeStatus::kPathEnd): where, and the angle
// between the base plane and the tangent plane at the path's last point there.
void warn_path_ends(const DrapeSurface& s, DrapeResult& res) {
  if (res.metrics.nodes.path_end == 0 || res.base_path.empty()) return;
  const DrapeNode& a = res.nodes[res.base_path.front()];
  const DrapeNode& b = res.nodes[res.base_path.back()];
  const DrapeNode* warned = nullptr;  // a path of one point ends both ways there: one warning
  for (const DrapeNode& n : res.nodes) {
    if (n.status != NodeStatus::kPathEnd) continue;
    const DrapeNode& last = (a.ply - n.ply).norm() <= (b.ply - n.ply).norm() ? a : b;
    if (&last == warned) continue;
    warned = &last;
    const SurfaceNormal sn = s.normal(last.at());
    const double sine = std::min(sn.n.cross(res.base_normal).norm(), 1.0);
    res.partial = true;
    res.warnings.push_back(
        {WarningCode::kPathEnds, {last.ply.x(), last.ply.y(), std::asin(sine) * kRadToDeg}});
  }
}

// The inputs drape() checks before it looks at the surface.
Status check_problem(const DrapeProblem& pb, const DrapeOptions& opt) {
  if (pb.sweeps.size() != pb.ply.sweeps.size())
    return Error{ErrorCode::kSweepCountMismatch,
                 "sweep3d",
                 {static_cast<std::int64_t>(pb.ply.sweeps.size()),
                  static_cast<std::int64_t>(pb.sweeps.size())}};
  if (!pb.start.allFinite()) return Error{ErrorCode::kStartNotFinite, "start3d"};
  if (!pb.base_normal.allFinite() || !(pb.base_normal.norm() > 0.0))
    return Error{ErrorCode::kBaseNormalZero, "base-normal"};
  if (!(opt.lock_angle > 0.0) || opt.lock_angle > kPi / 2)
    return Error{ErrorCode::kLockAngleRange, "lock-angle"};
  return ok_status();
}

// The start projected onto the surface (res: start point, location, distance moved, base
// normal) and the base path's 3D direction there, the base plane's section (§4.2.2); n0 the
// normal at the start.
Result<Vec3> place_start(const DrapeSurface& s, const DrapeProblem& pb, DrapeResult& res,
                         Vec3& n0) {
  res.base_normal = pb.base_normal.normalized();
  const Projection pr = s.project(pb.start);
  if (!pr.ok) return Error{ErrorCode::kStartNotProjected, "start3d"};
  res.start_point = pr.point;
  res.start_at = pr.at;
  res.start_moved = pr.distance;
  const SurfaceNormal sn = s.normal(pr.at);
  if (!sn.ok) return Error{ErrorCode::kStartNoNormal, "start3d"};
  n0 = sn.n;
  Vec3 t3 = n0.cross(res.base_normal);
  if (t3.norm() < kMinPlaneCutSin) return Error{ErrorCode::kBaseNormalTangent, "base-normal"};
  t3.normalize();
  return t3;
}

// SeedCurve::kCurve: the curve projected onto the surface, and the base path's direction at
// the start turned onto the curve's (t3 keeps its sense; the base normal is n0 x t3's
// complement, the plane the path starts in).
Result<std::optional<detail::SeedPolyline>> seed_polyline(const DrapeSurface& s,
                                                          const DrapeProblem& pb,
                                                          const Tolerances& tol, const Vec3& n0,
                                                          DrapeResult& res, Vec3& t3) {
  if (pb.seed_curve != SeedCurve::kCurve) return std::optional<detail::SeedPolyline>();
  auto curve = detail::SeedPolyline::create(s, pb, res.start_point, tol);
  if (!curve) return curve.error();
  const Vec3 c = curve->tangent(curve->start_place());
  Vec3 along = c - n0 * n0.dot(c);
  if (along.norm() < kMinPlaneCutSin) return Error{ErrorCode::kBaseNormalTangent, "seed-curve"};
  along = (along.dot(t3) >= 0.0 ? along : Vec3(-along)).normalized();
  t3 = along;
  res.base_normal = t3.cross(n0).normalized();
  return std::optional<detail::SeedPolyline>(std::move(curve).value());
}

// Pairing of 2D and 3D: (base, sweep) has the same handedness about the normal in both. Each
// 3D sweep must point to one side of the path (its part across the path, in the tangent
// plane: the sine of its angle with the plane of the path and the normal); t3 is turned round
// where the first sweep's sides disagree.
Status pair_sweeps(const DrapeProblem& pb, const Ply& P, const Tolerances& tol, const Vec3& n0,
                   Vec3& t3) {
  const Vec3 across = n0.cross(t3);
  std::vector<double> side3;
  for (std::size_t k = 0; k < pb.sweeps.size(); ++k) {
    const Vec3& w = pb.sweeps[k];
    if (!w.allFinite() || !(w.norm() > 0.0))
      return Error{ErrorCode::kSweep3dZero, "sweep3d", {static_cast<std::int64_t>(k + 1)}};
    const double c = across.dot(w) / w.norm();
    if (!(std::abs(c) >= std::sin(tol.sweep_min_angle)))
      return Error{
          ErrorCode::kSweep3dAlongPath,
          "sweep3d",
          {static_cast<std::int64_t>(k + 1), std::asin(std::min(std::abs(c), 1.0)) * kRadToDeg,
           tol.sweep_min_angle * kRadToDeg}};
    side3.push_back(c > 0 ? 1.0 : -1.0);
  }
  std::vector<double> side2;
  for (const Vec2& w : P.spec().sweeps) side2.push_back(cross2(P.base_dir(), w) > 0 ? 1.0 : -1.0);
  if (side3[0] != side2[0]) {
    t3 = -t3;
    for (double& x : side3) x = -x;
  }
  if (side3.size() == 2 && side3[1] != side2[1])
    return Error{ErrorCode::kSweeps3dSameSide, "sweep3d"};
  return ok_status();
}

// Warnings of the scan's stops: cancelled, the node cap, cloth on cloth, failed and
// conflicting nodes.
void warn_scan_stops(const detail::ScannedDrape& sd, const DrapeOptions& opt, DrapeResult& res) {
  if (sd.cancelled) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kCancelled, {}});
  }
  if (sd.truncated) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kNodeCap, {count(opt.max_nodes)}});
  }
  if (res.metrics.coverage > 1.0 + kCoverageSlack) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kClothOnItself, {res.metrics.coverage}});
  }
  if (res.metrics.nodes.failed > 0) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kFailedNodes, {count(res.metrics.nodes.failed)}});
  }
  if (res.metrics.nodes.conflict > 0) {
    res.partial = true;
    res.warnings.push_back({WarningCode::kConflictNodes, {count(res.metrics.nodes.conflict)}});
  }
}

// Warnings of threads that end inside the surface: outside nodes where a thread could not
// follow it, a slit along the base path's line.
void warn_thread_ends(const detail::ScannedDrape& sd, DrapeResult& res) {
  if (sd.thread_end_nodes > 0)
    res.warnings.push_back(
        {WarningCode::kThreadEnds,
         {count(sd.thread_end_nodes), sd.thread_end_first.x(), sd.thread_end_first.y()}});
  if (sd.slit_links > 0) {
    res.partial = true;
    res.warnings.push_back(
        {WarningCode::kPathSlit, {sd.slit_stop.x(), sd.slit_stop.y(), count(sd.slit_links)}});
  }
}

// The darts' cut lines, and the seams the scan cut (after the darts, marked).
void lay_darts_and_seams(const DrapeSurface& s, const detail::ScannedDrape& sd,
                         const Tolerances& tol, DrapeResult& res) {
  const detail::DartSet& darts = *sd.darts;
  if (sd.seam_links.empty()) {
    detail::lay_darts(s, darts, sd.cut_out, tol, res);
    return;
  }
  std::vector<detail::DartCurve> all = darts.curves();
  std::vector<detail::DartCurve> seams = detail::seam_curves(s, res, sd.seam_links);
  all.insert(all.end(), std::make_move_iterator(seams.begin()),
             std::make_move_iterator(seams.end()));
  detail::lay_darts(s, detail::DartSet::of(std::move(all), res.ply->d()), sd.cut_out, tol, res);
  for (std::size_t k = darts.curves().size(); k < res.darts.size(); ++k) res.darts[k].seam = true;
}

// What the scan leaves for the steps after it.
void keep_scan_facts(const detail::Scanner& scanner, detail::ScannedDrape& sd) {
  sd.cut_out = scanner.cut_out();
  sd.seam_links = scanner.seam_links();
  sd.cancelled = scanner.cancelled();
  sd.truncated = scanner.truncated();
  sd.path_off_ply = scanner.path_off_ply();
  sd.thread_end_nodes = scanner.thread_ends().nodes;
  sd.thread_end_first = scanner.thread_ends().first;
  const auto slit = scanner.path_slits();
  sd.slit_links = slit.links;
  sd.slit_stop = slit.stop;
}

}  // namespace

Result<DrapeResult> drape(const DrapeSurface& s, const DrapeProblem& pb, const DrapeOptions& opt) {
  return drape(s, pb, opt, detail::Redrape{});
}

Result<DrapeResult> drape(const DrapeSurface& s, const DrapeProblem& pb, const DrapeOptions& opt,
                          const detail::Redrape& again) {
  auto scanned = detail::scan_drape(s, pb, opt, again);
  if (!scanned) return scanned.error();
  return detail::measure_drape(s, pb, opt, std::move(scanned).value());
}

namespace detail {

Result<ScannedDrape> scan_drape(const DrapeSurface& s, const DrapeProblem& pb,
                                const DrapeOptions& opt, const Redrape& again) {
  const auto t0 = std::chrono::steady_clock::now();
  auto ply = Ply::create(pb.ply, opt.tol);
  if (!ply) return ply.error();
  if (auto ok = check_problem(pb, opt); !ok) return ok.error();
  ScannedDrape sd;
  DrapeResult& res = sd.res;
  res.index = std::make_shared<NodeIndex>();
  Vec3 n0 = Vec3::Zero();  // the normal at the start
  auto t3 = place_start(s, pb, res, n0);
  if (!t3) return t3.error();
  auto curve = seed_polyline(s, pb, opt.tol, n0, res, *t3);
  if (!curve) return curve.error();
  if (auto ok = pair_sweeps(pb, *ply, opt.tol, n0, *t3); !ok) return ok.error();
  res.base_tangent = *t3;
  res.seed_curve = pb.seed_curve;
  auto mply = std::make_shared<Ply>(std::move(ply).value());  // the scan extends the path
  res.ply = mply;
  res.nodes.reserve(
      expected_nodes(s, *mply, res.start_point, res.base_normal, pb.sweeps, opt.max_nodes));
  if (again.darts) {
    sd.darts = again.darts;
  } else {
    auto given = DartSet::create(s, pb.darts, mply->d(), opt.tol);
    if (!given) return given.error();
    sd.darts = std::make_shared<const DartSet>(std::move(given).value());
  }
  {
    Scanner scanner(s, *mply, opt, res);  // sized by the reserve
    if (*curve) scanner.follow(&**curve);
    scanner.cut_along(sd.darts.get());
    scanner.memo(again.last, again.next);
    scanner.seam_where_fronts_meet(again.seams);
    scanner.run(*t3);  // the scan of §6.2 from the base path along t3
    keep_scan_facts(scanner, sd);
  }
  sd.scan_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return sd;
}

DrapeResult measure_drape(const DrapeSurface& s, const DrapeProblem& pb, const DrapeOptions& opt,
                          ScannedDrape sd) {
  const auto t0 = std::chrono::steady_clock::now();
  DrapeResult res = std::move(sd.res);
  compute_metrics(s, opt.tol, res);
  res.metrics.nodes.off_ply += sd.path_off_ply;
  lay_darts_and_seams(s, sd, opt.tol, res);
  warn_scan_stops(sd, opt, res);
  warn_path_ends(s, res);
  warn_thread_ends(sd, res);
  judge_drape(s, pb, opt.tol, !sd.cancelled && !sd.truncated, res);
  if (!res.partial) warn_uncovered(s, res);
  res.drape_ms =
      sd.scan_ms +
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

std::uint64_t count_status(const DrapeResult& r, NodeStatus status) {
  return static_cast<std::uint64_t>(std::count_if(
      r.nodes.begin(), r.nodes.end(), [&](const DrapeNode& n) { return n.status == status; }));
}

}  // namespace detail

void release_drape_scratch() {
  detail::OverlapGrid::release_thread_spare();
}

}  // namespace plyfit
namespace plyfit {

Result<DrapeResult> drape(const MoldSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options) {
  return drape(surface.impl(), problem, options);
}

}  // namespace plyfit
