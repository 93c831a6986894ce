// A base path that crosses a hole in the face: the path goes on across the
// hole on the face's surface under it, the sweeps go on from every path node, and the flat
// pattern is the cloth of the face without the hole, less the hole.
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/face.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/problems.hpp"
#include "support/warnings.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace plyfit;
using plyfit::support::problem;

namespace {

constexpr double kRim = 1e-9;  // nodes this close to a boundary may fall either way

Face mold(const std::string& name, const std::map<std::string, double>& params) {
  auto fd = builtin_mold(name, params);
  REQUIRE(fd.ok());
  auto f = Face::create(std::move(fd).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

Face plate_with_hole() {
  return mold("plate",
              {{"W", 100.0}, {"H", 60.0}, {"hole_r", 10.0}, {"hole_x", 50.0}, {"hole_y", 30.0}});
}

// Nodes that are not mapped while both their neighbours along a weft or along a warp are: a
// slit in the net. A node the drape reached outside the face counts only if its (extended)
// point is strictly on the face (`on_face`, away from the boundary by more than rounding);
// one never reached always counts.
template <class OnFace>
int slit_nodes(const DrapeResult& r, OnFace&& on_face) {
  int slits = 0;
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    for (const auto& [di, dj] : {std::pair{2, 0}, std::pair{0, 2}}) {
      const DrapeNode* far = r.find(NodeId::regular(n.id.i + di, n.id.j + dj));
      if (!far || !far->mapped()) continue;
      const DrapeNode* mid = r.find(NodeId::regular(n.id.i + di / 2, n.id.j + dj / 2));
      if (mid && (mid->mapped() || !mid->has(DrapeNode::kExtended) || !on_face(mid->point)))
        continue;
      UNSCOPED_INFO("slit at (" << n.id.i + di / 2 << ", " << n.id.j + dj / 2
                                << "): " << (mid ? to_string(mid->status) : "never reached"));
      ++slits;
    }
  }
  return slits;
}

}  // namespace

// The path line beyond the hole is mapped, and the outline has a hole loop and no slit from the
// hole to the edge (docs/decisions/base-path-across-holes.md).
TEST_CASE("drape: a base path across a hole goes on beyond it, both sweeps from it") {
  const Face f = plate_with_hole();
  // Spacings that put nodes on the path line inside and beyond the hole, with and without a
  // node on the hole's rim.
  for (double d : {2.0, 1.7, 2.5}) {
    INFO("d = " << d);
    auto rr = drape(f, problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                               Vec3(20, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
    REQUIRE(rr.ok());
    const DrapeResult& r = rr.value();
    CHECK(r.metrics.nodes.failed == 0);
    CHECK(r.metrics.nodes.conflict == 0);
    CHECK_FALSE(r.partial);
    // Every node strictly inside the plate and off the hole's rim is mapped (on a plane the
    // ply lies on the face: ply point p is at (20, 30) + p), so no slit is left between the
    // two sweeps.
    const Ply& ply = *r.ply;
    const int ni = static_cast<int>(std::ceil(100 / d)), nj = static_cast<int>(std::ceil(60 / d));
    int missing = 0, inside = 0;
    for (int i = -ni; i <= ni; ++i) {
      for (int j = -nj; j <= nj; ++j) {
        const Vec2 p = ply.pos(i, j) + Vec2(20, 30);
        if (!(p.x() > kRim && p.x() < 100 - kRim && p.y() > kRim && p.y() < 60 - kRim) ||
            (p - Vec2(50, 30)).norm() < 10 + kRim)
          continue;
        ++inside;
        const auto k = r.index->find(NodeId::regular(i, j));
        if (k >= 0 && r.nodes[static_cast<std::size_t>(k)].mapped()) continue;
        UNSCOPED_INFO(
            "inside, not mapped: ("
            << i << ", " << j << ") "
            << (k >= 0 ? to_string(r.nodes[static_cast<std::size_t>(k)].status) : "never reached"));
        ++missing;
      }
    }
    CHECK(inside > 500);
    CHECK(missing == 0);
    CHECK(slit_nodes(r, [](const Vec3& p) {
            return p.x() > kRim && p.x() < 100 - kRim && p.y() > kRim && p.y() < 60 - kRim &&
                   (Vec2(p.x(), p.y()) - Vec2(50, 30)).norm() > 10 + kRim;
          }) == 0);
    // The base path runs from edge to edge: across the hole its nodes are outside, on the
    // plane under the hole (kInHole), and mapped again beyond it.
    int path_in_hole = 0, path_beyond = 0;
    for (const std::uint32_t k : r.base_path) {
      const DrapeNode& n = r.nodes[k];
      const double off = std::abs(n.ply.x() + 20 - 50) - 10;  // signed distance from the rim
      if (off < -kRim) CHECK(n.has(DrapeNode::kInHole));
      if (off > kRim) CHECK(n.mapped());
      if (n.has(DrapeNode::kInHole)) ++path_in_hole;
      if (n.mapped() && n.ply.x() + 20 > 60) ++path_beyond;
    }
    CHECK(path_in_hole >= static_cast<int>(std::floor(20 / d)) - 1);
    CHECK(path_beyond > 0);
    // The flat pattern: the plate less the hole (a plane: the ply is the face itself, up to
    // the hole's polygonal trim, whose area differs from pi r^2 by O(r h^2)); one outer loop
    // and one hole loop.
    const FlatPattern fp = flat_pattern(f, r);
    int outer = 0, holes = 0;
    for (const OutlineLoop& l : fp.outline) (l.hole ? holes : outer) += 1;
    CHECK(outer == 1);
    CHECK(holes == 1);
    CHECK(fp.area == Approx(6000.0 - kPi * 100.0).epsilon(2e-3));
  }
}

// The dish sample's mold (a trimmed paraboloid, builtin:dish) with and without its central
// hole, draped as samples/dish.ini does: base path along the meridian y = 0 from r = 18 across
// the hole to the far rim, both sweeps. The cloth on the holed face is the cloth of the
// holeless face node for node (the drape goes on under the hole on the same surface); the hole
// is cut out of the flat pattern.
TEST_CASE("drape: the dish with a hole is draped as the dish without it, less the hole") {
  constexpr double kR = 30, kRho = 40, kHole = 8;
  const Face holed = mold("dish", {{"R", kR}, {"rho", kRho}, {"hole_r", kHole}});
  const Face whole = mold("dish", {{"R", kR}, {"rho", kRho}});
  constexpr double d = 1.0;
  const DrapeProblem pb = problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                  Vec3(18, 0, 18.0 * 18.0 / (2 * kRho)), Vec3(0, 1, 0),
                                  {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  auto rh = drape(holed, pb);
  auto rw = drape(whole, pb);
  REQUIRE(rh.ok());
  REQUIRE(rw.ok());
  const DrapeResult& h = rh.value();
  const DrapeResult& w = rw.value();
  CHECK(h.metrics.nodes.failed == 0);
  CHECK(h.metrics.nodes.conflict == 0);
  CHECK(h.metrics.nodes.overlap == 0);
  CHECK(h.metrics.nodes.shear_limit == 0);
  CHECK_FALSE(h.partial);
  // Node for node: every node mapped on the holed dish is mapped on the whole one at the same
  // point (to rounding: the same solves from the same neighbours), and every node of the
  // whole dish's cloth that lies on the holed face is mapped there.
  constexpr double kSame = 1e-12;  // relative to the dish's size (60 mm): rounding only
  double worst = 0.0;
  int mapped_h = 0, missing = 0, differ = 0;
  for (const DrapeNode& n : h.nodes) {
    if (!n.mapped()) continue;
    ++mapped_h;
    const DrapeNode* m = w.find(n.id);
    if (!m || !m->mapped()) {
      UNSCOPED_INFO("mapped on the holed dish only: " << n.id.i << ", " << n.id.j);
      ++differ;
      continue;
    }
    worst = std::max(worst, (n.point - m->point).norm());
  }
  for (const DrapeNode& m : w.nodes) {
    if (!m.mapped() || std::hypot(m.point.x(), m.point.y()) <= kHole * (1 + 1e-9)) continue;
    const DrapeNode* n = h.find(m.id);
    if (n && n->mapped()) continue;
    UNSCOPED_INFO("on the holed face, not mapped there: "
                  << m.id.i << ", " << m.id.j << " "
                  << (n ? to_string(n->status) : std::string("never reached")));
    ++missing;
  }
  INFO("largest distance between the two drapes' nodes: " << worst);
  CHECK(mapped_h > 2000);
  CHECK(differ == 0);
  CHECK(missing == 0);
  CHECK(worst <= kSame * 2 * kR);
  CHECK(slit_nodes(h, [&](const Vec3& p) {
          const double r = std::hypot(p.x(), p.y());
          return r > kHole + kRim && r < kR - kRim;
        }) == 0);
  // The flat pattern: one outer loop and one hole loop; the holeless flat area less the
  // hole's. The hole's flat area is the paraboloid cap's surface area (the cloth is
  // inextensible; near the apex it is sheared by under a degree, which changes areas by
  // 1 - sin(gamma) < 2e-4), up to the outline's chords across the hole (segments about d
  // long on a circle of radius 8: area off by about perimeter * d^2 / (12 r) ~ 0.5 mm^2):
  // within 1 % of the cap.
  const FlatPattern fh = flat_pattern(holed, h);
  const FlatPattern fw = flat_pattern(whole, w);
  int outer = 0, holes = 0;
  for (const OutlineLoop& l : fh.outline) (l.hole ? holes : outer) += 1;
  CHECK(outer == 1);
  CHECK(holes == 1);
  const double cap =
      2 * kPi * kRho * kRho / 3 * (std::pow(1 + kHole * kHole / (kRho * kRho), 1.5) - 1);
  CHECK(fw.area - fh.area == Approx(cap).epsilon(0.01));
}

// No surface under the gap: a plate 60 x 60 sewn from a 3 x 3 grid of faces 20 x 20 whose
// middle face is missing (the hole is a missing face: no face's surface runs under it). The base
// path along y = 30 stops at the gap; the sweeps come round it through the rows above and below
// into the far face from both sides. Beyond the path's end its line is plain cloth: the sweep
// that reaches it first maps it and the other meets that cloth there; on a plane the two agree
// (no conflict), so the line is mapped and no slit is left (a curved face where they disagree
// stops the nodes as in conflict, partial).
TEST_CASE("drape: round a missing face the cloth closes the base path's line beyond it") {
  ShellData sd;
  auto index = [](int a, int b) { return a * 3 + b; };
  std::vector<std::vector<std::int32_t>> tags(9, std::vector<std::int32_t>(4, TrimLoop::kFreeEdge));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a == 1 && b == 1) continue;
      // Segments 0..3: v = 0, u = 1, v = 1, u = 0 of the unit square loop.
      if (a < 2 && !(a + 1 == 1 && b == 1)) {
        tags[index(a, b)][1] = tags[index(a + 1, b)][3] = sd.edge_count++;
      }
      if (b < 2 && !(a == 1 && b + 1 == 1)) {
        tags[index(a, b)][2] = tags[index(a, b + 1)][0] = sd.edge_count++;
      }
    }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a == 1 && b == 1) continue;
      FaceData f;
      f.surface = plane_patch(Vec3(20 * a, 20 * b, 0), Vec3(20, 0, 0), Vec3(0, 20, 0));
      f.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, tags[index(a, b)]});
      sd.faces.push_back(std::move(f));
    }
  auto sh = Shell::create(std::move(sd));
  REQUIRE(sh.ok());
  auto rr = drape(*sh, problem(2.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                               Vec3(10, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
  REQUIRE(rr.ok());
  const DrapeResult& r = rr.value();
  for (const std::uint32_t k : r.base_path) {
    CHECK(r.nodes[k].mapped());
    CHECK(r.nodes[k].ply.x() + 10 <= 20 + kRim);
  }
  // The far face is draped (round the gap) on both sides of the line.
  const DrapeNode* above = r.find(NodeId::regular(20, 1));  // (50, 32)
  const DrapeNode* below = r.find(NodeId::regular(20, -1));
  REQUIRE(above);
  REQUIRE(below);
  CHECK(above->mapped());
  CHECK(below->mapped());
  CHECK(r.metrics.nodes.failed == 0);
  CHECK(r.metrics.nodes.conflict == 0);
  CHECK_FALSE(r.partial);
  CHECK(support::with_code(r.warnings, WarningCode::kPathSlit).empty());
  // The line's nodes in the far face (x = 42 ... 58) are mapped, d from their neighbours on
  // both sides (the plane maps rigidly).
  for (std::int32_t i = 16; i <= 24; ++i) {
    const DrapeNode* on = r.find(NodeId::regular(i, 0));
    REQUIRE(on);
    CHECK(on->mapped());
    for (const std::int32_t j : {1, -1}) {
      const DrapeNode* nb = r.find(NodeId::regular(i, j));
      REQUIRE(nb);
      CHECK((nb->point - on->point).norm() == Approx(2.0).epsilon(1e-12));
    }
  }
}
