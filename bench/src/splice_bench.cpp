// plyfit-bench splices [--runs R]: a drape and its flat pattern split for the roll against the
// same without splices (issue 31: the splices cost at most 3 drapes of the ply), medians of
// R >= 5 paired runs: drape() + flat_pattern() against drape() + flat_pattern() +
// splice_pattern(), the ply 2.5 roll widths wide (3 pieces).

#include "bench.hpp"
#include "tables.hpp"

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/ply_definition.hpp>
#include <plyfit/kernel/splice.hpp>

#include <iostream>

namespace plyfit::bench {

namespace {

struct SpliceCase {
  std::string name;
  Result<MoldSurface> mold = Error{ErrorCode::kInternal};
  Vec3 seed, rosette;
  double d = 1.0;
};

std::vector<SpliceCase> splice_cases() {
  std::vector<SpliceCase> out;
  {
    SpliceCase c;
    c.name = "cylinder R = 500, 180 deg, H = 800, warp along the axis, d = 2";
    auto fd = builtin_mold("cylinder", {{"R", 500}, {"H", 800}, {"angle", 180}});
    if (fd) c.mold = MoldSurface::from_face(*fd);
    c.seed = Vec3(0, 500, 400);
    c.rosette = Vec3::UnitZ();
    c.d = 2.0;
    out.push_back(std::move(c));
  }
  {
    SpliceCase c;
    c.name = "sphere octant R = 400 (sheared), d = 2";
    auto fd = builtin_mold("sphere-octant", {{"R", 400}});
    if (fd) c.mold = MoldSurface::from_face(*fd);
    c.seed = Vec3(1, 1, 1).normalized() * 400;
    c.rosette = Vec3::UnitZ();
    c.d = 2.0;
    out.push_back(std::move(c));
  }
  return out;
}

struct Timed {
  double drape_flat = 0.0, splice = 0.0;
  double width = 0.0;  ///< the cut outline's width across the warp
  std::size_t pieces = 0;
  std::uint64_t mapped = 0;
};

// Drape and flat pattern of the ply, then (when roll_width > 0) its splices, timed apart.
Timed run_once(const SpliceCase& c, double roll_width) {
  Timed t;
  PlyDefinition def;
  def.seed = c.seed;
  def.rosette = c.rosette;
  PlySpec cloth;
  cloth.d_weft = cloth.d_warp = c.d;
  auto pb = ply_problem(*c.mold, def, cloth);
  if (!pb) return t;
  Result<DrapeResult> r = Error{ErrorCode::kInternal};
  FlatPattern f;
  t.drape_flat = time_once([&] {
    r = drape(*c.mold, *pb, DrapeOptions{});
    if (r) f = flat_pattern(*c.mold, *r);
  });
  if (!r) return t;
  t.mapped = r->metrics.nodes.mapped;
  double x0 = INFINITY, x1 = -INFINITY;
  for (const auto& l : f.cut)
    for (const Vec2& p : l.points) {
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
    }
  t.width = x1 - x0;
  if (roll_width <= 0.0) return t;
  SpliceOptions so;
  so.roll_width = roll_width;
  Result<SplicePlan> plan = Error{ErrorCode::kInternal};
  t.splice = time_once([&] { plan = splice_pattern(f, *r, so); });
  t.pieces = plan ? plan->pieces.size() : 0;
  return t;
}

Table splice_table(int runs, bool* ok) {
  Table t;
  t.caption =
      "Splices: drape() + flat_pattern() without splices against the same + splice_pattern() "
      "(roll = the pattern's width / 2.5: 3 pieces), medians of " +
      std::to_string(std::max(runs, kMinRuns)) +
      " paired runs; splices in drapes = splice ms / drape+flat ms (goal <= 3).";
  t.header = {"case",
              "nodes",
              "pieces",
              "drape+flat ms (without)",
              "with ms",
              "splice_pattern ms",
              "splices in drapes"};
  t.right = {false, true, true, true, true, true, true};
  for (const SpliceCase& c : splice_cases()) {
    if (!c.mold) {
      *ok = false;
      t.add_failed(c.name, "no mold");
      continue;
    }
    // The pattern's own width, measured once, sets the roll.
    const Timed first = run_once(c, 0.0);
    if (first.mapped == 0) {
      *ok = false;
      t.add_failed(c.name, "failed");
      continue;
    }
    const double roll = first.width / 2.5;
    Timed last;
    // Without, with (drape + flat + splices), and the splices alone.
    const auto m = paired_medians<3>(runs, [&] {
      const double without = run_once(c, 0.0).drape_flat;
      last = run_once(c, roll);
      return std::array{without, last.drape_flat + last.splice, last.splice};
    });
    const auto [base, with, splice] = *m;
    if (last.pieces != 3) *ok = false;
    t.add({c.name, std::to_string(last.mapped), format("%zu", last.pieces),
           format("%.1f", base * 1e3), format("%.1f", with * 1e3), format("%.1f", splice * 1e3),
           format("%.3f", splice / base)});
  }
  return t;
}

const BenchmarkRegistrar kSplices{runs_table_benchmark(
    "splices", "a drape split for the roll against one without, drape + flat + splices",
    splice_table)};

}  // namespace

}  // namespace plyfit::bench
