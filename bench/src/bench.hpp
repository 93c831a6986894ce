#pragma once
// plyfit-bench: programs that print figures. Each benchmark is one file that registers a
// subcommand; shared timing helpers live here. Time figures are medians of repeated runs;
// comparisons are ratios measured in the same run.

#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace plyfit::bench {

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

/// Median of `runs` timings of f (seconds); at least 5 runs.
inline double median_time(const std::function<void()>& f, int runs = 5) {
  std::vector<double> t;
  for (int i = 0; i < std::max(runs, 5); ++i) t.push_back(time_once(f));
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

/// True if `flag` is among args.
inline bool has_flag(const std::vector<std::string>& args, const std::string& flag) {
  return std::find(args.begin(), args.end(), flag) != args.end();
}

}  // namespace plyfit::bench
