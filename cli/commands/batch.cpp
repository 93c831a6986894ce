// plyfit batch SCENE... [-j N] [-o OUTROOT] [--shard K/N]: runs every scene in a child process
// (`plyfit drape SCENE -o DIR --quiet --outcome FILE`), N at a time, each into OUTROOT/<name>/,
// then prints a summary table and writes OUTROOT/summary.json and summary.csv.
//
// Process model: a child process per scene isolates crashes and OpenCASCADE's global reader
// state. A child writes into a staging folder OUTROOT/.plyfit-batch-<pid>/<name>/ that is
// renamed to OUTROOT/<name>/ only when the drape succeeded, so a failed, crashed or cancelled
// scene leaves neither final nor temporary files behind. Ctrl-C (SIGINT) or SIGTERM: no new
// scene starts, running children get SIGINT (SIGKILL after kKillGraceSeconds, or at a second
// Ctrl-C), their staging folders are removed, and the summary says which scenes were
// cancelled and which were not run.

#include "commands/commands.hpp"
#include "job/outcome.hpp"
#include "job/scene_names.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

extern char** environ;

namespace plyfit::cli {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Seconds a child has to stop after SIGINT before it is killed.
constexpr double kKillGraceSeconds = 5.0;
/// How often the loop looks for finished children and redraws the progress line.
constexpr auto kPollInterval = std::chrono::milliseconds(20);
/// Minimum time between two progress-line redraws.
constexpr double kProgressRedrawSeconds = 0.2;

std::atomic<int> g_interrupts{0};
extern "C" void on_batch_interrupt(int) {
  g_interrupts.fetch_add(1);
}

/// One scene of the batch and what became of it.
struct SceneRun {
  std::size_t index = 0;           ///< position in the given list
  std::string path;                ///< scene file as given
  std::string name;                ///< unique scene name (output folder name)
  std::string status = "not run";  ///< ok, partial, error, crashed, cancelled, not run
  std::string error;
  int exit_code = -1;  ///< -1: none (not run, or killed by a signal)
  int signal = 0;
  std::uint64_t mapped = 0;
  double shear_max_deg = 0.0;
  double seconds = 0.0;
  std::string outdir;  ///< final folder, empty if none
  std::vector<std::string> files;
  // While running:
  pid_t pid = -1;
  Clock::time_point started;
  std::string staging, outcome, log_out, log_err;
};

bool succeeded(const SceneRun& s) {
  return s.status == "ok" || s.status == "partial";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Last non-empty line of a child's stderr, without the "plyfit: error: " prefix.
std::string last_error_line(const std::string& text) {
  std::istringstream ss(text);
  std::string line, last;
  while (std::getline(ss, line))
    if (!line.empty() && line.find('\r') == std::string::npos) last = line;
  const std::string prefix = "plyfit: error: ";
  if (last.rfind(prefix, 0) == 0) last = last.substr(prefix.size());
  return last;
}

std::string signal_name(int sig) {
  const char* d = strsignal(sig);
  return "signal " + std::to_string(sig) + (d ? std::string(" (") + d + ")" : "");
}

/// Unique names over the whole list (see scene_names.hpp).
void assign_names(std::vector<SceneRun>& runs) {
  std::vector<std::string> paths;
  for (const auto& r : runs) paths.push_back(r.path);
  const auto names = unique_scene_names(paths);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].name = names[i];
}

/// True when every entry of `dir` is a file some exporter writes (a previous run's outputs).
bool holds_only_outputs(const fs::path& dir) {
  std::set<std::string> known;
  for (const auto& e : exporters::registry())
    for (const auto& f : e.files) known.insert(f);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (!e.is_regular_file() || !known.count(e.path().filename().string())) return false;
  return !ec;
}

/// Moves a finished scene's staging folder to its final place (replacing a previous run's
/// outputs, never anything else).
Status publish(const SceneRun& r, const fs::path& final_dir) {
  std::error_code ec;
  if (fs::exists(final_dir, ec)) {
    if (!fs::is_directory(final_dir) || !holds_only_outputs(final_dir))
      return Error{final_dir.string() + " exists and holds other files: not replaced"};
    fs::remove_all(final_dir, ec);
    if (ec) return Error{final_dir.string() + ": cannot replace: " + ec.message()};
  }
  fs::rename(r.staging, final_dir, ec);
  if (ec)
    return Error{final_dir.string() + ": cannot move the outputs into place: " + ec.message()};
  return ok_status();
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string fixed(double x, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << x;
  return os.str();
}

std::string pad(std::string s, std::size_t w) {
  if (s.size() < w) s.append(w - s.size(), ' ');
  return s;
}

void print_table(const std::vector<SceneRun>& runs, std::ostream& os) {
  std::vector<std::vector<std::string>> rows = {
      {"scene", "status", "mapped", "max shear (deg)", "time (s)", "outputs"}};
  for (const auto& r : runs) {
    std::string outputs;
    if (!r.outdir.empty())
      outputs = r.outdir + "/ (" + std::to_string(r.files.size()) + " files)";
    else
      outputs = r.error.empty() ? "-" : r.error;
    const bool ran = succeeded(r);
    rows.push_back({r.name, r.status, ran ? std::to_string(r.mapped) : "-",
                    ran ? fixed(r.shear_max_deg, 3) : "-",
                    r.status == "not run" ? "-" : fixed(r.seconds, 2), outputs});
  }
  std::vector<std::size_t> w(rows[0].size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c + 1 < row.size(); ++c) w[c] = std::max(w[c], row[c].size());
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += c + 1 < row.size() ? pad(row[c], w[c] + 2) : row[c];
    os << line << "\n";
  }
}

std::map<std::string, int> count_statuses(const std::vector<SceneRun>& runs) {
  std::map<std::string, int> c = {{"ok", 0},      {"partial", 0},   {"error", 0},
                                  {"crashed", 0}, {"cancelled", 0}, {"not run", 0}};
  for (const auto& r : runs) c[r.status]++;
  return c;
}

std::string summary_json(const std::vector<SceneRun>& runs, const std::string& outroot,
                         const std::string& shard, int jobs, bool interrupted, double elapsed) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const auto& r : runs) {
    nlohmann::json j = {
        {"index", r.index},
        {"name", r.name},
        {"scene", r.path},
        {"status", r.status},
        {"error", r.error},
        {"exit_code", r.exit_code >= 0 ? nlohmann::json(r.exit_code) : nullptr},
        {"signal", r.signal ? nlohmann::json(r.signal) : nullptr},
        {"mapped", r.mapped},
        {"shear_max_deg", r.shear_max_deg},
        {"time_s", r.seconds},
        {"outdir", r.outdir.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.outdir)},
        {"files", r.files}};
    scenes.push_back(std::move(j));
  }
  nlohmann::json counts;
  for (const auto& [k, v] : count_statuses(runs)) counts[k == "not run" ? "not_run" : k] = v;
  counts["total"] = runs.size();
  const nlohmann::json j = {
      {"outroot", outroot},
      {"shard", shard.empty() ? nlohmann::json(nullptr) : nlohmann::json(shard)},
      {"jobs", jobs},
      {"interrupted", interrupted},
      {"elapsed_s", elapsed},
      {"counts", counts},
      {"scenes", scenes}};
  return j.dump(2) + "\n";
}

std::string summary_csv(const std::vector<SceneRun>& runs) {
  std::ostringstream os;
  os << "index,name,scene,status,exit_code,mapped,shear_max_deg,time_s,outdir,files,error\n";
  for (const auto& r : runs) {
    std::string files;
    for (const auto& f : r.files) files += (files.empty() ? "" : ";") + f;
    std::ostringstream shear;
    shear.precision(17);
    shear << r.shear_max_deg;
    os << r.index << "," << csv_field(r.name) << "," << csv_field(r.path) << "," << r.status << ","
       << (r.exit_code >= 0 ? std::to_string(r.exit_code) : "") << "," << r.mapped << ","
       << shear.str() << "," << fixed(r.seconds, 3) << "," << csv_field(r.outdir) << ","
       << csv_field(files) << "," << csv_field(r.error) << "\n";
  }
  return os.str();
}

/// Starts `plyfit drape` on a scene; false (with r.error set) if the process could not start.
bool launch(SceneRun& r, const fs::path& work) {
  r.staging = (work / r.name).string();
  r.outcome = (work / (r.name + ".outcome.json")).string();
  r.log_out = (work / (r.name + ".stdout")).string();
  r.log_err = (work / (r.name + ".stderr")).string();
  std::vector<std::string> argv_s = {"plyfit",  "drape",   r.path,      "-o",
                                     r.staging, "--quiet", "--outcome", r.outcome};
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, r.log_out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, r.log_err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  r.started = Clock::now();
  const int rc = posix_spawn(&r.pid, "/proc/self/exe", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    r.pid = -1;
    r.status = "error";
    r.error = std::string("cannot start plyfit drape: ") + std::strerror(rc);
    return false;
  }
  return true;
}

/// Records a finished child: publishes its outputs or removes its staging folder.
void finish(SceneRun& r, int wstatus, bool interrupted, const fs::path& outroot) {
  r.seconds = std::chrono::duration<double>(Clock::now() - r.started).count();
  r.pid = -1;
  std::error_code ec;
  int code = -1;
  auto outcome = outcome_from_json(read_text(r.outcome), &code);
  if (WIFEXITED(wstatus)) {
    r.exit_code = WEXITSTATUS(wstatus);
    if (r.exit_code == kExitOk && outcome.ok() &&
        (outcome->status == "ok" || outcome->status == "partial")) {
      const fs::path final_dir = outroot / r.name;
      if (auto st = publish(r, final_dir); !st) {
        r.status = "error";
        r.error = exporters::describe(st.error());
      } else {
        r.status = outcome->status;
        r.mapped = outcome->mapped;
        r.shear_max_deg = outcome->shear_max_deg;
        r.files = outcome->files;
        r.outdir = final_dir.string();
      }
    } else if (r.exit_code == kExitInterrupted || interrupted) {
      r.status = "cancelled";
      r.error = "stopped by an interrupt";
    } else {
      r.status = "error";
      r.error = outcome.ok() && !outcome->error.empty() ? outcome->error
                                                        : last_error_line(read_text(r.log_err));
      if (r.error.empty()) r.error = "plyfit drape exited with code " + std::to_string(r.exit_code);
    }
  } else if (WIFSIGNALED(wstatus)) {
    r.signal = WTERMSIG(wstatus);
    if (interrupted) {
      r.status = "cancelled";
      r.error = "stopped by an interrupt";
    } else {
      r.status = "crashed";
      r.error = "plyfit drape was killed by " + signal_name(r.signal);
    }
  }
  if (fs::exists(r.staging, ec)) fs::remove_all(r.staging, ec);
  for (const auto& f : {r.outcome, r.log_out, r.log_err}) fs::remove(f, ec);
}

void progress_line(std::size_t done, std::size_t total, int failures, double elapsed) {
  std::ostringstream os;
  os << "\rplyfit batch: " << done << "/" << total << " done, " << failures << " failed, "
     << fixed(elapsed, 0) << " s elapsed";
  if (done > 0 && done < total)
    os << ", ~" << fixed(elapsed / static_cast<double>(done) * static_cast<double>(total - done), 0)
       << " s left";
  os << "\033[K";
  std::cerr << os.str() << std::flush;
}

void batch_help(std::ostream& os, const po::options_description& opts) {
  os << "usage: plyfit batch SCENE... [-j N] [-o OUTROOT] [--shard K/N]\n\n"
        "Runs `plyfit drape SCENE` for every scene, N at a time, each in its own process and\n"
        "into OUTROOT/<scene name>/ (the file name without extension; a repeated name gets\n"
        "-2, -3, ...). A failing or crashing scene does not stop the others. Prints a summary\n"
        "table and writes OUTROOT/summary.json and OUTROOT/summary.csv (with --shard K/N:\n"
        "summary-shard-K-of-N.json/.csv). Exit 0 when every scene succeeded (ok or partial),\n"
        "1 otherwise, 130 when interrupted (Ctrl-C: finished scenes keep their outputs,\n"
        "running ones leave nothing, the summary lists them as cancelled or not run).\n\n"
     << opts;
}

int run_batch(const std::vector<std::string>& args) {
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")(
      "jobs,j", po::value<int>(), "scenes run at a time (default: the number of cores)")(
      "output,o", po::value<std::string>()->default_value("batch-out"), "output root folder")(
      "shard", po::value<std::string>(),
      "run only the scenes whose index (0-based, in the given order) mod N is K")(
      "quiet", "no progress line")("scene", po::value<std::vector<std::string>>(), "scene files");
  po::positional_options_description pos;
  pos.add("scene", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("batch: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    batch_help(std::cout, opts);
    return kExitOk;
  }
  if (!vm.count("scene")) {
    print_error("batch: no scene files (plyfit batch SCENE... [-j N] [-o OUTROOT] [--shard K/N])");
    return kExitUsage;
  }
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (vm.count("jobs")) {
    jobs = vm["jobs"].as<int>();
    if (jobs < 1 || jobs > 1024) {
      print_error("batch: -j " + std::to_string(jobs) + ": must be from 1 to 1024");
      return kExitUsage;
    }
  }
  long shard_k = 0, shard_n = 1;
  std::string shard;
  if (vm.count("shard")) {
    shard = vm["shard"].as<std::string>();
    const auto slash = shard.find('/');
    char* end = nullptr;
    bool good = slash != std::string::npos && slash > 0 && slash + 1 < shard.size();
    if (good) {
      shard_k = std::strtol(shard.c_str(), &end, 10);
      good = end == shard.c_str() + slash;
      shard_n = std::strtol(shard.c_str() + slash + 1, &end, 10);
      good = good && *end == '\0' && shard_n >= 1 && shard_k >= 0 && shard_k < shard_n;
    }
    if (!good) {
      print_error("batch: --shard '" + shard + "': must be K/N with 0 <= K < N (e.g. 0/4)");
      return kExitUsage;
    }
  }
  const fs::path outroot = vm["output"].as<std::string>();

  std::vector<SceneRun> all;
  for (const auto& p : vm["scene"].as<std::vector<std::string>>()) {
    SceneRun r;
    r.index = all.size();
    r.path = p;
    all.push_back(std::move(r));
  }
  assign_names(all);  // over the whole list, so that every shard names scenes alike
  std::vector<SceneRun> runs;
  for (auto& r : all)
    if (static_cast<long>(r.index % static_cast<std::size_t>(shard_n)) == shard_k)
      runs.push_back(std::move(r));

  std::error_code ec;
  fs::create_directories(outroot, ec);
  if (ec) {
    print_error("batch: " + outroot.string() +
                ": cannot create the output folder: " + ec.message());
    return kExitFailure;
  }
  const fs::path work = outroot / (".plyfit-batch-" + std::to_string(::getpid()));
  fs::create_directories(work, ec);
  if (ec) {
    print_error("batch: " + work.string() + ": cannot create the work folder: " + ec.message());
    return kExitFailure;
  }

  struct sigaction sa {};
  sa.sa_handler = on_batch_interrupt;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {
  }, old_term{};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);

  const bool tty = !vm.count("quiet") && ::isatty(2);
  const auto t0 = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  std::size_t next = 0, done = 0;
  int failures = 0;
  std::vector<std::size_t> running;
  bool forwarded = false, killed = false;
  Clock::time_point interrupted_at;
  double last_draw = -1.0;
  while (true) {
    const bool interrupted = g_interrupts.load() > 0;
    if (!interrupted) {
      while (static_cast<int>(running.size()) < jobs && next < runs.size()) {
        SceneRun& r = runs[next++];
        if (launch(r, work)) {
          running.push_back(r.index);
        } else {
          ++done;
          ++failures;
        }
      }
    } else if (!forwarded) {
      forwarded = true;
      interrupted_at = Clock::now();
      for (auto& r : runs)
        if (r.pid > 0) ::kill(r.pid, SIGINT);
    }
    if (interrupted && !killed &&
        (g_interrupts.load() > 1 ||
         std::chrono::duration<double>(Clock::now() - interrupted_at).count() >
             kKillGraceSeconds)) {
      killed = true;
      for (auto& r : runs)
        if (r.pid > 0) ::kill(r.pid, SIGKILL);
    }
    if (running.empty() && (interrupted || next >= runs.size())) break;
    int wstatus = 0;
    const pid_t pid = ::waitpid(-1, &wstatus, WNOHANG);
    if (pid > 0) {
      for (auto& r : runs) {
        if (r.pid != pid) continue;
        finish(r, wstatus, interrupted, outroot);
        running.erase(std::remove(running.begin(), running.end(), r.index), running.end());
        ++done;
        if (!succeeded(r)) ++failures;
        break;
      }
      continue;
    }
    if (tty && elapsed() - last_draw >= kProgressRedrawSeconds) {
      last_draw = elapsed();
      progress_line(done, runs.size(), failures, last_draw);
    }
    std::this_thread::sleep_for(kPollInterval);
  }
  if (tty) std::cerr << "\r\033[K" << std::flush;
  fs::remove_all(work, ec);
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  const bool interrupted = g_interrupts.load() > 0;

  print_table(runs, std::cout);
  const auto counts = count_statuses(runs);
  std::cout << "plyfit batch: " << runs.size() << " scenes: " << counts.at("ok") << " ok, "
            << counts.at("partial") << " partial, " << counts.at("error") << " error, "
            << counts.at("crashed") << " crashed, " << counts.at("cancelled") << " cancelled, "
            << counts.at("not run") << " not run; " << fixed(elapsed(), 1) << " s\n";
  const std::string stem =
      shard.empty() ? "summary"
                    : "summary-shard-" + std::to_string(shard_k) + "-of-" + std::to_string(shard_n);
  bool written = true;
  for (const auto& [file, text] :
       {std::pair{outroot / (stem + ".json"),
                  summary_json(runs, outroot.string(), shard, jobs, interrupted, elapsed())},
        std::pair{outroot / (stem + ".csv"), summary_csv(runs)}}) {
    if (auto st = exporters::write_file_atomic(file.string(), text); !st) {
      print_error(exporters::describe(st.error()));
      written = false;
    }
  }
  if (interrupted) return kExitInterrupted;
  const bool all_ok = std::all_of(runs.begin(), runs.end(), succeeded);
  return all_ok && written ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterBatch{
    Command{"batch", "run many scenes in parallel, each into its own folder, with a summary", 30,
            run_batch}};

}  // namespace
}  // namespace plyfit::cli
