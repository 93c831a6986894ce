// plyfit optimize SCENE [--vary start,angle] [--objective LIST] [--evaluations N]
// [--min-coverage PCT] [--radius R] [--angle-range DEG] [-j N] [-o DIR] [--quiet]: drapes
// many initial conditions of a scene (seed point, ply angle) in parallel and reports the best
// drape per objective and the Pareto front; with -o, optimize.json, front.svg and the best
// scenes as loadable .ini files.

#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "job/scene_file.hpp"
#include "report/optimize_report.hpp"

#include <plyfit/exporters/atomic_file.hpp>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <limits>
#include <thread>

namespace plyfit::cli {
namespace {

namespace fs = std::filesystem;

/// Largest drape budget accepted.
constexpr long kMaxEvaluations = 1'000'000;
/// Most drapes run at a time.
constexpr long kMaxJobs = 1024;

// Set by SIGINT/SIGTERM: running drapes stop, nothing is written.
std::atomic<bool> g_stop{false};
extern "C" void on_optimize_signal(int) {
  g_stop.store(true);
}

const OptionTable& optimize_options() {
  static const OptionTable table = {
      help_option(),
      {"vary", "LIST", "start,angle",
       "what varies, comma-separated: start (the seed point on the face), angle (the ply's "
       "threads turned about the normal at the seed), path (the base path turned)"},
      {"objective", "LIST", "energy",
       "objectives to refine, comma-separated: energy (sum cos^2 gamma), max-shear, area (the "
       "flat pattern's)"},
      {"evaluations", "N", "200",
       "drapes of the search (half a space-filling design, half refinement)"},
      {"min-coverage", "PCT", "",
       "smallest coverage of the face, percent (default: the best coverage found, at most 100, "
       "less 0.5)"},
      {"radius", "R", "",
       "seeds within this distance (mm) of the scene's start (default: anywhere on the face)"},
      {"angle-range", "DEG", "",
       "ply angles within +-DEG of the scene's (default: half the cloth's symmetry period, 45 "
       "for a square weave)"},
      {"path-range", "DEG", "", "base-path angles within +-DEG of the scene's (default: 90)"},
      jobs_option("drapes"),
      output_option("DIR", "write optimize.json, front.svg and best-OBJECTIVE.ini into DIR"),
      quiet_option(),
  };
  return table;
}

const CommandHelp kOptimizeHelp = {
    "plyfit optimize SCENE [--vary start,angle,path] [--objective energy|max-shear|area]\n"
    "                       [--evaluations N] [--min-coverage PCT] [--radius R]\n"
    "                       [--angle-range DEG] [--path-range DEG] [-j N] [-o DIR] [--quiet]",
    "Drapes the scene's ply from many initial conditions (the seed point on the face, the\n"
    "ply's angle, the base path's angle; both sides of the base path), N at a time, and\n"
    "prints the best drape per objective and the Pareto front over energy, max shear and\n"
    "flat area. A drape counts only if it is ok (no failed node, no cloth on cloth) and\n"
    "covers at least the minimum coverage of the face. Exit 0 when done, 1 for a bad scene\n"
    "or mold or when no drape counts, 2 for a bad command line, 130 when interrupted.\n"
    "The same input gives the same result for any -j.\n"};

// --vary and --objective: lists of known names.
Status read_lists(const Options& o, OptimizeOptions& opt) {
  const std::string vary = *o.text("vary");
  opt.vary_start = opt.vary_angle = false;
  for (const auto& item : split_list(vary)) {
    if (item == "start")
      opt.vary_start = true;
    else if (item == "angle")
      opt.vary_angle = true;
    else if (item == "path")
      opt.vary_path = true;
    else
      return Error{ErrorCode::kUnknownValue, "vary", {item, std::string("start, angle, path")}};
  }
  if (!opt.vary_start && !opt.vary_angle && !opt.vary_path)
    return Error{ErrorCode::kEmptyList, "vary", {vary, std::string("start, angle, path")}};
  opt.objectives.clear();
  const std::string objectives = *o.text("objective");
  for (const auto& item : split_list(objectives)) {
    const auto ob = parse_objective(item);
    if (!ob)
      return Error{
          ErrorCode::kUnknownValue, "objective", {item, std::string("energy, max-shear, area")}};
    if (std::find(opt.objectives.begin(), opt.objectives.end(), *ob) == opt.objectives.end())
      opt.objectives.push_back(*ob);
  }
  if (opt.objectives.empty())
    return Error{
        ErrorCode::kEmptyList, "objective", {objectives, std::string("energy, max-shear, area")}};
  return ok_status();
}

// The optional bounds of the search, each within its range and given only for a coordinate
// that varies.
Status read_bounds(const Options& o, OptimizeOptions& opt) {
  struct Bounded {
    const char* key;
    Range range;
    bool varies;
    const char* vary;  ///< what --vary must have
    std::optional<double>* to;
    double scale;
  };
  const double inf = std::numeric_limits<double>::infinity();
  const Bounded bounded[] = {
      {"min-coverage", {0, 100, true, false, "percent"}, true, "", &opt.min_coverage, 0.01},
      {"radius", {0, inf, true, false, ""}, opt.vary_start, "start", &opt.radius, 1.0},
      {"angle-range",
       {0, 180, true, false, "degrees"},
       opt.vary_angle,
       "angle",
       &opt.angle_range,
       kDegToRad},
      {"path-range",
       {0, 90, true, false, "degrees"},
       opt.vary_path,
       "path",
       &opt.path_range,
       kDegToRad},
  };
  for (const Bounded& b : bounded) {
    if (!o.given(b.key)) continue;
    auto x = o.number_in(b.key, b.range);
    if (!x) return x.error();
    if (!b.varies) return Error{ErrorCode::kOptionNeedsVary, b.key, {std::string(b.vary)}};
    *b.to = *x * b.scale;
  }
  return ok_status();
}

// The search's options from the command line (errors: a bad command line).
Result<OptimizeOptions> read_search(const Options& o) {
  OptimizeOptions opt;
  if (auto st = read_lists(o, opt); !st) return st.error();
  auto evaluations = o.integer("evaluations", 1, kMaxEvaluations);
  if (!evaluations) return evaluations.error();
  opt.evaluations = static_cast<int>(*evaluations);
  if (auto st = read_bounds(o, opt); !st) return st.error();
  opt.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.given("jobs")) {
    auto jobs = o.integer("jobs", 1, kMaxJobs);
    if (!jobs) return jobs.error();
    opt.jobs = static_cast<int>(*jobs);
  }
  return opt;
}

/// The scene and the one face it drapes.
struct Scene {
  DrapeJob job;
  MoldSurface surface;
};

// A bad scene or mold fails the command: printed, none returned.
std::optional<Scene> load_scene(const std::string& path) {
  auto fail = [](const Error& e, const exporters::InputNamer& name_input) {
    print_error(e, name_input);
    return std::optional<Scene>();
  };
  auto raw = raw_from_scene(path);
  if (!raw) return fail(raw.error(), scene_namer(path));
  auto job = make_job(*raw, false);
  if (!job) return fail(job.error(), input_namer(*raw, drape_options()));
  job->outdir.clear();
  auto surface = load_surface(*job);
  if (!surface) return fail(surface.error(), job->name_input);
  // The search moves the seed over one face's (u, v); a shell's seed would also choose a face.
  if (surface->face_count() != 1) return fail(Error{ErrorCode::kOptimizeShell, path}, {});
  // The search varies the scene's problem on the mold (the seed's, turned by the ply angle).
  auto problem = job_problem(*job, *surface);
  if (!problem) return fail(problem.error(), job->name_input);
  job->problem = *problem;
  job->problem_on_mold = true;
  return Scene{std::move(job).value(), std::move(surface).value()};
}

// The search, stopped by SIGINT or SIGTERM, with a progress line on a terminal.
Result<OptimizeResult> search(const Scene& scene, OptimizeOptions opt, bool quiet,
                              double& seconds) {
  const CatchInterrupts interrupts(on_optimize_signal);
  opt.cancel = &g_stop;
  const bool tty = !quiet && ::isatty(2);
  if (tty)
    opt.progress = [](int done, int total) {
      std::cerr << "\rplyfit optimize: " << done << " / " << total << " drapes" << std::flush;
    };
  const auto t0 = std::chrono::steady_clock::now();
  auto result = optimize(search_scene(scene.job), scene.surface, opt);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (tty) std::cerr << "\r\033[K" << std::flush;
  return result;
}

// optimize.json, front.svg and best-OBJECTIVE.ini into `dir`, each written whole.
int write_outputs(const fs::path& dir, const std::string& path, const Scene& scene,
                  const OptimizeResult& r, const OptimizeOptions& opt, double seconds) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    return error_exit(kExitFailure,
                      Error{ErrorCode::kCannotCreateFolder, dir.string(), {ec.message()}});
  std::vector<std::pair<std::string, std::string>> files = {
      {"optimize.json", optimize_json(scene.job, r, opt, seconds, opt.jobs)},
      {"front.svg", optimize_svg(scene.job, r)}};
  for (Objective ob : opt.objectives)
    if (r.best[static_cast<int>(ob)] >= 0)
      files.emplace_back(std::string("best-") + to_string(ob) + ".ini",
                         best_scene_ini(scene.job, scene.surface, r, ob, path));
  for (const auto& [name, text] : files)
    if (auto st = exporters::write_file_atomic((dir / name).string(), text); !st)
      return error_exit(kExitFailure, st.error());
  std::cout << "written: ";
  for (std::size_t k = 0; k < files.size(); ++k)
    std::cout << (k ? ", " : "") << (dir / files[k].first).string();
  std::cout << "\n";
  return kExitOk;
}

int run_optimize(const Options& o) {
  auto opt = read_search(o);
  if (!opt) return error_exit(kExitUsage, opt.error(), o.namer());

  const std::string path = o.all("scene").front();
  const auto scene = load_scene(path);
  if (!scene) return kExitFailure;
  double seconds = 0;
  auto result = search(*scene, *opt, o.given("quiet"), seconds);
  if (g_stop.load() || (result && result->cancelled))
    return error_exit(kExitInterrupted, Error{ErrorCode::kInterrupted});
  if (!result)
    return error_exit(kExitFailure, Error(result.error()).in(path), scene->job.name_input);
  const OptimizeResult& r = *result;
  std::cout << optimize_table(scene->job, r, *opt, seconds, opt->jobs);
  if (std::all_of(std::begin(r.best), std::end(r.best), [](int b) { return b < 0; }))
    return error_exit(kExitFailure,
                      Error{ErrorCode::kNoFeasibleDrape, path, {note_of(r.evaluations.front())}});
  if (!o.given("output")) return kExitOk;
  return write_outputs(*o.text("output"), path, *scene, r, *opt, seconds);
}

const CommandRegistrar kRegisterOptimize{options_command(
    "optimize", "search a scene's seed point and ply angle for the lowest energy, shear or area",
    45, {optimize_options, {"scene", "scene file"}, kOptimizeHelp}, run_optimize)};

}  // namespace
}  // namespace plyfit::cli
