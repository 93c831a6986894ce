// plyfit-bench boundary [--runs R]: a drape with a ply boundary against the same drape without
// one (issue 29: at most 1.2x), per mapped node: the mold restricted by bound_mold() (timed
// with the drape), the drape and the flat pattern, medians of R >= 5 runs interleaved.

#include "bench.hpp"
#include "tables.hpp"

#include <plyfit/kernel/boundary.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include "support/boundary_curves.hpp"

#include <cmath>
#include <iostream>

namespace plyfit::bench {

namespace {

struct BoundaryCase {
  std::string name;
  Result<MoldSurface> mold = Error{ErrorCode::kInternal};
  PlyBoundary boundary;
  Vec3 seed;
  double d = 0.25;
};

std::vector<BoundaryCase> boundary_cases() {
  std::vector<BoundaryCase> out;
  {
    BoundaryCase c;
    c.name = "plate 100 x 60, circle r = 20 (720 points), d = 0.1";
    auto fd = builtin_mold("plate", {});
    if (fd) c.mold = MoldSurface::from_face(*fd);
    c.boundary.curves = {
        support::circle_curve([](double x, double y) { return Vec3(x, y, 0); }, 50, 30, 20, 720)};
    c.seed = Vec3(50, 30, 0);
    c.d = 0.1;
    out.push_back(std::move(c));
  }
  {
    BoundaryCase c;
    c.name = "flange-fillet-wall, development circle r = 25 (1440 points), d = 0.2";
    auto sd = builtin_shell("flange-fillet-wall", {});
    if (sd) c.mold = MoldSurface::from_shell(*sd);
    const double q = 0.5 * kPi * 10.0;  // the fillet's arc
    c.boundary.curves = {
        support::circle_curve(support::flange_fillet_wall_at, 0.5 * q, 30, 25, 1440)};
    c.seed = support::flange_fillet_wall_at(0.5 * q, 30);
    c.d = 0.2;
    out.push_back(std::move(c));
  }
  return out;
}

// Drape and flat pattern of the ply from the seed; the mapped node count.
std::uint64_t drape_ply(const MoldSurface& m, const Vec3& seed, double d) {
  PlyDefinition def;
  def.seed = seed;
  PlySpec cloth;
  cloth.d_weft = cloth.d_warp = d;
  auto pb = ply_problem(m, def, cloth);
  if (!pb) return 0;
  auto r = drape(m, *pb, DrapeOptions{});
  if (!r) return 0;
  const FlatPattern f = flat_pattern(m, *r);
  return f.outline.empty() ? 0 : r->metrics.nodes.mapped;
}

Table boundary_table(int runs, bool* ok) {
  Table t;
  t.caption =
      "A drape with a ply boundary against the same drape without one: wall time per "
      "mapped node of bound_mold() + drape() + flat_pattern() against drape() + "
      "flat_pattern() on the whole mold, medians of " +
      std::to_string(std::max(runs, kMinRuns)) +
      " runs each, interleaved; ratio = with / without (target <= 1.20).";
  t.header = {"case",         "nodes without", "nodes with", "bound_mold ms", "without ns/node",
              "with ns/node", "ratio"};
  t.right = {false, true, true, true, true, true, true};
  for (BoundaryCase& c : boundary_cases()) {
    if (!c.mold) {
      *ok = false;
      t.add_failed(c.name, "no mold");
      continue;
    }
    std::uint64_t n0 = 0, n1 = 0;
    // Without, bound_mold() alone, and with (bound_mold() + the drape of the bounded mold).
    const auto m = paired_medians<3>(runs, [&]() -> std::optional<std::array<double, 3>> {
      const double whole = time_once([&] { n0 = drape_ply(*c.mold, c.seed, c.d); });
      Result<BoundedMold> b = Error{ErrorCode::kInternal};
      const double bound = time_once([&] { b = bound_mold(*c.mold, c.boundary, c.seed); });
      if (!b) return std::nullopt;
      return std::array{whole, bound,
                        bound + time_once([&] { n1 = drape_ply(b->surface, c.seed, c.d); })};
    });
    if (!m || n0 == 0 || n1 == 0) {
      *ok = false;
      t.add_failed(c.name, "failed");
      continue;
    }
    const auto [whole, bound, with] = *m;
    const double a = whole / static_cast<double>(n0) * 1e9;
    const double w = with / static_cast<double>(n1) * 1e9;
    t.add({c.name, std::to_string(n0), std::to_string(n1), format("%.1f", bound * 1e3),
           format("%.0f", a), format("%.0f", w), format("%.2f", w / a)});
  }
  return t;
}

const BenchmarkRegistrar kBoundary{runs_table_benchmark(
    "boundary", "a drape with a ply boundary against one without, per node", boundary_table)};

}  // namespace

}  // namespace plyfit::bench
