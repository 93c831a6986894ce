#pragma once
// plyfit-bench: programs that print figures. Each benchmark is one file that registers a
// subcommand; shared timing helpers and the table type live here. Time figures are medians
// of repeated runs; comparisons are ratios measured in the same run.

#include <plyfit/exporters/format.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace plyfit::bench {

/// Output of a shell command without its trailing newlines, or empty on failure.
inline std::string capture(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) return out;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), buf.size(), p.get())) out += buf.data();
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

/// The plyfit executable the benchmarks run: $PLYFIT_BIN, else the build's, else `plyfit`.
inline std::string plyfit_binary() {
  if (const char* env = std::getenv("PLYFIT_BIN")) return env;
#ifdef PLYFIT_BIN
  return PLYFIT_BIN;
#else
  return "plyfit";
#endif
}

/// User + system CPU seconds of all waited-for child processes so far.
inline double children_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// The machine's cores as the standard library reports them (at least 1).
inline unsigned machine_cores() {
  return std::max(1u, std::thread::hardware_concurrency());
}

/// Runs a shell command, its output discarded: its exit status, -1 if it did not exit.
int run_quiet(const std::string& cmd);

/// One child process, its output discarded: wall seconds, exit code (-1 if it did not exit)
/// and its peak resident set as wait4 reports it, bytes (process.cpp).
struct ProcessRun {
  double seconds = 0.0;
  double max_rss = 0.0;
  int code = -1;
};
/// Runs `args` (args[0] a path) with the environment plus `env` ("NAME=value" each).
ProcessRun run_process(const std::vector<std::string>& args,
                       const std::vector<std::string>& env = {});

/// A plyfit-bench subcommand; `run` gets the arguments after its name and returns the exit
/// code.
struct Benchmark {
  std::string name;
  std::string summary;
  std::function<int(const std::vector<std::string>& args)> run;
};

std::vector<Benchmark>& benchmarks();

/// Registers a subcommand at static-initialisation time.
struct BenchmarkRegistrar {
  explicit BenchmarkRegistrar(Benchmark b) { benchmarks().push_back(std::move(b)); }
};

/// Seconds elapsed running `f` once.
inline double time_once(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(t1 - t0).count();
}

/// Minimum number of timed runs behind every time figure.
constexpr int kMinRuns = 5;

/// Median of a sample (the upper middle one for an even count).
inline double median(std::vector<double> t) {
  if (t.empty()) return 0.0;
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

/// Median of `runs` timings of f (seconds); at least kMinRuns runs.
inline double median_time(const std::function<void()>& f, int runs = kMinRuns) {
  std::vector<double> t;
  for (int i = 0; i < std::max(runs, kMinRuns); ++i) t.push_back(time_once(f));
  return median(t);
}

/// Medians of paired runs: each of max(runs, kMinRuns) rounds calls `round`, which times every
/// one of N arms once, in turn (so that the machine's load falls on all of them alike), and
/// gives their seconds, or nothing when a run failed (then there are no medians).
template <std::size_t N>
std::optional<std::array<double, N>> paired_medians(
    int runs, const std::function<std::optional<std::array<double, N>>()>& round) {
  std::array<std::vector<double>, N> t;
  for (int k = 0; k < std::max(runs, kMinRuns); ++k) {
    const auto seconds = round();
    if (!seconds) return std::nullopt;
    for (std::size_t a = 0; a < N; ++a) t[a].push_back((*seconds)[a]);
  }
  std::array<double, N> m{};
  for (std::size_t a = 0; a < N; ++a) m[a] = median(t[a]);
  return m;
}

/// True if `flag` is among args.
inline bool has_flag(const std::vector<std::string>& args, const std::string& flag) {
  return std::find(args.begin(), args.end(), flag) != args.end();
}

/// The value after `option` in args, or `fallback`.
inline std::string option_value(const std::vector<std::string>& args, const std::string& option,
                                const std::string& fallback) {
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == option) return args[i + 1];
  return fallback;
}

/// printf-style formatting into a std::string (the CLI's formatter).
using exporters::format;

/// A table of formatted cells: printed as Markdown, saved as CSV. `caption` says what was
/// measured and how (printed above the table).
struct Table {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  /// Column alignment in Markdown: true = right-aligned (figures).
  std::vector<bool> right;

  /// Adds a row (as many cells as the header).
  void add(std::vector<std::string> row) { rows.push_back(std::move(row)); }
  /// Adds the row of a case that gave no figures: its name, "-" in the columns between, and
  /// `why` in the last.
  void add_failed(const std::string& name, const std::string& why) {
    std::vector<std::string> row(std::max<std::size_t>(header.size(), 2), "-");
    row.front() = name;
    row.back() = why;
    add(std::move(row));
  }
  /// The caption, an empty line, and the Markdown table.
  std::string markdown() const;
  /// Comma-separated values with a header line (cells quoted when they hold a comma or a
  /// quote).
  std::string csv() const;
};

/// The plyfit binary (plyfit_binary()) if `COMMAND` is in its build (its --help runs); when it
/// is not, nothing, and the caption of `t` says the table was not measured. `*available` (when
/// given) says which.
std::optional<std::string> plyfit_with_command(Table& t, const std::string& command,
                                               bool* available);

/// A path of this process in the temporary folder, `plyfit-bench-NAME-PID`.
std::filesystem::path scratch_path(const std::string& name);

/// Medians of kMinRuns runs of the shell command `cmd` (run quietly), each after `before`
/// (e.g. clearing its output folder): wall seconds and the CPU seconds of the processes it
/// ran; ok false when a run failed.
struct CommandTimes {
  double wall = 0.0, cpu = 0.0;
  bool ok = true;
};
CommandTimes time_command(const std::string& cmd, const std::function<void()>& before);

/// A subcommand that prints one table in Markdown, `make(args, &ok)` (ok starts true): exit
/// code 1 when ok comes back false (a case failed, or the tool the table measures is not
/// there).
Benchmark table_benchmark(
    std::string name, std::string summary,
    std::function<Table(const std::vector<std::string>& args, bool* ok)> make);
/// The same for a table of paired runs, `make(runs, &ok)`: `--runs R` (at least kMinRuns; the
/// summary says so).
Benchmark runs_table_benchmark(std::string name, std::string summary,
                               std::function<Table(int runs, bool* ok)> make);

/// Writes `text` to `path` (creating parent folders); false on failure.
bool write_text_file(const std::string& path, const std::string& text);

}  // namespace plyfit::bench
