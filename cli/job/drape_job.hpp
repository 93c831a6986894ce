#pragma once
// A drape job: every input of `plyfit drape`, from command-line flags and scene files alike
// (their keys: drape_options()), and running it (import, drape, flat pattern, outputs). Shared
// by drape, batch, compare and optimize.

#include "commands/command_line.hpp"
#include "job/curve_file.hpp"

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/optimize.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/splice.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace plyfit::exporters {
struct RunInfo;
}

namespace plyfit::cli {

/// The keys of a drape job (flags --key, scene keys `key`), in help order.
const OptionTable& drape_options();

/// Seams of other plies a ply's seams keep at least `distance` from (on the part).
struct SpliceStagger {
  std::vector<std::vector<Vec3>> seams;
  double distance = 0.0;
};

/// Every input of a drape, converted and validated.
struct DrapeJob {
  std::string mold;  ///< file path (resolved) or "builtin:NAME[:k=v,...]"
  int face = 0;
  std::vector<int> faces;        ///< --faces: file faces sewn into a shell (empty: --face)
  std::optional<Vec3> faces_at;  ///< --faces-at: the face nearest this point (instead of face)
  bool all_faces = false;        ///< --faces all
  /// --faces connected: the faces reached from the face under --faces-at (else --seed) across
  /// shared edges whose crease is at most max_crease_deg.
  bool connected_faces = false;
  double max_crease_deg = 60.0;
  std::string format;  ///< importer override
  DrapeProblem problem;
  DrapeOptions drape;  ///< lock angle, tolerances, guess rule, node cap
  double lock_angle_deg = 90.0;
  double tolerance_rel = 1e-14;
  int max_iterations = 40;
  bool flip_normal = false;
  std::string outdir;
  std::vector<std::string> outputs;
  /// What the writers are told as given (--curve-degree, --view, --dxf-threads, the
  /// material's label and table); run_job adds the warning angle and the ply as laid.
  exporters::ExportOptions exports;
  /// --min-width: the cut outline's minimum width; empty: half the spacing.
  std::optional<double> min_width;
  double warn_angle_deg = 25.0;
  std::string ply_name = "ply";
  double ply_angle_deg = 0.0;             ///< --ply-angle: the warp from the rosette (degrees)
  std::optional<Vec3> seed;               ///< --seed: the ply defined by seed, rosette and angle
  Vec3 rosette = Vec3::UnitX();           ///< --rosette: the 0 deg direction
  bool rosette_given = false;             ///< else, with the start keys, their warp is 0 deg
  std::optional<CurveFileSpec> boundary;  ///< --boundary: the ply's boundary curves
  double boundary_offset = 0.0;           ///< --boundary-offset (mm; > 0 grows the region)
  std::vector<CurveFileSpec> darts;       ///< --dart: curves the ply is cut along
  bool darts_auto = false;                ///< --darts auto: darts proposed (drape_auto_darts)
  /// --seed-curve FILE[:PICK]: the curve the base path follows (problem.seed_curve kCurve).
  std::optional<CurveFileSpec> seed_curve_file;
  /// `problem` is already the problem on the mold (job_problem() applied: seed, angle).
  bool problem_on_mold = false;
  /// --roll-width (or the material's roll width): split the flat pattern into pieces no wider
  /// across the warp; empty: no splices.
  std::optional<double> roll_width;
  double splice_overlap = 0.0;  ///< --splice-overlap (mm)
  /// The seams this ply's keep apart from, asked for once the drape is done (plyfit laminate's
  /// stagger across plies); empty: none.
  std::function<SpliceStagger()> stagger;
  std::string material = "woven";  ///< name in the materials table
  std::string scene;               ///< scene file the job came from, if any
  /// Names the inputs its errors blame (scene keys) as the flag or the scene file's key their
  /// value came from ("--sweep3d", "FILE: key 'sweep3d'").
  exporters::InputNamer name_input;
};

/// Converts raw values (flags, a scene file, or both merged) into a job. `need_output` requires
/// the output folder. Errors blame the key (name them with input_namer(raw, drape_options())).
Result<DrapeJob> make_job(const RawOptions& raw, bool need_output = true);

/// What a finished job reports (also for batch summaries).
struct JobOutcome {
  std::string status = "error";  ///< ok, partial, error, cancelled
  std::string error;             ///< for status error: the error's text
  std::string error_code;        ///< and its code (to_string(ErrorCode))
  std::uint64_t mapped = 0;
  double shear_max_deg = 0.0;
  double total_ms = 0.0;
  std::vector<std::string> files;
  DrapeMetrics metrics;
  double face_area = 0.0;
  double flat_outline_area = 0.0;  ///< area of the cut outline (FlatPattern::cut_area)
  /// The share of the surface the flat pattern's outline covers (outline_coverage.hpp).
  double outline_coverage = 0.0;
  std::vector<Warning> warnings;  ///< the drape's (why partial, and notes)
  /// The mold's (reading and sewing it: report.json's mold.warnings, e.g. faces that share
  /// no edge form separate shells).
  std::vector<Warning> mold_warnings;
  /// The flat pattern's cut outline (FlatPattern::cut), for drawings of several plies.
  std::vector<OutlineLoop> cut;
  /// The pieces and seams, when the job has a roll width (SplicePlan::split() when cut).
  std::shared_ptr<const SplicePlan> splices;
};

/// A job's surface, loaded once for every job that drapes it (plyfit laminate's plies share
/// their mold): the surface and what the report says of the mold (faces, unit, warnings,
/// import time).
struct LoadedSurface {
  std::shared_ptr<const MoldSurface> surface;
  exporters::RunInfo mold;
};

/// Imports the surface a job drapes: a built-in mold (one face, or a built-in shell), one face
/// of a file (--face), or several faces of a file sewn into a shell (--faces), with the job's
/// side applied; `run`, if given, gets what the report says of the mold. run_job's import,
/// shared with `plyfit optimize` (which drapes one surface many times).
Result<MoldSurface> load_surface(const DrapeJob& job, exporters::RunInfo* run = nullptr);
/// The drape problem of a job on its mold: from --seed, --rosette and --ply-angle, or the start
/// keys turned by --ply-angle (ply_setup.cpp).
Result<DrapeProblem> job_problem(const DrapeJob& job, const MoldSurface& surface);
/// A job's surface restricted to its boundary's region, and what report.json says of the
/// boundary (none without one: the surface unchanged).
struct JobBoundary {
  MoldSurface surface;
  std::optional<exporters::BoundaryReport> report;
};
/// The job's surface restricted to its --boundary (ply_setup.cpp): the curves read, bounded
/// about the seed (or the 3D start); `run`, if given, gets the faces that remain. Errors blame
/// "boundary" and name the file.
Result<JobBoundary> job_boundary(const DrapeJob& job, const MoldSurface& surface,
                                 exporters::RunInfo* run = nullptr);
/// What report.json's `ply` and the labels say of the ply a drape laid: the angle measured on
/// the drape from the rosette, whatever keys made it.
Result<exporters::PlyReport> ply_report(const DrapeJob& job, const MoldSurface& surface,
                                        const DrapeResult& result);

/// Loads a job's surface (load_surface) with its import time.
Result<LoadedSurface> load_job_surface(const DrapeJob& job);

/// Runs a job end to end; outputs are written atomically into job.outdir. `cancel` stops
/// the drape (no files are written then). Progress goes to stderr when it is a terminal and
/// `progress` is true. Errors blame drape inputs by key (job.name_input names them).
Result<JobOutcome> run_job(const DrapeJob& job, const std::atomic<bool>* cancel = nullptr,
                           bool progress = false);

/// run_job on a surface already loaded (load_job_surface): safe to call from several threads
/// at once on one surface.
Result<JobOutcome> run_job_on(const DrapeJob& job, const LoadedSurface& loaded,
                              const std::atomic<bool>* cancel = nullptr, bool progress = false);

/// The scene the search of initial conditions starts from (plyfit optimize).
SearchScene search_scene(const DrapeJob& job);
/// The scene of a candidate of the search: the scene with the candidate's seed, ply angle and
/// sweeps (both sides of the base path), loadable with dump_scene.
DrapeJob candidate_job(const DrapeJob& scene, const MoldSurface& face, const OptimizeResult& r,
                       const Candidate& c);

}  // namespace plyfit::cli
