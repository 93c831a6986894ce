// A job's ply on its mold: the drape problem from the seed, rosette and ply angle (or the
// start keys turned by the angle), and the ply's frame as the drape laid it.

#include "job/drape_job.hpp"

#include <plyfit/kernel/ply_definition.hpp>

namespace plyfit::cli {

Result<DrapeProblem> job_problem(const DrapeJob& job, const MoldSurface& surface) {
  if (job.problem_on_mold) return job.problem;
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
  return pb;
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
