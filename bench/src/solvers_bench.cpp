// plyfit-bench solvers: the three mapping solvers on a bicubic and a rational surface:
// mean iterations and surface evaluations, ns per solve (median of runs), and the
// distribution of final residuals (|F1| + |F2|) / d.

#include <plyfit/exporters/messages.hpp>
#include "drape/solvers/solvers.hpp"
#include "geometry/analytic_surfaces.hpp"

#include "bench.hpp"
#include "support/solver_cases.hpp"
#include "tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace plyfit::bench {
namespace {

NurbsSurfaceData random_bicubic() {
  std::mt19937_64 gen(31);
  std::uniform_real_distribution<double> h(-12, 12);
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 3;
  s.count_u = s.count_v = 9;
  const std::vector<double> k = {0, 0, 0, 0, 0.2, 0.35, 0.5, 0.7, 0.85, 1, 1, 1, 1};
  s.knots_u = s.knots_v = k;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) s.poles.emplace_back(12.5 * i, 12.5 * j, h(gen));
  return s;
}

struct Row {
  std::string surface, solver;
  int solves = 0, converged = 0;
  double mean_it = 0, mean_eval = 0, ns = 0;
  double r50 = 0, r99 = 0, rmax = 0;
  int hist[5] = {};  // residual/d: <1e-15, <1e-14, <1e-13, <1e-12, >=1e-12
};

template <class Solve>
Row measure(const std::string& surface, const std::string& solver, int n, double d, Solve&& solve) {
  Row row{surface, solver};
  std::vector<double> res;
  long it = 0, ev = 0;
  for (int i = 0; i < n; ++i) {
    const SolveResult r = solve(i);
    ++row.solves;
    if (r.status != SolveStatus::kConverged) continue;
    ++row.converged;
    it += r.iterations;
    ev += r.evaluations;
    const double q = r.residual / d;
    res.push_back(q);
    row.hist[q < 1e-15 ? 0 : q < 1e-14 ? 1 : q < 1e-13 ? 2 : q < 1e-12 ? 3 : 4]++;
  }
  std::sort(res.begin(), res.end());
  if (!res.empty()) {
    row.r50 = res[res.size() / 2];
    row.r99 = res[std::min(res.size() - 1, res.size() * 99 / 100)];
    row.rmax = res.back();
  }
  row.mean_it = row.converged ? double(it) / row.converged : 0;
  row.mean_eval = row.converged ? double(ev) / row.converged : 0;
  volatile double sink = 0;
  const double t = median_time(
      [&] {
        for (int i = 0; i < n; ++i) sink = sink + solve(i).point.x();
      },
      7);
  row.ns = t / n * 1e9;
  return row;
}

bool run_rows(std::vector<Row>& rows) {
  const int n = 4000;
  struct Surf {
    std::string name;
    NurbsSurfaceData data;
    double d;
  };
  const std::vector<Surf> surfs = {
      {"bicubic 9x9", random_bicubic(), 1.0},
      {"rational torus", torus_patch(30.0, 10.0, -2.5, 2.5, 0.0, 4.0), 1.0}};
  for (const auto& sf : surfs) {
    FaceData fd;
    fd.surface = sf.data;
    auto face = Face::create(fd);
    if (!face) {
      std::fprintf(stderr, "plyfit-bench: %s\n", exporters::describe(face.error()).c_str());
      return false;
    }
    const Face& f = *face;
    SolverSettings st;
    st.spacing = sf.d;
    const auto cases = support::make_solver_cases(f, sf.d, n, 77);
    const int m = static_cast<int>(cases.size());
    rows.push_back(measure(sf.name, "1 base path", m, sf.d, [&](int i) {
      const auto& k = cases[i];
      return solve_base_path(f, {k.c, k.uc, k.plane_normal, k.travel, sf.d}, st);
    }));
    rows.push_back(measure(sf.name, "2 two spheres (parallelogram guess)", m, sf.d, [&](int i) {
      const auto& k = cases[i];
      return solve_two_spheres(f, {k.a, k.ua, sf.d, k.b, k.ub, sf.d, k.side, k.guess}, st);
    }));
    rows.push_back(measure(sf.name, "2 two spheres (planar guess)", m, sf.d, [&](int i) {
      const auto& k = cases[i];
      return solve_two_spheres(f, {k.a, k.ua, sf.d, k.b, k.ub, sf.d, k.side, std::nullopt}, st);
    }));
    rows.push_back(measure(sf.name, "3 plane and sphere", m, sf.d, [&](int i) {
      const auto& k = cases[i];
      return solve_plane_sphere(f, {k.c, k.uc, sf.d, k.a - k.c}, st);
    }));
  }
  return true;
}

Table make_table(const std::vector<Row>& rows) {
  Table t;
  t.caption =
      "Solves of independently built configurations (tests/support/solver_cases.hpp), d = 1; "
      "ns/solve: median of 7 runs over all cases; residual (|F1| + |F2|) / d of the converged "
      "solves: percentiles and histogram";
  t.header = {
      "surface",        "solver", "converged", "mean iterations", "mean evaluations", "ns/solve",
      "residual/d p50", "p99",    "max",       "<1e-15",          "<1e-14",           "<1e-13",
      "<1e-12",         ">=1e-12"};
  t.right = {false, false, true, true, true, true, true, true, true, true, true, true, true, true};
  for (const auto& r : rows)
    t.add({r.surface, r.solver, format("%d/%d", r.converged, r.solves), format("%.2f", r.mean_it),
           format("%.2f", r.mean_eval), format("%.0f", r.ns), format("%.1e", r.r50),
           format("%.1e", r.r99), format("%.1e", r.rmax), format("%d", r.hist[0]),
           format("%d", r.hist[1]), format("%d", r.hist[2]), format("%d", r.hist[3]),
           format("%d", r.hist[4])});
  return t;
}

int run(const std::vector<std::string>& args) {
  const bool json = has_flag(args, "--json");
  std::vector<Row> rows;
  if (!run_rows(rows)) return 1;
  if (json) {
    std::printf("{\"cases\": [\n");
    for (size_t i = 0; i < rows.size(); ++i) {
      const auto& r = rows[i];
      std::printf(
          "  {\"surface\": \"%s\", \"solver\": \"%s\", \"solves\": %d, \"converged\": %d, "
          "\"mean_iterations\": %.3f, \"mean_evaluations\": %.3f, \"ns_per_solve\": %.1f, "
          "\"residual_rel_p50\": %.3g, \"residual_rel_p99\": %.3g, \"residual_rel_max\": %.3g}%s\n",
          r.surface.c_str(), r.solver.c_str(), r.solves, r.converged, r.mean_it, r.mean_eval, r.ns,
          r.r50, r.r99, r.rmax, i + 1 < rows.size() ? "," : "");
    }
    std::printf("]}\n");
    return 0;
  }
  std::printf("%s", make_table(rows).markdown().c_str());
  return 0;
}

const BenchmarkRegistrar kRegister{
    {"solvers", "the three mapping solvers: iterations, ns per solve, residuals [--json]", run}};

}  // namespace

Table solvers_table() {
  std::vector<Row> rows;
  if (!run_rows(rows)) return {};
  return make_table(rows);
}

}  // namespace plyfit::bench
