// plyfit optimize SCENE [--vary start,angle] [--objective LIST] [--evaluations N]
// [--min-coverage PCT] [--radius R] [--angle-range DEG] [-j N] [-o DIR] [--quiet]: drapes
// many initial conditions of a scene (seed point, ply angle) in parallel and reports the best
// drape per objective and the Pareto front; with -o, optimize.json, front.svg and the best
// scenes as loadable .ini files.

#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "report/optimize_report.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/messages.hpp>

#include <boost/program_options.hpp>

#include <unistd.h>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>
#include <thread>

namespace plyfit::cli {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

/// Largest drape budget accepted.
constexpr int kMaxEvaluations = 1'000'000;

// Set by SIGINT/SIGTERM: running drapes stop, nothing is written.
std::atomic<bool> g_stop{false};
extern "C" void on_optimize_signal(int) {
  g_stop.store(true);
}

po::options_description optimize_options() {
  po::options_description opts("options");
  auto text = [](const char* name, const char* def = nullptr) {
    auto* v = po::value<std::string>()->value_name(name);
    return def ? v->default_value(def) : v;
  };
  opts.add_options()("help,h", "show this help")(
      "vary", text("LIST", "start,angle"),
      "what varies, comma-separated: start (the seed point on the face), angle (the ply's "
      "threads turned about the normal at the seed), path (the base path turned)")(
      "objective", text("LIST", "energy"),
      "objectives to refine, comma-separated: energy (sum cos^2 gamma), max-shear, area (the "
      "flat pattern's)")("evaluations", text("N", "200"),
                         "drapes of the search (half a space-filling design, half refinement)")(
      "min-coverage", text("PCT"),
      "smallest coverage of the face, percent (default: the best coverage found, at most 100, "
      "less 0.5)")("radius", text("R"),
                   "seeds within this distance (mm) of the scene's start (default: anywhere on "
                   "the face)")(
      "angle-range", text("DEG"),
      "ply angles within +-DEG of the scene's (default: half the cloth's symmetry period, 45 "
      "for a square weave)")("path-range", text("DEG"),
                             "base-path angles within +-DEG of the scene's (default: 90)")(
      "jobs,j", text("N"), "drapes run at a time (default: the number of cores)")(
      "output,o", text("DIR"), "write optimize.json, front.svg and best-OBJECTIVE.ini into DIR")(
      "quiet", "no progress line");
  return opts;
}

void optimize_help(std::ostream& os) {
  os << "usage: plyfit optimize SCENE [--vary start,angle,path] [--objective "
        "energy|max-shear|area]\n"
        "                       [--evaluations N] [--min-coverage PCT] [--radius R]\n"
        "                       [--angle-range DEG] [--path-range DEG] [-j N] [-o DIR] "
        "[--quiet]\n\n"
        "Drapes the scene's ply from many initial conditions (the seed point on the face, the\n"
        "ply's angle, the base path's angle; both sides of the base path), N at a time, and\n"
        "prints the best drape per objective and the Pareto front over energy, max shear and\n"
        "flat area. A drape counts only if it is ok (no failed node, no cloth on cloth) and\n"
        "covers at least the minimum coverage of the face. Exit 0 when done, 1 for a bad scene\n"
        "or mold or when no drape counts, 2 for a bad command line, 130 when interrupted.\n"
        "The same input gives the same result for any -j.\n\n"
     << optimize_options();
}

Result<double> number(const po::variables_map& vm, const std::string& key) {
  return parse_number(vm[key].as<std::string>(), "--" + key);
}

int run_optimize(const std::vector<std::string>& args) {
  po::options_description opts = optimize_options();
  opts.add_options()("scene", po::value<std::vector<std::string>>(), "scene file");
  po::positional_options_description pos;
  pos.add("scene", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("optimize: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    optimize_help(std::cout);
    return kExitOk;
  }
  auto usage = [](const std::string& message) {
    print_error("optimize: " + message);
    return kExitUsage;
  };
  if (!vm.count("scene")) return usage("no scene file (plyfit optimize SCENE [options])");
  const auto scenes = vm["scene"].as<std::vector<std::string>>();
  if (scenes.size() > 1) return usage("one scene file only, got '" + scenes[1] + "' too");

  OptimizeOptions o;
  {
    const std::string v = vm["vary"].as<std::string>();
    std::stringstream ss(v);
    std::string item;
    o.vary_start = o.vary_angle = false;
    while (std::getline(ss, item, ',')) {
      if (item == "start")
        o.vary_start = true;
      else if (item == "angle")
        o.vary_angle = true;
      else if (item == "path")
        o.vary_path = true;
      else
        return usage("--vary: unknown '" + item + "' (a list of start, angle, path)");
    }
    if (!o.vary_start && !o.vary_angle && !o.vary_path)
      return usage("--vary: give a list of start, angle, path");
  }
  {
    o.objectives.clear();
    std::stringstream ss(vm["objective"].as<std::string>());
    std::string item;
    while (std::getline(ss, item, ',')) {
      const auto ob = parse_objective(item);
      if (!ob) return usage("--objective: unknown '" + item + "' (energy, max-shear or area)");
      if (std::find(o.objectives.begin(), o.objectives.end(), *ob) == o.objectives.end())
        o.objectives.push_back(*ob);
    }
    if (o.objectives.empty()) return usage("--objective: give energy, max-shear or area");
  }
  if (auto n = number(vm, "evaluations"); !n) {
    return usage(exporters::describe(n.error()));
  } else if (*n != std::floor(*n) || *n < 1 || *n > kMaxEvaluations) {
    return usage("--evaluations: '" + vm["evaluations"].as<std::string>() +
                 "' must be an integer from 1 to " + std::to_string(kMaxEvaluations));
  } else {
    o.evaluations = static_cast<int>(*n);
  }
  // The optional numbers: each within (lo, hi], and the bounds of a coordinate only when it
  // varies.
  struct Bounded {
    const char* key;
    double lo, hi;
    const char* range;
    bool needed;
    const char* needs;
    std::optional<double>* to;
    double scale;
  };
  const double inf = std::numeric_limits<double>::infinity();
  const Bounded bounded[] = {
      {"min-coverage", 0, 100, "in (0, 100] percent", true, "", &o.min_coverage, 0.01},
      {"radius", 0, inf, "positive", o.vary_start, "the seed does not vary (--vary has no start)",
       &o.radius, 1.0},
      {"angle-range", 0, 180, "in (0, 180] degrees", o.vary_angle,
       "the angle does not vary (--vary has no angle)", &o.angle_range, kDegToRad},
      {"path-range", 0, 90, "in (0, 90] degrees", o.vary_path,
       "the base path does not vary (--vary has no path)", &o.path_range, kDegToRad},
  };
  for (const Bounded& b : bounded) {
    if (!vm.count(b.key)) continue;
    const std::string flag = std::string("--") + b.key;
    auto x = number(vm, b.key);
    if (!x) return usage(exporters::describe(x.error()));
    if (!(*x > b.lo && *x <= b.hi))
      return usage(flag + ": '" + vm[b.key].as<std::string>() + "' must be " + b.range);
    if (!b.needed) return usage(flag + ": " + b.needs);
    *b.to = *x * b.scale;
  }
  o.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (vm.count("jobs")) {
    auto x = number(vm, "jobs");
    if (!x) return usage(exporters::describe(x.error()));
    if (*x != std::floor(*x) || *x < 1 || *x > 1024)
      return usage("-j: '" + vm["jobs"].as<std::string>() + "' must be an integer from 1 to 1024");
    o.jobs = static_cast<int>(*x);
  }

  // The scene and its face: a bad scene or mold fails the command (exit 1).
  const std::string path = scenes.front();
  auto raw = raw_from_scene(path);
  if (!raw) {
    print_error("optimize: " + exporters::describe(raw.error()));
    return kExitFailure;
  }
  auto job = make_job(*raw, false);
  if (!job) {
    print_error("optimize: " + exporters::describe(job.error()));
    return kExitFailure;
  }
  job->outdir.clear();
  auto surface = load_surface(*job);
  if (!surface) {
    print_error("optimize: " + exporters::describe(surface.error()));
    return kExitFailure;
  }
  // The search moves the seed over one face's (u, v); a shell's seed would also choose a face.
  if (surface->face_count() != 1) {
    print_error("optimize: " + path +
                ": the scene drapes several faces (--faces); plyfit optimize searches one face");
    return kExitFailure;
  }

  struct sigaction sa {};
  sa.sa_handler = on_optimize_signal;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {
  }, old_term{};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  o.cancel = &g_stop;
  const bool tty = !vm.count("quiet") && ::isatty(2);
  if (tty)
    o.progress = [](int done, int total) {
      std::cerr << "\rplyfit optimize: " << done << " / " << total << " drapes" << std::flush;
    };
  const auto t0 = std::chrono::steady_clock::now();
  auto result = optimize(search_scene(*job), *surface, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (tty) std::cerr << "\r\033[K" << std::flush;
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  if (g_stop.load() || (result && result->cancelled)) {
    print_error("optimize: interrupted: nothing written");
    return kExitInterrupted;
  }
  if (!result) {
    print_error("optimize: " + (job->scene.empty() ? "" : job->scene + ": ") +
                exporters::describe(result.error()));
    return kExitFailure;
  }
  const OptimizeResult& r = *result;
  std::cout << optimize_table(*job, r, o, seconds, o.jobs);
  bool any = false;
  for (int b : r.best) any = any || b >= 0;
  if (!any) {
    print_error("optimize: " + path +
                ": no drape is feasible (the scene's: " + note_of(r.evaluations.front()) + ")");
    return kExitFailure;
  }
  if (vm.count("output")) {
    const fs::path dir = vm["output"].as<std::string>();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
      print_error("optimize: " + dir.string() +
                  ": cannot create the output folder: " + ec.message());
      return kExitFailure;
    }
    std::vector<std::pair<std::string, std::string>> files = {
        {"optimize.json", optimize_json(*job, r, o, seconds, o.jobs)},
        {"front.svg", optimize_svg(*job, r)}};
    for (Objective ob : o.objectives) {
      const int b = r.best[static_cast<int>(ob)];
      if (b < 0) continue;
      const Evaluation& e = r.evaluations[static_cast<std::size_t>(b)];
      std::ostringstream ini;
      ini.precision(17);
      ini << "# plyfit optimize: the lowest " << to_string(ob) << " of " << path << " (drape #"
          << e.index << ": energy " << e.figures.energy << ", max shear " << e.figures.max_shear_deg
          << " deg, flat area " << e.figures.flat_area << " mm^2, coverage "
          << 100.0 * e.figures.coverage << "%; ply angle " << e.candidate.angle / kDegToRad
          << " deg from the scene's)\n";
      ini << dump_scene(candidate_job(*job, *surface, r, e.candidate));
      files.emplace_back(std::string("best-") + to_string(ob) + ".ini", ini.str());
    }
    for (const auto& [name, text] : files) {
      if (auto st = exporters::write_file_atomic((dir / name).string(), text); !st) {
        print_error("optimize: " + exporters::describe(st.error()));
        return kExitFailure;
      }
    }
    std::cout << "written: ";
    for (std::size_t k = 0; k < files.size(); ++k)
      std::cout << (k ? ", " : "") << (dir / files[k].first).string();
    std::cout << "\n";
  }
  return kExitOk;
}

const CommandRegistrar kRegisterOptimize{Command{
    "optimize", "search a scene's seed point and ply angle for the lowest energy, shear or area",
    45, run_optimize}};

}  // namespace
}  // namespace plyfit::cli
