// A job's ply on its mold: the drape problem from the seed, rosette and ply angle (or the
// start keys turned by the angle), and the ply's frame as the drape laid it.

#include "job/drape_job.hpp"

#include <plyfit/kernel/boundary.hpp>
#include <plyfit/kernel/ply_definition.hpp>

namespace plyfit::cli {

namespace {

// The darts' curves (every curve of each --dart file, open: a CSV block's closing link is not
// part of the cut).
Status read_darts(const DrapeJob& job, DrapeProblem& pb) {
  pb.darts.clear();
  for (const CurveFileSpec& spec : job.darts) {
    auto curves = read_curves(spec);
    if (!curves) {  // a file that does not read: named with the option it was given to
      Error e = curves.error();
      e.input = e.input.empty() || e.input == spec.path ? "--dart " + spec.path : e.input;
      return e;
    }
    for (const BoundaryCurve& c : *curves) pb.darts.push_back(c.points);
  }
  return ok_status();
}

}  // namespace

Result<DrapeProblem> job_problem(const DrapeJob& job, const MoldSurface& surface) {
  if (job.problem_on_mold) {
    DrapeProblem pb = job.problem;
    if (auto st = read_darts(job, pb); !st) return st.error();
    return pb;
  }
  const double angle = job.ply_angle_deg * kDegToRad;
  Result<DrapeProblem> pb = [&]() -> Result<DrapeProblem> {
    if (!job.seed) return turned_problem(surface, job.problem, angle);
    PlyDefinition def;
    def.seed = *job.seed;
    def.rosette = job.rosette;
    def.angle = angle;
    return ply_problem(surface, def, job.problem.ply, job.drape.tol);
  }();
  if (!pb) return pb.error();
  pb->seed_curve = job.problem.seed_curve;
  if (job.seed_curve_file) {
    auto curves = read_curves(*job.seed_curve_file);
    if (!curves) return Error(curves.error()).in("seed-curve");
    if (curves->size() != 1)
      return Error{ErrorCode::kSeedCurveOneCurve,
                   job.seed_curve_file->path,
                   {static_cast<std::int64_t>(curves->size())}};
    // A CSV block is a boundary's closed loop by definition; as a seed curve it is open
    // unless its last point repeats its first.
    const BoundaryCurve& c = curves->front();
    pb->seed_polyline = c.points;
    pb->seed_polyline_closed = is_cad_curve_file(job.seed_curve_file->path)
                                   ? c.closed
                                   : c.points.size() > 2 && c.points.front() == c.points.back();
  }
  if (auto st = read_darts(job, *pb); !st) return st.error();
  return pb;
}

Result<JobBoundary> job_boundary(const DrapeJob& job, const MoldSurface& surface,
                                 exporters::RunInfo* run) {
  if (!job.boundary) return JobBoundary{surface, std::nullopt};
  auto curves = read_curves(*job.boundary);
  if (!curves) return Error(curves.error()).in("boundary");
  PlyBoundary b;
  b.curves = std::move(curves).value();
  b.offset = job.boundary_offset;
  const Vec3 seed = job.seed ? *job.seed : job.problem.start;
  auto bounded = bound_mold(surface, b, seed, job.drape.tol);
  if (!bounded) {
    Error e = bounded.error();
    e.input = job.boundary->path;
    return e;
  }
  if (run) {  // the faces that remain, by their index in the file
    std::vector<int> faces;
    std::vector<FaceInfo> infos;
    for (int k : bounded->faces) {
      const auto i = static_cast<std::size_t>(k);
      faces.push_back(i < run->faces.size() ? run->faces[i] : k);
      if (i < run->faces_info.size()) infos.push_back(run->faces_info[i]);
    }
    run->faces = faces;
    if (!run->faces_info.empty()) run->faces_info = infos;
  }
  exporters::BoundaryReport r;
  r.source = to_string(*job.boundary);
  r.offset = job.boundary_offset;
  r.area = bounded->area;
  for (const auto& loop : bounded->loops) {
    r.loops.push_back(loop.points);
    r.lengths.push_back(loop.length);
  }
  return JobBoundary{bounded->surface, r};
}

Result<exporters::PlyReport> ply_report(const DrapeJob& job, const MoldSurface& surface,
                                        const DrapeResult& result) {
  // The start keys without a rosette define 0 deg themselves: the warp they lay, before
  // --ply-angle turns it. Measured against the drape's own base tangent, then referred to it.
  const bool own_zero = !job.seed && !job.rosette_given;
  auto laid =
      draped_frame(surface, result, own_zero ? result.base_tangent : job.rosette, job.drape.tol);
  if (!laid) return laid.error();
  if (own_zero) {
    laid->angle = job.ply_angle_deg * kDegToRad;
    laid->zero = Eigen::AngleAxisd(-laid->angle, laid->normal) * laid->warp;
  }
  exporters::PlyReport r;
  r.from_seed = job.seed.has_value();
  if (job.seed) r.seed = *job.seed;
  r.rosette = own_zero ? laid->zero : job.rosette;
  r.angle_deg = job.ply_angle_deg;
  r.seed_curve = to_string(result.seed_curve);
  r.point = laid->point;
  r.normal = laid->normal;
  r.zero = laid->zero;
  r.warp = laid->warp;
  r.weft = laid->weft;
  r.laid_angle_deg = laid->angle * kRadToDeg;
  return r;
}

}  // namespace plyfit::cli
