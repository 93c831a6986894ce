// plyfit-bench profile: where the drape's time goes. `perf record` samples
// `plyfit-bench profile-drape` (drapes of the bicubic face at about 1000^2 nodes) and the
// samples are summed by function into the parts of the drape.

#include "bench.hpp"
#include "drape_cases.hpp"
#include "tables.hpp"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <sstream>

namespace plyfit::bench {

namespace {

// Drapes per profile and their size (nodes per side).
constexpr int kProfileDrapes = 3;
constexpr int kProfileSize = 1000;
// perf's sampling frequency (Hz).
constexpr int kPerfFrequency = 4000;

int run_profile_drape(const std::vector<std::string>&) {
  auto f = builtin_face("wave", {});
  if (!f) return 1;
  const double d = spacing_for_nodes(**f, double(kProfileSize) * kProfileSize);
  auto pb = middle_problem(**f, d, true);
  if (!pb) return 1;
  for (int k = 0; k < kProfileDrapes; ++k) {
    auto r = drape(**f, *pb, {});
    if (!r) return 1;
  }
  return 0;
}

// The part of the drape a sampled function belongs to.
std::string category(const std::string& sym) {
  static const std::vector<std::pair<std::regex, std::string>> rules = {
      {std::regex("\\[k\\]"), "operating system (page faults of growing vectors, ...)"},
      {std::regex("eval_fixed|eval_homogeneous|NurbsSurface::eval|NurbsSurface::point|"
                  "Face::eval|Face::wrap|ders_basis|find_span"),
       "surface evaluation"},
      {std::regex("newton|solve_two_spheres|solve_plane_sphere|plane_sphere_core|solve_base_path|"
                  "two_sphere_guess|classify_converged|face_normal|is_degenerate|"
                  "metric_direction|Face::delta|Face::contains|uv_direction|residual_tolerance"),
       "Newton solvers (without evaluation)"},
      {std::regex("compute_metrics|thread_angles|cell_areas|for_each_mapped_cell|links|"
                  "cell_parts|net_links|for_each_link"),
       "metrics"},
      {std::regex("Scanner|NodeIndex|Ply::|heap|priority_queue|node_for|push_neighbours"),
       "scan: frontier, node creation, index"},
      {std::regex("atan2|__cos|__sin|sqrt|libm"), "libm (atan2 for thread angles, sin, cos)"},
      {std::regex("malloc|free|memcpy|memmove|memset|operator new|operator delete"),
       "allocation and copies"},
  };
  for (const auto& [re, name] : rules)
    if (std::regex_search(sym, re)) return name;
  return "other";
}

}  // namespace

Table profile_table(bool* available) {
  Table t;
  t.caption = format(
      "Where the time of a drape goes: `perf record -F %d` over %d drapes of the bicubic face "
      "at about %d^2 nodes (`plyfit-bench profile-drape`), self time of each function summed "
      "by part (inlined functions count in their callers).",
      kPerfFrequency, kProfileDrapes, kProfileSize);
  t.header = {"part", "share of samples", "main functions"};
  t.right = {false, true, false};
  char self[4096] = {};
  const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
  const std::string data = scratch_path("perf").string() + ".data";
  if (n <= 0 ||
      std::system(format("perf record -q -F %d -o '%s' '%s' profile-drape >/dev/null 2>&1",
                         kPerfFrequency, data.c_str(), self)
                      .c_str()) != 0) {
    if (available) *available = false;
    t.caption += " Not measured: perf record failed here.";
    return t;
  }
  const std::string rep = capture(format(
      "perf report -i '%s' --stdio --no-children --sort dso,symbol 2>/dev/null", data.c_str()));
  std::filesystem::remove(data);
  std::map<std::string, double> share;
  std::map<std::string, std::vector<std::pair<double, std::string>>> top;
  std::istringstream is(rep);
  std::string line;
  static const std::regex row("^\\s*([0-9.]+)%\\s+(\\S+)\\s+(\\[.\\])\\s+(.*)$");
  double total = 0.0;
  while (std::getline(is, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    const double pct = std::stod(m[1]);
    const std::string sym = m[3].str() + " " + m[4].str().substr(0, m[4].str().find("  "));
    // perf pads the symbol column (and may add more columns after it).
    std::string name = m[4].str().substr(0, m[4].str().find("  "));
    // Shorten C++ names: drop the namespaces, return types, argument and template lists.
    name = std::regex_replace(name, std::regex("\\(anonymous namespace\\)::|plyfit::|bench::"), "");
    name = std::regex_replace(name, std::regex("\\(.*"), "");
    name = std::regex_replace(name, std::regex("^(void|bool|int|double) "), "");
    name = std::regex_replace(name, std::regex("<.*"), "<>");
    if (name.size() > 40) name = name.substr(0, 37) + "...";
    const std::string c = category(sym);
    share[c] += pct;
    top[c].push_back({pct, name});
    total += pct;
  }
  if (total <= 0.0) {
    if (available) *available = false;
    t.caption += " Not measured: no samples in perf's report.";
    return t;
  }
  if (available) *available = true;
  std::vector<std::pair<double, std::string>> parts;
  for (const auto& [c, s] : share) parts.push_back({s, c});
  std::sort(parts.rbegin(), parts.rend());
  for (const auto& [s, c] : parts) {
    auto& v = top[c];
    std::sort(v.rbegin(), v.rend());
    std::string names;
    for (std::size_t k = 0; k < std::min<std::size_t>(3, v.size()); ++k)
      names += format("%s%s %.1f%%", k ? ", " : "", v[k].second.c_str(), v[k].first);
    t.add({c, format("%.1f%%", 100.0 * s / total), names});
  }
  return t;
}

namespace {

const BenchmarkRegistrar kProfileDrape{
    {"profile-drape", "drapes to be profiled (the bicubic face at 1000^2 nodes, 3 times)",
     run_profile_drape}};
const BenchmarkRegistrar kProfile{
    table_benchmark("profile", "where the drape's time goes (perf record, by part)",
                    [](const std::vector<std::string>&, bool* ok) { return profile_table(ok); })};

}  // namespace

}  // namespace plyfit::bench
