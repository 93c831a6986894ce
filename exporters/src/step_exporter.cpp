// net.step: the draped threads as 3D B-spline curves in an AP214 STEP file, millimetres,
// written by plyfit's own STEP writer (step_curves.hpp; no OpenCASCADE, so a drape does not load
// it). Each maximal run of consecutive mapped nodes of a thread (DrapeResult::threads()) is one
// curve, and the base path is one curve through its mapped nodes in path order. The curves are
// grouped into named sets, each a product: `weft`, `warp` and `base_path` (net_curve_sets()); a
// set without curves is left out.
//
// Curves are the kernel's: polyline_curve() (degree 1, through the nodes) by default, or
// interpolate_cubic() for ExportOptions::curve_degree 3; a run the cubic interpolation rejects
// (two coincident nodes) is written as a polyline. The header's FILE_NAME time stamp is fixed
// (2000-01-01T00:00:00), its name is "net.step" and its author and organisation are "plyfit",
// so equal inputs give equal bytes.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/step_curves.hpp>
#include <plyfit/kernel/nurbs_curve.hpp>

#include "plugins.hpp"

#include <filesystem>

namespace plyfit::exporters {

namespace {

// The named curve sets of net.step, in file order. Another set (e.g. the ply boundary in 3D,
// polyline_set(..., closed = true)) is one more entry here.
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
        return Error{std::string("cannot build a ") + g.name + " curve: " + curve.error().message};
      set.curves.push_back(curve->data());
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

Status write_step(const ExportContext& ctx, const std::string& path) {
  auto sets = net_curve_sets(ctx);
  if (!sets) return Error{path + ": " + sets.error().message};
  StepFileInfo info;
  info.file_name = "net.step";
  info.description = "plyfit draped thread net";
  return write_step_curves(path, *sets, info);
}

}  // namespace

Exporter make_step_exporter() {
  return {"step",
          {"net.step"},
          "net.step: draped weft, warp and base path as 3D curves (AP214)",
          [](const ExportContext& ctx, const std::string& outdir) {
            return write_step(ctx, (std::filesystem::path(outdir) / "net.step").string());
          }};
}

}  // namespace plyfit::exporters
