// plyfit-bench laminate [--plies N] [--spacing D] [-j J]: `plyfit laminate` on a generated
// laminate of N plies (0/45/-45/90 in turn) on a real CAD file (trj7_c2-td-203.stp face 2, a
// strongly doubly curved panel), at -j 1 and -j J (default: the cores) in pairs of runs. The
// plies' own time is the -j 1 run's wall less its one import (everything a ply costs: drape,
// flat pattern, outputs, one after another in one process); the bound is
// wall(-j J) <= 1.3 x (that sum / J) + one import.

#include <plyfit/exporters/atomic_file.hpp>

#include "bench.hpp"
#include "drape_cases.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace plyfit::bench {

namespace {

namespace fs = std::filesystem;

constexpr int kDefaultPlies = 40;
constexpr double kDefaultSpacing = 4.0;
// The factor on the ideal parallel time.
constexpr double kBoundFactor = 1.3;

std::string laminate_text(const std::string& mold, int plies, double spacing) {
  std::string s = format(
      "# plyfit-bench laminate\n[laminate]\nmold = %s\nface = 2\nseed = 150,600,260\n"
      "rosette = 1,0,0\nspacing = %.3f\nroll-width = 1500\n",
      mold.c_str(), spacing);
  const int angles[] = {0, 45, -45, 90};
  for (int k = 0; k < plies; ++k) s += format("\n[ply P%02d]\nangle = %d\n", k + 1, angles[k % 4]);
  return s;
}

// The import time (ms) the plies' reports give (one import: every ply reports it).
double import_ms(const fs::path& out) {
  const auto report = exporters::read_file((out / "P01" / "report.json").string());
  return nlohmann::json::parse(report.value_or("")).at("timing_ms").at("import").get<double>();
}

int run_laminate_bench(const std::vector<std::string>& args) {
  const int plies = std::stoi(option_value(args, "--plies", std::to_string(kDefaultPlies)));
  const double spacing = std::stod(option_value(args, "--spacing", format("%g", kDefaultSpacing)));
  const unsigned cores = machine_cores();
  const unsigned jobs =
      static_cast<unsigned>(std::stoi(option_value(args, "-j", std::to_string(cores))));
  const std::string mold = shared_dir() + "/cad/trj7_c2-td-203.stp";
  if (!fs::exists(mold)) {
    std::fprintf(stderr, "laminate: %s is missing\n", mold.c_str());
    return 1;
  }
  const fs::path dir = scratch_path("laminate");
  fs::create_directories(dir);
  const fs::path file = dir / "laminate.ini";
  write_text_file(file.string(), laminate_text(mold, plies, spacing));
  const std::string bin = plyfit_binary();
  std::vector<double> wall1, wallj, imports;
  bool ok = true;
  for (int r = 0; r < kMinRuns; ++r) {
    for (const unsigned j : {1u, jobs}) {
      const fs::path out = dir / format("out-j%u", j);
      fs::remove_all(out);
      const std::string cmd = format("'%s' laminate '%s' -o '%s' -j %u --quiet >/dev/null 2>&1",
                                     bin.c_str(), file.string().c_str(), out.string().c_str(), j);
      const double sec = time_once([&] { ok = ok && std::system(cmd.c_str()) == 0; });
      (j == 1 ? wall1 : wallj).push_back(sec);
      imports.push_back(import_ms(out) / 1000.0);
    }
  }
  fs::remove_all(dir);
  if (!ok) {
    std::fprintf(stderr, "laminate: plyfit laminate failed\n");
    return 1;
  }
  const double w1 = median(wall1), wj = median(wallj), imp = median(imports);
  const double plies_s = w1 - imp, bound = kBoundFactor * plies_s / jobs + imp;
  Table t;
  t.caption = format(
      "`plyfit laminate` on %d plies (0/45/-45/90) on trj7_c2-td-203.stp face 2, spacing %g mm, "
      "every output; medians of %d paired runs (-j 1, -j %u). Plies' time: the -j 1 wall less "
      "its one import. Bound: %.1f x plies' time / %u + import.",
      plies, spacing, kMinRuns, jobs, kBoundFactor, jobs);
  t.header = {"import (s)", "wall -j 1 (s)", "plies' time (s)", format("wall -j %u (s)", jobs),
              "bound (s)",  "wall / bound"};
  t.right = {true, true, true, true, true, true};
  t.add({format("%.2f", imp), format("%.2f", w1), format("%.2f", plies_s), format("%.2f", wj),
         format("%.2f", bound), format("%.2f", wj / bound)});
  std::printf("%s", t.markdown().c_str());
  return wj <= bound ? 0 : 1;
}

const BenchmarkRegistrar kLaminate{
    {"laminate", "plyfit laminate -j 1 against -j N: wall time against the plies' time / N",
     run_laminate_bench}};

}  // namespace

}  // namespace plyfit::bench
