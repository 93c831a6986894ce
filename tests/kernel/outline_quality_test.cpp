// Issue 13: every flat-pattern outline is simple and spike-free (tests/support/
// outline_checks.hpp), over many drapes: the sample scenes' cases on the built-in molds, every
// built-in mold and shell with random initial conditions.

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/builtin_shells.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/shell.hpp>

#include <catch2/catch.hpp>

#include "support/outline_checks.hpp"
#include "support/problems.hpp"

#include <cmath>
#include <random>
#include <sstream>

using namespace plyfit;

namespace {

Face builtin(const std::string& name, std::map<std::string, double> p = {}) {
  auto f = Face::create(builtin_mold(name, p).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

// Drapes `pb` on `s` and checks its outline; returns false when the drape itself was refused
// (an input error, as a base plane that misses the surface).
bool check_drape(const DrapeSurface& s, const DrapeProblem& pb, const std::string& what,
                 const DrapeOptions& opt = {}) {
  const auto r = drape(s, pb, opt);
  if (!r.ok()) return false;
  const FlatPattern fp = flat_pattern(s, *r);
  const double d = std::max(pb.ply.d_weft, pb.ply.d_warp);
  INFO(what);
  const auto defects = support::outline_defects(fp.outline, d);
  INFO(support::describe(defects));
  CHECK(defects.empty());
  return true;
}

Vec3 unit(std::mt19937& g) {
  std::normal_distribution<double> n;
  Vec3 v(n(g), n(g), n(g));
  return v.normalized();
}

// Random initial conditions on `s` (as scripts/fuzz-drape picks them): a start in the middle
// of the box, random base normal and sweep direction, one or both sweeps, a spacing of 1/15
// to 1/60 of the size, sometimes a lock angle. Returns the number of drapes checked.
int random_drapes(const DrapeSurface& s, const std::string& name, unsigned seed, int count) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int checked = 0;
  for (int k = 0; k < count; ++k) {
    const BBox3 box = s.bbox();
    Vec3 start;
    for (int i = 0; i < 3; ++i)
      start[i] = box.min[i] + (box.max[i] - box.min[i]) * (0.3 + 0.4 * u01(g));
    const double t = 2.0 * 3.14159265358979323846 * u01(g);
    const Vec2 b2(std::cos(t), std::sin(t));
    const double side = u01(g) < 0.5 ? 1.0 : -1.0;
    const Vec2 w2 = side * Vec2(-b2.y(), b2.x());
    const Vec3 bn = unit(g), sw = unit(g);
    const double d = s.size() / (15.0 + 45.0 * u01(g));
    DrapeProblem pb = support::problem(d, Vec2(0, 0), b2, {w2}, start, bn, {sw});
    if (u01(g) < 0.5) {
      pb.ply.sweeps.push_back(-w2);
      pb.sweeps.push_back(-sw);
    }
    DrapeOptions opt;
    if (u01(g) < 0.3) opt.lock_angle = (20.0 + 40.0 * u01(g)) * 3.14159265358979323846 / 180.0;
    std::ostringstream what;
    what.precision(17);
    what << name << " drape " << k << ": d " << d << " b2 " << b2.transpose() << " w2 "
         << w2.transpose() << " start " << start.transpose() << " bn " << bn.transpose()
         << " sweep " << sw.transpose() << " sweeps " << pb.sweeps.size();
    what << " lock " << opt.lock_angle;
    if (check_drape(s, pb, what.str(), opt)) ++checked;
  }
  return checked;
}

}  // namespace

TEST_CASE("flat pattern: no sliver at the pole of the revolution third (samples d and e)") {
  // samples/revolution-third-d.ini and -e.ini on the built-in mold they were written from:
  // the outline ran ~1.2 mm past the pole and back (a 134-degree turn then a 46-degree one,
  // 0.14 mm apart): a cell's (u, v) edge near the pole is an arc about it, not the cell.
  const Face f = builtin("revolution-third");
  const Vec3 s3(10, 17.32050807568877, 0);
  check_drape(f,
              support::problem(1.0, Vec2(35, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, s3,
                               Vec3(1, -1, 0), {Vec3(1, -1, 0), Vec3(-1, 1, 0)}),
              "revolution-third-d");
  // Case (e): start on the profile at (13.75, 7.5), the base path at 45 degrees in the ply
  // (on today's code a 136-degree turn then a 44-degree one, 0.11 mm apart).
  check_drape(f,
              support::problem(1.0, Vec2(35, 35), Vec2(1, 1), {Vec2(-1, 1), Vec2(1, -1)},
                               Vec3(6.875, 11.90784930203603, 7.5), Vec3(1, -1, 0),
                               {Vec3(1, -1, 0), Vec3(-1, 1, 0)}),
              "revolution-third-e");
}

// [!mayfail]: open findings of issue 13 (tiny loops and multi-vertex spikes on random drapes,
// listed in the report of branch flatpattern); the failures are printed, the run goes on.
TEST_CASE("flat pattern: outlines are simple and spike-free on every built-in mold", "[!mayfail]") {
  int checked = 0;
  unsigned seed = 1;
  for (const BuiltinInfo& info : builtin_molds()) {
    const Face f = builtin(info.name);
    checked += random_drapes(f, info.name, seed++, 12);
  }
  // Most random initial conditions are valid drapes.
  CHECK(checked >= 6 * static_cast<int>(builtin_molds().size()));
}

TEST_CASE("flat pattern: outlines are simple and spike-free on every built-in shell",
          "[!mayfail]") {
  int checked = 0;
  unsigned seed = 100;
  for (const BuiltinInfo& info : builtin_shells()) {
    auto data = builtin_shell(info.name, {});
    REQUIRE(data.ok());
    auto sh = Shell::create(std::move(data).value());
    REQUIRE(sh.ok());
    checked += random_drapes(*sh, info.name, seed++, 12);
  }
  CHECK(checked >= 6 * static_cast<int>(builtin_shells().size()));
}
