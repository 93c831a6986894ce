// plyfit-bench darts [--runs R]: a drape with automatic darts (drape_auto_darts) against the
// same drape without (issue 31: at most 3 drapes of the ply), medians of R >= 5 runs
// interleaved; the drapes it made and whether the ply was laid; and each drape's flat pattern
// (a job's other large step: the darts' V's are cut out of it). The hemisphere's darts relieve
// the lock; the closed torus's seams part the fronts that meet round it.

#include "bench.hpp"
#include "tables.hpp"

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <iostream>

namespace plyfit::bench {

namespace {

struct DartCase {
  std::string name;
  Result<MoldSurface> mold = Error{ErrorCode::kInternal};
  DrapeProblem problem;
  DrapeOptions options;
};

// The hemisphere from its pole, both sweeps, locked at `lock` degrees.
DartCase hemisphere_case(double R, double d, double lock) {
  DartCase c;
  c.name = "hemisphere R = " + format("%g", R) + ", d = " + format("%g", d) + ", lock " +
           format("%g", lock) + " deg";
  auto fd = builtin_mold("hemisphere", {{"R", R}});
  if (fd) c.mold = MoldSurface::from_face(*fd);
  DrapeProblem& pb = c.problem;
  pb.ply.d_weft = pb.ply.d_warp = d;
  pb.ply.base_dir = Vec2(0, 1);
  pb.ply.sweeps = {Vec2(-1, 0), Vec2(1, 0)};
  pb.start = Vec3(0, 0, R);
  pb.base_normal = Vec3(1, 0, 0);
  pb.sweeps = {Vec3(1, 0, 0), Vec3(-1, 0, 0)};
  c.options.lock_angle = lock * kDegToRad;
  return c;
}

// The outer half of a torus closed round Z (R 30, r 10), from its outer equator up the tube,
// both sweeps, no lock: the fronts meet behind the axis (the scan's seams).
DartCase torus_case(double d) {
  DartCase c;
  c.name = "closed half torus R = 30, r = 10, d = " + format("%g", d) + ", no lock";
  auto fd = builtin_mold("torus",
                         {{"R", 30.0}, {"r", 10.0}, {"t0", -90.0}, {"t1", 90.0}, {"angle", 360.0}});
  if (fd) c.mold = MoldSurface::from_face(*fd);
  DrapeProblem& pb = c.problem;
  pb.ply.d_weft = pb.ply.d_warp = d;
  pb.ply.base_dir = Vec2(0, 1);
  pb.ply.sweeps = {Vec2(-1, 0), Vec2(1, 0)};
  pb.start = Vec3(40, 0, 0);
  pb.base_normal = Vec3(0, 1, 0);
  pb.sweeps = {Vec3(0, 1, 0), Vec3(0, -1, 0)};
  return c;
}

Table darts_table(int runs, bool* ok) {
  Table t;
  t.caption = "A drape with --darts auto against the same drape without: wall time, medians of " +
              std::to_string(std::max(runs, kMinRuns)) +
              " runs each, interleaved; ratio = with / without (target <= 3: at most 3 drapes); "
              "reused = nodes of the last drape that took the drape before's solve; flat = the "
              "flat pattern of each drape (without / with darts).";
  t.header = {"case",       "drapes",  "laid",  "darts",           "nodes",       "reused",
              "without ms", "with ms", "ratio", "flat without ms", "flat with ms"};
  t.right = {false, true, false, true, true, true, true, true, true, true, true};
  for (DartCase c :
       {hemisphere_case(10, 0.1, 40), hemisphere_case(10, 0.05, 40), torus_case(0.5)}) {
    if (!c.mold) {
      *ok = false;
      t.add_failed(c.name, "no mold");
      continue;
    }
    Result<DrapeResult> without = Error{ErrorCode::kInternal}, with = without;
    const auto m = paired_medians<4>(runs, [&] {
      const double t0 = time_once([&] { without = drape(*c.mold, c.problem, c.options); });
      const double t1 = time_once([&] { with = drape_auto_darts(*c.mold, c.problem, c.options); });
      if (!without || !with) return std::array{t0, t1, 0.0, 0.0};
      return std::array{t0, t1, time_once([&] { (void)flat_pattern(*c.mold, *without); }),
                        time_once([&] { (void)flat_pattern(*c.mold, *with); })};
    });
    if (!m || !without || !with) {
      *ok = false;
      t.add_failed(c.name, "failed");
      continue;
    }
    const auto [t0, t1, f0, f1] = *m;
    const bool laid = with->metrics.nodes.conflict == 0 && with->metrics.nodes.shear_limit == 0;
    t.add({c.name, format("%u", with->drapes), laid ? "yes" : "no",
           format("%zu", with->darts.size()), format("%zu", with->nodes.size()),
           format("%llu", static_cast<unsigned long long>(with->solves_reused)),
           format("%.1f", t0 * 1e3), format("%.1f", t1 * 1e3), format("%.2f", t1 / t0),
           format("%.1f", f0 * 1e3), format("%.1f", f1 * 1e3)});
  }
  return t;
}

const BenchmarkRegistrar kDarts{
    runs_table_benchmark("darts", "a drape with automatic darts against one without", darts_table)};

}  // namespace

}  // namespace plyfit::bench
