// run_job: a job end to end (import, drape, flat pattern, outputs) and what it reports.

#include "job/drape_job.hpp"

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <iostream>

namespace plyfit::cli {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// What the report says of the job's inputs (the mold's part comes with the import).
exporters::RunInfo run_info(const DrapeJob& job) {
  exporters::RunInfo run;
  run.mold = job.mold;
  run.flip_normal = job.flip_normal;
  run.tolerance_rel = job.tolerance_rel;
  run.max_iterations = job.max_iterations;
  run.lock_angle_deg = job.lock_angle_deg;
  run.warn_angle_deg = job.warn_angle_deg;
  run.guess = to_string(job.drape.guess);
  run.max_nodes = job.drape.max_nodes;
  run.ply_name = job.ply_name;
  run.material = job.material;
  if (job.seed_curve_file) run.seed_curve_file = to_string(*job.seed_curve_file);
  for (const auto& dart : job.darts) run.dart_files.push_back(to_string(dart));
  run.outputs = job.outputs;
  return run;
}

// The drape, with the node count on stderr while it runs when that is a terminal.
Result<DrapeResult> drape_with_progress(const MoldSurface& surface, const DrapeJob& job,
                                        const DrapeProblem& problem,
                                        const std::atomic<bool>* cancel, bool progress) {
  DrapeOptions opt = job.drape;
  opt.cancel = cancel;
  const bool tty = progress && ::isatty(2);
  if (tty) {
    opt.progress = [](std::uint64_t n) {
      std::cerr << "\rplyfit: " << n << " nodes solved" << std::flush;
    };
  }
  auto res =
      job.darts_auto ? drape_auto_darts(surface, problem, opt) : drape(surface, problem, opt);
  if (tty) std::cerr << "\r\033[K" << std::flush;
  return res;
}

JobOutcome outcome_of(const DrapeJob& job, const MoldSurface& surface, const DrapeResult& res,
                      const FlatPattern& flat) {
  JobOutcome out;
  out.status = res.partial ? "partial" : "ok";
  out.mapped = res.metrics.nodes.mapped;
  const auto& m = res.metrics;
  out.shear_max_deg = m.shear_max / kDegToRad;
  out.metrics = m;
  out.face_area = surface.area();
  out.flat_outline_area = flat.cut_area;
  out.outline_coverage = out.face_area > 0 ? outline_surface_area(res, flat) / out.face_area : 0.0;
  out.warnings = res.warnings;
  for (const auto& k : job.outputs)
    if (const auto* e = exporters::find_exporter(k))
      for (const auto& f : e->files) out.files.push_back(f);
  return out;
}

// The pieces of the flat pattern on the job's roll (none without a roll width), their seams
// kept from the other plies' seams the job is given, a warning when they could not be.
Result<std::shared_ptr<const SplicePlan>> splice_job(const DrapeJob& job, DrapeResult& res,
                                                     const FlatPattern& flat) {
  if (!job.roll_width) return std::shared_ptr<const SplicePlan>();
  SpliceOptions so;
  so.roll_width = *job.roll_width;
  so.overlap = job.splice_overlap;
  so.ply_name = job.ply_name;
  if (job.stagger) {
    SpliceStagger st = job.stagger();
    so.avoid = std::move(st.seams);
    so.stagger = st.distance;
  }
  auto plan = splice_pattern(flat, res, so);
  if (!plan) return plan.error();
  if (!plan->stagger_met) {
    double nearest = INFINITY;
    for (const Seam& s : plan->seams) nearest = std::min(nearest, s.stagger_distance);
    res.warnings.push_back({WarningCode::kSpliceStaggerUnmet, {so.stagger, nearest}});
  }
  return std::make_shared<const SplicePlan>(std::move(plan).value());
}

}  // namespace

Result<LoadedSurface> load_job_surface(const DrapeJob& job) {
  const auto t0 = Clock::now();
  LoadedSurface loaded;
  auto surface = load_surface(job, &loaded.mold);
  if (!surface) return surface.error();
  loaded.surface = std::make_shared<const MoldSurface>(std::move(surface).value());
  loaded.mold.import_ms = ms_since(t0);
  return loaded;
}

Result<JobOutcome> run_job(const DrapeJob& job, const std::atomic<bool>* cancel, bool progress) {
  auto loaded = load_job_surface(job);
  if (!loaded) return loaded.error();
  return run_job_on(job, *loaded, cancel, progress);
}

Result<JobOutcome> run_job_on(const DrapeJob& job, const LoadedSurface& loaded,
                              const std::atomic<bool>* cancel, bool progress) {
  const auto t0 = Clock::now();
  exporters::RunInfo run = run_info(job);
  run.faces = loaded.mold.faces;
  run.faces_info = loaded.mold.faces_info;
  run.mold_unit = loaded.mold.mold_unit;
  run.warnings = loaded.mold.warnings;
  run.import_ms = loaded.mold.import_ms;
  // The ply's boundary restricts the shared surface for this job alone (its time counts in
  // the total, not in the import a laminate shares).
  auto bounded = job_boundary(job, *loaded.surface, &run);
  if (!bounded) return bounded.error();
  const MoldSurface surface = bounded->surface;

  auto problem = job_problem(job, surface);
  if (!problem) return problem.error();
  auto res = drape_with_progress(surface, job, *problem, cancel, progress);
  if (!res) return res.error();
  if (cancel && cancel->load()) return Error{ErrorCode::kCancelled};
  run.drape_ms = res->drape_ms;
  FlatPatternOptions fo;
  fo.min_width = job.min_width;
  const FlatPattern flat = flat_pattern(surface, *res, fo);
  warn_outline_short(flat, surface.area(), *res);
  auto splices = splice_job(job, *res, flat);
  if (!splices) return splices.error();
  run.total_ms = run.import_ms + ms_since(t0);
  exporters::ExportOptions eo = job.exports;
  eo.warn_shear = job.warn_angle_deg * kDegToRad;
  auto ply = ply_report(job, surface, *res);
  if (!ply) return ply.error();
  eo.ply = *ply;
  eo.ply->boundary = bounded->report;
  eo.ply_angle_deg = ply->laid_angle_deg;  // the label says what the drape laid
  exporters::ExportContext ctx{*problem, *res, surface, &flat, run, eo};
  ctx.splices = *splices && (*splices)->split() ? splices->get() : nullptr;
  if (!job.outdir.empty())
    if (auto s = exporters::write_outputs(ctx, job.outdir, job.outputs); !s) return s.error();
  JobOutcome out = outcome_of(job, surface, *res, flat);
  out.mold_warnings = run.warnings;
  out.cut = flat.cut;
  out.splices = *splices;
  out.total_ms = run.import_ms + ms_since(t0);
  return out;
}

SearchScene search_scene(const DrapeJob& job) {
  return {job.problem, job.drape, job.min_width};
}

DrapeJob candidate_job(const DrapeJob& scene, const MoldSurface& face, const OptimizeResult& r,
                       const Candidate& c) {
  DrapeJob job = scene;
  if (auto pb = candidate_problem(search_scene(scene), face, r, c)) job.problem = *pb;
  return job;
}

}  // namespace plyfit::cli
