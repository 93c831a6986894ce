// Every flat-pattern outline is simple and spike-free (tests/support/
// outline_checks.hpp), over many drapes: the sample scenes' cases on the built-in molds, every
// built-in mold and shell with random initial conditions.

#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/outline_checks.hpp"
#include "support/problems.hpp"
#include "support/shells.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
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
  // Spikes the drape itself shows to be the draped region's own shape are no defects
  // (support::spike_reason); everything else is.
  std::vector<support::OutlineDefect> wrong;
  for (const auto& df : support::outline_defects(fp.outline, d))
    if (support::spike_reason(s, *r, fp.outline, df, d).empty()) wrong.push_back(df);
  INFO(support::describe(wrong));
  CHECK(wrong.empty());
  return true;
}

// Random initial conditions on `s` (support::random_drape, as scripts/fuzz-drape picks them).
// Returns the number of drapes checked.
int random_drapes(const DrapeSurface& s, const std::string& name, unsigned seed, int count) {
  std::mt19937 g(seed);
  int checked = 0;
  for (int k = 0; k < count; ++k) {
    const support::RandomDrape rd = support::random_drape(s, name, k, g);
    if (check_drape(s, rd.problem, rd.what, rd.options)) ++checked;
  }
  return checked;
}

// The outline's defects by the geometric check alone, and those spike_reason() does not
// explain.
struct Checked {
  std::vector<support::OutlineDefect> all, unexplained;
};
Checked check_outline(const DrapeSurface& s, const DrapeResult& r,
                      const std::vector<OutlineLoop>& outline, double d) {
  Checked c;
  c.all = support::outline_defects(outline, d);
  for (const auto& df : c.all)
    if (support::spike_reason(s, r, outline, df, d).empty()) c.unexplained.push_back(df);
  return c;
}

// A drape as random_drapes() builds it, and what to call it.
using SpikeCase = support::DrapeCase;

// Drapes case c and checks its outline; `more`, if given, checks the drape further.
Checked check_case(
    const SpikeCase& c,
    const std::function<void(const DrapeResult&, const FlatPattern&)>& more = nullptr) {
  const Face f = builtin(c.mold);
  const auto r = drape(f, c.problem(), c.options());
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(f, *r);
  if (more) more(*r, fp);
  return check_outline(f, *r, fp.outline, c.d);
}

}  // namespace

TEST_CASE("outline checks: draped_at on a plate, analytic") {
  // Plate 100 x 60, d = 5, both sweeps from (50, 30) along x: the cloth covers the plate and
  // nothing else; the ply is the plate itself (x, y), shifted by the start.
  const Face f = builtin("plate");
  const auto r =
      drape(f, support::problem(5.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                Vec3(50, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
  REQUIRE(r.ok());
  for (const Vec2& p : {Vec2(-49.5, -29.5), Vec2(12.3, 7.7), Vec2(49.9, 29.9), Vec2(-3.1, 17.0)})
    CHECK(support::draped_at(f, *r, p) == support::Draped::kYes);
  for (const Vec2& p : {Vec2(-50.5, 0.3), Vec2(12.3, 30.2), Vec2(50.1, -29.0), Vec2(0.3, -30.4)})
    CHECK(support::draped_at(f, *r, p) == support::Draped::kNo);
}

TEST_CASE("outline checks: a spike or notch put into a true outline is a defect") {
  // The plate's outline is its rectangle, spike-free. A sliver out of the plate (cloth off the
  // face) and a notch into it (cloth missing from the middle of the plate) are spikes no
  // drape explains.
  const Face f = builtin("plate");
  const double d = 5.0;
  const auto r =
      drape(f, support::problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                Vec3(50, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(f, *r);
  REQUIRE(fp.outline.size() == 1);
  CHECK(check_outline(f, *r, fp.outline, d).all.empty());
  // The top edge y = 30 runs from (50, 30) to (-50, 30) (counter-clockwise); put a spike
  // 0.4 d high and 0.02 d wide at x = 2, or a notch as deep.
  for (const double dir : {1.0, -1.0}) {
    auto outline = fp.outline;
    auto& pts = outline[0].points;
    std::size_t k = 0;
    auto top = [&](const Vec2& p) { return std::abs(p.y() - 30.0) < 1e-6; };
    while (k < pts.size() && !(top(pts[k]) && top(pts[(k + 1) % pts.size()]) && pts[k].x() > 2.0 &&
                               pts[(k + 1) % pts.size()].x() < 2.0))
      ++k;
    REQUIRE(k < pts.size());
    const std::vector<Vec2> bump = {Vec2(2.05, 30.0), Vec2(2.0, 30.0 + dir * 0.4 * d),
                                    Vec2(1.95, 30.0)};
    pts.insert(pts.begin() + static_cast<std::ptrdiff_t>(k + 1), bump.begin(), bump.end());
    const Checked c = check_outline(f, *r, outline, d);
    INFO((dir > 0 ? "spike" : "notch") << "\n" << support::describe(c.all));
    CHECK(!c.all.empty());
    CHECK(c.unexplained.size() == c.all.size());
  }
}

// Random-drape spikes, one of each kind found (this file's drapes with seeds 1..): the outline
// turns back within d/2 (the geometric check fails), and the drape itself shows the narrow shape is
// the draped region's (spike_reason explains it).
TEST_CASE("outline checks: narrow shapes of the draped region are no defects") {
  const SpikeCase cases[] = {
      // A strip of cloth 0.18 d wide between the face's edge and a row whose cells below
      // were stopped (overlap): the edge runs 0.02 above the row.
      {"hemisphere: strip between the face edge and an overlap stop", "hemisphere",
       0.10973817914653033, Vec2(0.99834856016847195, -0.057446953004828792),
       Vec2(0.057446953004828792, 0.99834856016847195),
       Vec3(0.23447179449406841, 0.13044943651281971, 0.54521187752363209),
       Vec3(-0.99580287622940966, -0.064639367141352835, 0.064794937370141345),
       Vec3(-0.43134763568172607, -0.55503042602519637, 0.71125272820430974), false},
      // The face's edge crosses a row whose cells below were stopped (overlap) at 7 degrees.
      {"cylinder: the face edge meets an overlap stop at 7 degrees", "cylinder",
       0.56238192339513193, Vec2(0.97329854998431597, 0.2295428774726587),
       Vec2(-0.2295428774726587, 0.97329854998431597),
       Vec3(5.2458738567917518, 3.0417066884813773, 7.8391752014920471),
       Vec3(0.2321169838569678, 0.86483966877425067, 0.44516744391249974),
       Vec3(-0.035171467151345642, 0.033934334760646188, 0.99880500039936437), true},
      // One sweep: the base path is the cut; it leaves the face at 6 degrees to the edge.
      {"saddle: the base path of a one-sided drape meets the face edge at 6 degrees", "saddle",
       1.9850544454896293, Vec2(-0.99436142692706109, -0.10604410704786445),
       Vec2(0.10604410704786445, -0.99436142692706109),
       Vec3(5.8730553998389858, -7.994534347582638, -3.353416879543297),
       Vec3(0.13236925105854483, -0.039963955386671572, -0.99039449899726928),
       Vec3(0.3223892288769471, 0.57940124850625652, -0.74857155859244251), false},
      // One sweep, lock angle 29.1 degrees: the cloth is a strip 0.45 d wide between the base
      // path and the first warp thread, whose neighbours hit the lock; where that thread
      // stops too, the strip ends square. (scripts/fuzz-drape --seed 11; a rounding-thin
      // mismatch on the strip's end edge, 6e-17 d off, was first taken for a defect.)
      {"cylinder: a strip between the base path and a thread ends at the lock", "cylinder", 0.24745,
       Vec2(-0.037955, 0.999279), Vec2(-0.999279, -0.037955), Vec3(6.936050, 3.461219, 6.872162),
       Vec3(-0.958010, -0.216617, -0.187868), Vec3(0.156870, 0.316674, 0.935473), false,
       29.1 * 3.14159265358979323846 / 180.0},
  };
  std::vector<SpikeCase> all(std::begin(cases), std::end(cases));
  for (const SpikeCase& c : support::explained_outline_spikes()) all.push_back(c);
  for (const SpikeCase& c : all) {
    INFO(c.what);
    const Checked k = check_case(c);
    INFO(support::describe(k.all));
    CHECK(!k.all.empty());
    CHECK(k.unexplained.empty());
  }
}

// Spikes found by more random drapes (60 per mold, other seeds) that the drape did not
// explain: faults of the exact outline, each failed before its fix. The outline of
// each is now free of any geometric spike, one loop, every loop holding a mapped node, and no
// point of the mold in two places of the ply.
TEST_CASE("outline checks: faults of the exact outline at poles and face corners") {
  for (const SpikeCase& c : support::fixed_outline_faults()) {
    INFO(c.what);
    const Checked k = check_case(c, [&](const DrapeResult& r, const FlatPattern& fp) {
      CHECK(fp.outline.size() == 1);
      CHECK(support::loops_without_mapped_node(r, fp.outline, c.d).empty());
      CHECK(support::one_point_two_places(fp.outline, c.d).empty());
    });
    INFO(support::describe(k.all));
    CHECK(k.all.empty());
  }
}

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

// Random drapes: every spike of their outlines must be the draped region's own shape
// (support::spike_reason); 12 per mold, as scripts/fuzz-drape picks them.
TEST_CASE("flat pattern: outlines are simple and spike-free on every built-in mold") {
  int checked = 0;
  unsigned seed = 1;
  int molds = 0;
  for (const BuiltinInfo& info : builtin_molds()) {
    const Face f = builtin(info.name);
    checked += random_drapes(f, info.name, seed++, 12);
    ++molds;
  }
  // Most random initial conditions are valid drapes.
  CHECK(checked >= 6 * molds);
}

TEST_CASE("flat pattern: outlines are simple and spike-free on every built-in shell") {
  int checked = 0;
  unsigned seed = 100;
  for (const BuiltinInfo& info : builtin_shells()) {
    auto sh = support::make_builtin_shell(info.name);
    REQUIRE(sh.ok());
    checked += random_drapes(*sh, info.name, seed++, 12);
  }
  CHECK(checked >= 6 * static_cast<int>(builtin_shells().size()));
}
