// plyfit-bench shell-drape [--runs R]: a drape over a shell of N faces against the same
// surface as one face (issue 12: within 20 % per node). The same problem on both, medians of
// R >= 5 runs interleaved, per mapped node; the two nets are compared node for node.

#include "bench.hpp"
#include "tables.hpp"

#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "surface/shell/shell.hpp"

#include "support/problems.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace plyfit::bench {

namespace {

struct ShellCase {
  std::string name;
  std::unique_ptr<DrapeSurface> one, many;
  DrapeProblem problem;
};

std::unique_ptr<DrapeSurface> face_of(Result<FaceData> fd) {
  if (!fd) return nullptr;
  auto f = Face::create(std::move(fd).value());
  return f ? std::make_unique<Face>(std::move(f).value()) : nullptr;
}

std::unique_ptr<DrapeSurface> shell_of(const std::string& name,
                                       const std::map<std::string, double>& params) {
  auto data = builtin_shell(name, params);
  if (!data) return nullptr;
  auto sh = Shell::create(std::move(data).value());
  return sh ? std::make_unique<Shell>(std::move(sh).value()) : nullptr;
}

std::vector<ShellCase> shell_cases() {
  std::vector<ShellCase> out;
  {
    // The sphere R = 20: one face (closed, poles) against 8 octants; a 30 x 30 ply started
    // where three octants meet (tests/kernel/shell_test.cpp).
    ShellCase c;
    c.name = "sphere R = 20: 1 face / sphere-8 (8 faces)";
    FaceData fd;
    fd.surface = sphere_patch(20.0, -kPi / 2, kPi / 2, 0.0, 2 * kPi);
    fd.closed_v = true;
    c.one = face_of(Result<FaceData>(std::move(fd)));
    c.many = shell_of("sphere-8", {{"R", 20.0}});
    const Vec3 s3 = Vec3(1, 1, 1).normalized() * 20.0;
    c.problem = support::problem(0.05, Vec2(15, 15), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, s3,
                                 Vec3(1, -1, 0).normalized().cross(s3).normalized(),
                                 {Vec3(0, 0, 1), Vec3(0, 0, -1)});
    c.problem.ply.rect = Vec2(30, 30);
    out.push_back(std::move(c));
  }
  for (const int parts : {2, 8}) {
    // The full cylinder R = 10, H = 20 as one face (seam) against `parts` faces; threads at
    // about 29 degrees to the axis.
    ShellCase c;
    c.name = format("cylinder R = 10: 1 face / cylinder-split (%d faces)", parts);
    c.one = face_of(builtin_mold("cylinder", {{"R", 10}, {"H", 20}, {"angle", 360}}));
    c.many = shell_of("cylinder-split", {{"angle", 360}, {"parts", parts}});
    c.problem =
        support::problem(0.05, Vec2(0, 0), Vec2(std::cos(0.5), std::sin(0.5)),
                         {Vec2(-std::sin(0.5), std::cos(0.5)), Vec2(std::sin(0.5), -std::cos(0.5))},
                         Vec3(10 * std::cos(1.4), 10 * std::sin(1.4), 10), Vec3(0, 0, 1),
                         {Vec3(0, 0, 1), Vec3(0, 0, -1)});
    out.push_back(std::move(c));
  }
  return out;
}

// How far two nets with the same nodes differ: nodes whose status differs (or that only one
// reached), and the largest distance between mapped nodes of both.
struct NetDifference {
  std::size_t status = 0;
  double distance = 0.0;
};
NetDifference net_difference(const DrapeResult& a, const DrapeResult& b) {
  NetDifference out;
  out.status = a.nodes.size() > b.nodes.size() ? a.nodes.size() - b.nodes.size()
                                               : b.nodes.size() - a.nodes.size();
  for (const DrapeNode& x : a.nodes) {
    const DrapeNode* y = b.find(x.id);
    if (!y || y->status != x.status) {
      ++out.status;
    } else if (x.mapped()) {
      out.distance = std::max(out.distance, (x.point - y->point).norm());
    }
  }
  return out;
}

}  // namespace

Table shell_drape_table(int runs, double* worst_ratio, bool* ok) {
  Table t;
  t.caption =
      "Drapes over a shell of N faces against the same surface as one face: the same problem, "
      "wall time of drape() per mapped node, median of " +
      std::to_string(std::max(runs, kMinRuns)) +
      " runs each, the two interleaved run by run; ratio = N faces / 1 face (target <= 1.20). "
      "The two nets compared node for node: nodes whose status differs, and the largest distance "
      "between a node mapped on both (tests/kernel/shell_test.cpp holds it to 1e-9 d on plies of "
      "about 1000 nodes; here rounding accumulates over 1000 links and more).";
  t.header = {"surface",
              "nodes",
              "1 face ns/node",
              "N faces ns/node",
              "ratio",
              "nodes of another status",
              "largest node distance / d"};
  t.right = {false, true, true, true, true, true, true};
  double worst = 0.0;
  for (ShellCase& c : shell_cases()) {
    if (!c.one || !c.many) {
      *ok = false;
      t.add({c.name, "-", "-", "-", "-", "could not build"});
      continue;
    }
    std::vector<double> t1, tn;
    Result<DrapeResult> r1 = drape(*c.one, c.problem), rn = drape(*c.many, c.problem);
    if (!r1 || !rn) {
      *ok = false;
      t.add({c.name, "-", "-", "-", "-", "drape failed"});
      continue;
    }
    for (int k = 0; k < std::max(runs, kMinRuns); ++k) {
      t1.push_back(time_once([&] { r1 = drape(*c.one, c.problem); }));
      tn.push_back(time_once([&] { rn = drape(*c.many, c.problem); }));
    }
    const double n1 = static_cast<double>(std::max<std::uint64_t>(1, r1->metrics.nodes.mapped));
    const double nn = static_cast<double>(std::max<std::uint64_t>(1, rn->metrics.nodes.mapped));
    const double a = median(t1) / n1 * 1e9, b = median(tn) / nn * 1e9;
    const NetDifference diff = net_difference(*r1, *rn);
    worst = std::max(worst, b / a);
    t.add({c.name, std::to_string(rn->metrics.nodes.mapped), format("%.0f", a), format("%.0f", b),
           format("%.2f", b / a), format("%zu", diff.status),
           format("%.1e", diff.distance / c.problem.ply.d_weft)});
  }
  if (worst_ratio) *worst_ratio = worst;
  return t;
}

namespace {

const BenchmarkRegistrar kShellDrape{runs_table_benchmark(
    "shell-drape", "a drape over N faces against one face, per node", [](int runs, bool* ok) {
      double worst = 0.0;
      return shell_drape_table(runs, &worst, ok);
    })};

}  // namespace

}  // namespace plyfit::bench
