// plyfit-bench batch: batch throughput of `plyfit batch` with -j1 against -j2 .. -jN (N the
// number of cores), on generated scene files (drapes of the built-in wave), each a separate
// child process writing every output.

#include "bench.hpp"
#include "tables.hpp"

#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <thread>

namespace plyfit::bench {

namespace {

namespace fs = std::filesystem;

// Scenes per batch and their ply spacing on the 100 x 100 mm wave (about 30,000 nodes each:
// the drape, not process start-up, dominates).
constexpr int kScenes = 8;
constexpr double kSceneSpacing = 0.6;

std::string scene_text(int k) {
  // Base paths at different angles, so that the scenes are different drapes.
  const double a = 0.15 * k;
  return format(
      "# plyfit-bench batch scene %d\n[mold]\nmold = builtin:wave\n\n[ply]\nspacing = %.3f\n\n"
      "[start]\nstart2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\nsweep2d = 0,-1\n"
      "start3d = 50,50,0\nbase-normal = %.6f,%.6f,0\nsweep3d = %.6f,%.6f,0\nsweep3d = "
      "%.6f,%.6f,0\n",
      k, kSceneSpacing, -std::sin(a), std::cos(a), -std::sin(a), std::cos(a), std::sin(a),
      -std::cos(a));
}

}  // namespace

Table batch_table(bool* available, double* speedup) {
  Table t;
  const unsigned cores = machine_cores();
  t.caption = format(
      "`plyfit batch` on %d generated scenes (built-in wave, spacing %.1f mm, base paths at "
      "different angles; every output written), one child process per scene. Time: median of "
      "%d runs of the whole batch; speed-up against -j1 measured in the same invocation; "
      "cores used: CPU time of the batch's processes (median) over its wall time. Other "
      "processes on the machine share its cores (see the load average above).",
      kScenes, kSceneSpacing, kMinRuns);
  t.header = {"jobs", "batch time (s)", "scenes/s", "speed-up vs -j1", "cores used"};
  t.right = {false, true, true, true, true};
  if (speedup) *speedup = 0.0;
  const std::optional<std::string> plyfit = plyfit_with_command(t, "batch", available);
  if (!plyfit) return t;
  const std::string& bin = *plyfit;
  const fs::path dir = scratch_path("batch");
  fs::create_directories(dir);
  std::string scenes;
  for (int k = 0; k < kScenes; ++k) {
    const fs::path p = dir / format("scene%02d.ini", k);
    write_text_file(p.string(), scene_text(k));
    scenes += " '" + p.string() + "'";
  }
  double t1 = 0.0;
  for (unsigned j = 1; j <= cores; ++j) {
    const fs::path out = dir / format("out-j%u", j);
    const CommandTimes run = time_command(
        format("'%s' batch%s -j %u -o '%s'", bin.c_str(), scenes.c_str(), j, out.string().c_str()),
        [&] { fs::remove_all(out); });
    if (!run.ok) {
      t.add({format("-j%u", j), "failed", "-", "-", "-"});
      continue;
    }
    const double sec = run.wall;
    if (j == 1) t1 = sec;
    if (speedup && t1 > 0) *speedup = t1 / sec;
    t.add({format("-j%u", j), format("%.2f", sec), format("%.2f", kScenes / sec),
           t1 > 0 ? format("%.2fx", t1 / sec) : std::string("-"), format("%.2f", run.cpu / sec)});
    std::fprintf(stderr, "batch: -j%u: %.2f s\n", j, sec);
  }
  fs::remove_all(dir);
  return t;
}

namespace {

const BenchmarkRegistrar kBatch{table_benchmark(
    "batch", "plyfit batch -j1 against -j2 .. -jN on generated scenes",
    [](const std::vector<std::string>&, bool* available) { return batch_table(available); })};

}  // namespace

}  // namespace plyfit::bench
