#include "commands/batch_runner.hpp"

#include "commands/commands.hpp"
#include "job/outcome.hpp"
#include "report/text_format.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

extern char** environ;

namespace plyfit::cli {

namespace {

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

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A child's file, empty when there is none.
std::string read_text(const std::string& path) {
  return exporters::read_file(path).value_or("");
}

/// Last non-empty line of a child's stderr (progress lines, with '\r', skipped).
std::string last_line(const std::string& text) {
  std::istringstream ss(text);
  std::string line, last;
  while (std::getline(ss, line))
    if (!line.empty() && line.find('\r') == std::string::npos) last = line;
  return last;
}

void set_error(SceneRun& r, const Error& e) {
  r.error = exporters::describe(e);
  r.error_code = to_string(e.code);
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
      return Error{ErrorCode::kFolderHoldsOtherFiles, final_dir.string()};
    fs::remove_all(final_dir, ec);
    if (ec) return Error{ErrorCode::kCannotMoveOutputs, final_dir.string(), {ec.message()}};
  }
  fs::rename(r.staging, final_dir, ec);
  if (ec) return Error{ErrorCode::kCannotMoveOutputs, final_dir.string(), {ec.message()}};
  return ok_status();
}

/// Starts `plyfit drape` on a scene; false (with the error set) if the process could not start.
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
    set_error(r, Error{ErrorCode::kCannotStartDrape, "", {std::string(std::strerror(rc))}});
    return false;
  }
  return true;
}

/// A child that exited: its outputs published when it succeeded, else its error (from its
/// outcome file, or the last line it printed when it left none).
void record_exit(SceneRun& r, bool interrupted, const fs::path& outroot) {
  int code = -1;
  auto outcome = outcome_from_json(read_text(r.outcome), &code);
  if (r.exit_code == kExitOk && outcome.ok() &&
      (outcome->status == "ok" || outcome->status == "partial")) {
    const fs::path final_dir = outroot / r.name;
    r.status = "error";
    if (auto st = publish(r, final_dir); !st) return set_error(r, st.error());
    r.status = outcome->status;
    r.mapped = outcome->mapped;
    r.shear_max_deg = outcome->shear_max_deg;
    r.files = outcome->files;
    r.outdir = final_dir.string();
  } else if (r.exit_code == kExitInterrupted || interrupted) {
    r.status = "cancelled";
    set_error(r, Error{ErrorCode::kInterrupted});
  } else if (outcome.ok() && !outcome->error.empty()) {
    r.status = "error";
    r.error = outcome->error;
    r.error_code = outcome->error_code;
  } else {
    r.status = "error";
    set_error(r, Error{ErrorCode::kDrapeNoOutcome,
                       "",
                       {std::int64_t{r.exit_code}, last_line(read_text(r.log_err))}});
  }
}

/// Records a finished child and removes its staging folder and files.
void finish(SceneRun& r, int wstatus, bool interrupted, const fs::path& outroot) {
  r.seconds = seconds_since(r.started);
  r.pid = -1;
  if (WIFEXITED(wstatus)) {
    r.exit_code = WEXITSTATUS(wstatus);
    record_exit(r, interrupted, outroot);
  } else if (WIFSIGNALED(wstatus)) {
    r.signal = WTERMSIG(wstatus);
    r.status = interrupted ? "cancelled" : "crashed";
    const char* d = strsignal(r.signal);
    set_error(r, interrupted ? Error{ErrorCode::kInterrupted}
                             : Error{ErrorCode::kDrapeCrashed,
                                     "",
                                     {std::int64_t{r.signal}, std::string(d ? d : "")}});
  }
  std::error_code ec;
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

/// The children of a batch: started while slots are free, reaped as they end, stopped on an
/// interrupt.
class Pool {
 public:
  Pool(std::vector<SceneRun>& runs, int jobs, const fs::path& outroot, const fs::path& work,
       bool tty)
      : runs_(runs), jobs_(jobs), outroot_(outroot), work_(work), tty_(tty) {}

  void run() {
    while (true) {
      const bool interrupted = g_interrupts.load() > 0;
      if (!interrupted)
        start_scenes();
      else
        stop_children();
      if (running_.empty() && (interrupted || next_ >= runs_.size())) break;
      if (reap(interrupted)) continue;
      draw();
      std::this_thread::sleep_for(kPollInterval);
    }
    if (tty_) std::cerr << "\r\033[K" << std::flush;
  }

 private:
  void start_scenes() {
    while (static_cast<int>(running_.size()) < jobs_ && next_ < runs_.size()) {
      SceneRun& r = runs_[next_++];
      if (launch(r, work_)) {
        running_.push_back(r.index);
      } else {
        ++done_;
        ++failures_;
      }
    }
  }

  // SIGINT to every child at the first interrupt; SIGKILL after the grace time or a second.
  void stop_children() {
    if (!forwarded_) {
      forwarded_ = true;
      interrupted_at_ = Clock::now();
      signal_children(SIGINT);
    }
    if (!killed_ &&
        (g_interrupts.load() > 1 || seconds_since(interrupted_at_) > kKillGraceSeconds)) {
      killed_ = true;
      signal_children(SIGKILL);
    }
  }

  void signal_children(int sig) {
    for (auto& r : runs_)
      if (r.pid > 0) ::kill(r.pid, sig);
  }

  // A child that ended, if any.
  bool reap(bool interrupted) {
    int wstatus = 0;
    const pid_t pid = ::waitpid(-1, &wstatus, WNOHANG);
    if (pid <= 0) return false;
    for (auto& r : runs_) {
      if (r.pid != pid) continue;
      finish(r, wstatus, interrupted, outroot_);
      running_.erase(std::remove(running_.begin(), running_.end(), r.index), running_.end());
      ++done_;
      if (!succeeded(r)) ++failures_;
      break;
    }
    return true;
  }

  void draw() {
    if (!tty_ || seconds_since(t0_) - last_draw_ < kProgressRedrawSeconds) return;
    last_draw_ = seconds_since(t0_);
    progress_line(done_, runs_.size(), failures_, last_draw_);
  }

  std::vector<SceneRun>& runs_;
  const int jobs_;
  const fs::path outroot_, work_;
  const bool tty_;
  const Clock::time_point t0_ = Clock::now();
  std::size_t next_ = 0, done_ = 0;
  int failures_ = 0;
  std::vector<std::size_t> running_;
  bool forwarded_ = false, killed_ = false;
  Clock::time_point interrupted_at_;
  double last_draw_ = -1.0;
};

}  // namespace

bool succeeded(const SceneRun& s) {
  return s.status == "ok" || s.status == "partial";
}

bool run_scenes(std::vector<SceneRun>& runs, int jobs, const fs::path& outroot,
                const fs::path& work, bool progress) {
  {
    const CatchInterrupts interrupts(on_batch_interrupt);
    Pool(runs, jobs, outroot, work, progress && ::isatty(2)).run();
    std::error_code ec;
    fs::remove_all(work, ec);
  }
  return g_interrupts.load() > 0;
}

}  // namespace plyfit::cli
