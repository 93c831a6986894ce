#pragma once
// The tables of the benchmark report. Each function runs its measurements and returns
// formatted tables; the subcommands print them and `plyfit-bench report` collects them into
// BENCHMARKS.md and bench/results/*.csv.

#include "bench.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace plyfit::bench {

/// Table 4a: NurbsSurface::eval1 against OpenCASCADE's Geom_BSplineSurface::D1.
Table kernel_table();
/// Table 4b: the three solvers on independently built configurations.
Table solvers_table();

/// Table 1: drape time, throughput and memory against the number of nodes.
struct ThroughputOptions {
  std::vector<int> sizes = {100, 300, 1000, 2000};  ///< plies of size^2 nodes
  int runs = kMinRuns;
};
struct ThroughputReport {
  Table table;  ///< one row per face and size
  Table fit;    ///< per face: fitted exponent of time against n
  /// The bicubic face's rows, for the targets: mapped nodes per second and peak heap bytes
  /// per mapped node at each size; the worst link error / d.
  std::vector<double> bicubic_nodes_per_s, peak_bytes_per_node;
  double bicubic_link_rel = 0.0;
  bool ok = true;
};
/// The throughput options of a command line: --sizes N,N,... and --runs N.
ThroughputOptions throughput_options(const std::vector<std::string>& args);
ThroughputReport throughput_report(const ThroughputOptions& o);

/// Table 2: time against error for Newton tolerances 1e-3 .. 1e-14 (x d).
struct TolerancePoint {
  std::string face;
  double tol = 0.0, ms = 0.0, link_rel = 0.0, surface_rel = 0.0;
  double iterations = 0.0;    ///< Newton iterations per solve
  double displacement = 0.0;  ///< largest node displacement from the default's net / d
};
struct ToleranceReport {
  Table table;
  std::vector<TolerancePoint> points;
  bool ok = true;
};
ToleranceReport tolerance_report(int runs);
/// Sentences summarising the tolerance table per face: time and error at the default against
/// looser tolerances (figures from `points`).
std::string tolerance_summary(const std::vector<TolerancePoint>& points, double default_tol);

/// Table 3: discretisation error against spacing on cases with exact answers.
struct ConvergenceReport {
  Table table;
  Table orders;  ///< fitted log-log slopes
  bool ok = true;
};
ConvergenceReport convergence_report();

/// Table 5: hard cases, one full drape each.
Table hard_case_table(int runs, bool* ok);
/// Cost of the overlap test (drapes with and without it, alternating) on the throughput
/// faces and the closed hemisphere at ply sizes `sizes` (nodes per side; empty: 300 and
/// 1000); the hemisphere's time per node against the sphere octant's.
Table overlap_table(int runs, std::vector<int> sizes, bool* ok);

/// Batch throughput: `plyfit batch -j1` against `-j2` (and more, up to the cores); the
/// speed-up of the most jobs against -j1 in `speedup` (0 if not measured).
Table batch_table(bool* available, double* speedup = nullptr);

/// plyfit optimize on the paper's sphere-octant cases: the lowest of the scenes' energies
/// (the paper's best case), the highest of the best energies found from the three, the
/// slowest run on all cores (seconds).
struct OptimizeFigures {
  double paper_best = 1e300;
  double found_worst = 0.0;
  double seconds = 0.0;
  bool ok = true;
};
/// `plyfit optimize` with -j1 against all cores on the three sphere-octant cases.
Table optimize_bench_table(bool* available, OptimizeFigures* figures = nullptr);

/// Where the drape's time goes (perf record on the bicubic face, by part).
Table profile_table(bool* available);

/// Writes a large mold file of `faces` trimmed bicubic B-spline faces with poles x poles poles
/// and `holes` holes each (IGES or STEP by the extension; stress_mold.cpp); false on failure.
bool write_stress_mold(const std::string& path, int faces, int poles, int holes);

/// Import speed: per file (the shared CAD files, stress files written by write_stress_mold()
/// into `stress_dir`), OpenCASCADE's own read time against plyfit's open, listing and import
/// of one face, and the `plyfit info` process (also with `baseline`, another plyfit binary,
/// when not empty). `max_ratio` gets the largest import / OpenCASCADE read ratio and
/// `max_info_s` the longest plyfit info (medians).
struct ImportReport {
  Table table;
  double max_ratio = 0.0, max_info_s = 0.0;
  bool ok = true;
};
ImportReport import_report(int runs, const std::string& stress_dir, const std::string& baseline);

/// Face areas: plyfit's integration against OpenCASCADE's, per file: time, agreement of the
/// listing with the described areas, of the two integration directions, with OpenCASCADE.
Table area_table(const std::string& stress_dir);

/// Small jobs: process time of a small drape on a built-in mold (with OpenCASCADE loaded at
/// start as the comparison, and `baseline`'s when given) and of small file jobs.
Table small_jobs_table(int runs, const std::string& baseline);

/// Writes an SVG plot of drape time against link-length error (one series per face).
std::string time_error_svg(const std::vector<TolerancePoint>& points, double default_tol);

/// Drapes over built-in shells of N faces against the same surface as one face: ns per
/// mapped node on both and their ratio (issue 12's target <= 1.2); the largest ratio in
/// *worst_ratio; *ok false if a case could not be built or draped.
Table shell_drape_table(int runs, double* worst_ratio, bool* ok);

}  // namespace plyfit::bench
