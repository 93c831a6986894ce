// net.step: the draped threads as 3D B-spline curves in an AP214 STEP file, millimetres,
// written by plyfit's own STEP writer (step_curves.hpp; no OpenCASCADE, so a drape does not load
// it). Each maximal run of consecutive mapped nodes of a thread (DrapeResult::threads()) is one
// curve, and the base path is one curve through its mapped nodes in path order. The curves are
// grouped into named sets, each a product: `weft`, `warp` and `base_path` (net_curve_sets()); a
// set without curves is left out. With a flat pattern, the 3D ply boundary follows (the exact
// outline's loops on the mold, OutlineLoop::points3d, e.g. for laser projection): the outer
// loops as closed polylines in the set `ply_boundary`, each hole as a closed polyline in its
// own set `ply_hole_N` (N = 1, 2, ... in outline order) (boundary_sets()). A pattern split for
// the roll adds its seams on the part as open polylines in the set `splice_seams`.
//
// Curves are the kernel's: polyline_curve() (degree 1, through the nodes) by default, or
// interpolate_cubic() for ExportOptions::curve_degree 3; a run the cubic interpolation rejects
// (two coincident nodes) is written as a polyline. The header's FILE_NAME time stamp is fixed
// (2000-01-01T00:00:00), its name is "net.step" and its author and organisation are "plyfit",
// so equal inputs give equal bytes.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/step_curves.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/splice.hpp>

#include "plugins.hpp"

#include <string>
#include <vector>

namespace plyfit::exporters {

namespace {

// Consecutive outline points closer than this fraction of the loop's length are one point of
// the boundary polyline: a degree-1 curve needs distinct points, and its knots (chord-length
// parameters) must stay apart by more than OpenCASCADE's knot resolution (about 1e-15 of the
// range) to read back. 1e-9 of a 1 m loop is 1 nm, far below any projector's resolution.
constexpr double kBoundaryMergeRel = 1e-9;

// The 3D points of `loop` without (near-)repeats, the first point not repeated at the end.
std::vector<Vec3> boundary_points(const OutlineLoop& loop) {
  double length = 0.0;
  for (size_t k = 0; k < loop.points3d.size(); ++k)
    length += (loop.points3d[(k + 1) % loop.points3d.size()] - loop.points3d[k]).norm();
  const double merge = kBoundaryMergeRel * length;
  std::vector<Vec3> pts;
  for (const Vec3& p : loop.points3d)
    if (pts.empty() || (p - pts.back()).norm() > merge) pts.push_back(p);
  while (pts.size() > 1 && (pts.back() - pts.front()).norm() <= merge) pts.pop_back();
  return pts;
}

// The 3D ply boundary as closed polylines: `ply_boundary` (the outer loops), `ply_hole_N`.
Result<std::vector<StepCurveSet>> boundary_sets(const FlatPattern& flat) {
  std::vector<std::vector<Vec3>> outer;
  std::vector<StepCurveSet> sets;
  int holes = 0;
  for (const OutlineLoop& loop : flat.outline) {
    std::vector<Vec3> pts = boundary_points(loop);
    const std::string name = loop.hole ? "ply_hole_" + std::to_string(++holes) : "ply_boundary";
    if (pts.size() < 3) return Error{ErrorCode::kBoundaryLoopTooSmall, {}, {name}};
    if (!loop.hole) {
      outer.push_back(std::move(pts));
      continue;
    }
    auto set = polyline_set(name, {pts}, true);
    if (!set) return Error{ErrorCode::kCurveSetNotBuilt}.because(set.error());
    sets.push_back(std::move(set).value());
  }
  auto set = polyline_set("ply_boundary", outer, true);
  if (!set) return Error{ErrorCode::kCurveSetNotBuilt}.because(set.error());
  sets.insert(sets.begin(), std::move(set).value());
  return sets;
}

// The named curve sets of net.step, in file order.
Result<std::vector<StepCurveSet>> net_curve_sets(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  struct Group {
    const char* name;
    std::vector<std::vector<std::uint32_t>> runs;
  };
  std::vector<Group> groups = {
      {"weft", r.threads(true)}, {"warp", r.threads(false)}, {"base_path", {}}};
  if (r.base_path.size() >= 2) groups[2].runs.push_back(r.base_path);
  std::vector<StepCurveSet> sets;
  for (const Group& g : groups) {
    StepCurveSet set{g.name, {}};
    for (const auto& run : g.runs) {
      std::vector<Vec3> pts;
      pts.reserve(run.size());
      for (const std::uint32_t k : run) pts.push_back(r.nodes[k].point);
      auto curve = ctx.options.curve_degree == 3 ? interpolate_cubic(pts) : polyline_curve(pts);
      if (!curve) curve = polyline_curve(pts);
      if (!curve)
        return Error{ErrorCode::kThreadCurveNotBuilt, {}, {std::string(g.name)}}.because(
            curve.error());
      set.curves.push_back(curve->data());
    }
    sets.push_back(std::move(set));
  }
  if (ctx.flat) {
    auto boundary = boundary_sets(*ctx.flat);
    if (!boundary) return boundary.error();
    for (auto& set : *boundary) sets.push_back(std::move(set));
  }
  if (ctx.splices) {  // the seams between the pieces, on the part: open polylines
    std::vector<std::vector<Vec3>> seams;
    for (const Seam& seam : ctx.splices->seams)
      for (const auto& line : seam.polylines)
        if (line.size() >= 2) seams.push_back(line);
    auto set = polyline_set("splice_seams", seams, false);
    if (!set) return Error{ErrorCode::kCurveSetNotBuilt}.because(set.error());
    sets.push_back(std::move(set).value());
  }
  if (!ctx.result.darts.empty()) {  // each dart's curve on the mold
    std::vector<std::vector<Vec3>> curves;
    for (const DartResult& d : ctx.result.darts) curves.push_back(d.curve);
    auto set = polyline_set("darts", curves, false);
    if (!set) return Error{ErrorCode::kCurveSetNotBuilt}.because(set.error());
    sets.push_back(std::move(set).value());
  }
  if (ctx.options.ply && ctx.options.ply->boundary) {  // the boundary as given, on the mold
    auto set = polyline_set("boundary_curves", ctx.options.ply->boundary->loops, true);
    if (!set) return Error{ErrorCode::kCurveSetNotBuilt}.because(set.error());
    sets.push_back(std::move(set).value());
  }
  return sets;
}

// The text of net.step.
Result<std::string> net_step(const ExportContext& ctx) {
  auto sets = net_curve_sets(ctx);
  if (!sets) return sets.error();
  StepFileInfo info;
  info.file_name = "net.step";
  info.description = "plyfit draped thread net";
  return step_curves_text(*sets, info);
}

}  // namespace

Exporter make_step_exporter() {
  return file_exporter(
      "step",
      "net.step: draped weft, warp and base path, and the ply boundary, as 3D curves (AP214)",
      {{"net.step", net_step}});
}

}  // namespace plyfit::exporters
