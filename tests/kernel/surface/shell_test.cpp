// Shells of several faces: validation and topology, moving across shared edges, and drapes
// across faces compared with the same surface as one face.
#include "surface/shell/shell.hpp"
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "pattern/flat_pattern.hpp"

#include "support/faces.hpp"
#include "support/net_checks.hpp"
#include "support/problems.hpp"
#include "support/shells.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

using namespace plyfit;
using plyfit::support::make_face;

namespace {

Shell make_shell(const std::string& name, const std::map<std::string, double>& params = {}) {
  auto sh = support::make_builtin_shell(name, params);
  INFO(name << ": " << (sh.ok() ? "" : exporters::describe(sh.error())));
  REQUIRE(sh.ok());
  return std::move(sh).value();
}

// Two planar faces w wide along Y, hinged along the Y axis: face 0 is -e0 + s e0 + t (0, w, 0)
// (its side u = 1 on the axis), face 1 is s e1 + t (0, w, 0) (its side u = 0 on the axis); the
// hinge is shared edge 0.
Shell hinge(const Vec3& e0, const Vec3& e1, double w) {
  ShellData sd;
  FaceData f0, f1;
  f0.surface = plane_patch(-e0, e0, Vec3(0, w, 0));
  f1.surface = plane_patch(Vec3(0, 0, 0), e1, Vec3(0, w, 0));
  f0.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {-1, 0, -1, -1}});
  f1.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}, {-1, -1, -1, 0}});
  sd.faces = {f0, f1};
  sd.edge_count = 1;
  auto sh = Shell::create(std::move(sd));
  REQUIRE(sh.ok());
  return std::move(sh).value();
}

// The whole sphere as one face: closed around Z, poles at both ends of u.
Face one_patch_sphere(double R) {
  FaceData fd;
  fd.surface = sphere_patch(R, -kPi / 2, kPi / 2, 0.0, 2 * kPi);
  fd.closed_v = true;
  return make_face(std::move(fd));
}

}  // namespace

TEST_CASE("shell: the built-in shells are sewn, oriented and have the topology they should") {
  const Shell sphere = make_shell("sphere-8");
  CHECK(sphere.face_count() == 8);
  CHECK(sphere.edge_count() == 12);
  CHECK(sphere.euler_characteristic() == 2);  // a sphere
  CHECK(sphere.free_loop_count() == 0);
  CHECK(sphere.closes_on_itself());
  CHECK(sphere.area() == Approx(4 * kPi * 400).epsilon(1e-9));
  for (std::int32_t e = 0; e < sphere.edge_count(); ++e) CHECK(sphere.crease_angle(e) < 1e-9);

  const Shell half = make_shell("cylinder-split", {{"angle", 180}, {"parts", 3}});
  CHECK(half.euler_characteristic() == 1);  // a disc
  CHECK(half.free_loop_count() == 1);
  CHECK_FALSE(half.closes_on_itself());

  const Shell tube = make_shell("cylinder-split", {{"angle", 360}, {"parts", 2}});
  CHECK(tube.euler_characteristic() == 0);  // a tube
  CHECK(tube.free_loop_count() == 2);
  CHECK(tube.closes_on_itself());

  const Shell ffw = make_shell("flange-fillet-wall");
  CHECK(ffw.euler_characteristic() == 1);
  CHECK(ffw.free_loop_count() == 1);
  CHECK_FALSE(ffw.closes_on_itself());
  CHECK(ffw.area() == Approx(60 * (40 + 10 * kPi / 2 + 40)).epsilon(1e-9));
  CHECK(ffw.crease_angle(0) < 1e-9);  // tangent joins
  CHECK(ffw.crease_angle(1) < 1e-9);
}

TEST_CASE("shell: a face given the wrong way round is turned to agree with its neighbours") {
  auto data = builtin_shell("flange-fillet-wall", {});
  REQUIRE(data.ok());
  data->faces[1].reversed = true;  // the fillet's normal inward
  auto sh = Shell::create(std::move(data).value());
  REQUIRE(sh.ok());
  // Every face's normal points to the convex side: +Z on the flange, +X on the wall, and
  // away from the fillet's axis.
  CHECK(sh->normal(SurfaceLocation(Vec2(0.5, 0.5), 0)).n.z() == Approx(1.0));
  CHECK(sh->normal(SurfaceLocation(Vec2(0.5, 0.5), 2)).n.x() == Approx(1.0));
  const SurfaceLocation mid(Vec2(0.5 * (sh->domain(SurfaceLocation(Vec2::Zero(), 1)).u0 +
                                        sh->domain(SurfaceLocation(Vec2::Zero(), 1)).u1),
                                 0.5),
                            1);
  const Vec3 p = sh->eval1(mid).p;
  const Vec3 radial = Vec3(p.x(), 0, p.z() + 10).normalized();
  CHECK(sh->normal(mid).n.dot(radial) == Approx(1.0));
}

TEST_CASE("shell: a crease between two faces is measured") {
  // Two planar faces meeting along the Y axis at 30 degrees.
  const double a = 30.0 * kDegToRad;
  const Shell sh = hinge(Vec3(10, 0, 0), Vec3(10 * std::cos(a), 0, -10 * std::sin(a)), 10);
  CHECK(sh.crease_angle(0) == Approx(a).epsilon(1e-12));
  CHECK(sh.crease_angle(0, 1) == Approx(a).epsilon(1e-12));
}

TEST_CASE("shell: bad shells are refused, naming the face or the edge") {
  auto data = builtin_shell("flange-fillet-wall", {});
  REQUIRE(data.ok());
  using V = std::vector<MessageValue>;
  auto refused = [](ShellData sd) {
    auto sh = Shell::create(std::move(sd));
    REQUIRE_FALSE(sh.ok());
    return sh.error();
  };
  SECTION("an edge used by one face") {
    data->faces[2].loops[0].edges = {-1, -1, -1, -1};
    const Error e = refused(*data);
    CHECK(e.code == ErrorCode::kSharedEdgeUses);
    CHECK(e.values == V{std::int64_t{1}, std::int64_t{1}});
  }
  SECTION("an edge index out of range") {
    data->faces[0].loops[0].edges[1] = 7;
    const Error e = refused(*data);
    CHECK(e.code == ErrorCode::kSharedEdgeRange);
    CHECK(e.face == 0);
    CHECK(e.values == V{std::int64_t{7}});
  }
  SECTION("a loop with a tag too few") {
    data->faces[1].loops[0].edges.pop_back();
    const Error e = refused(*data);
    CHECK(e.code == ErrorCode::kTrimLoopEdgeTags);
    CHECK(e.face == 1);
    CHECK(e.values == V{std::int64_t{0}, std::int64_t{3}, std::int64_t{4}});
  }
  SECTION("a face that does not validate, named by its index in the file") {
    data->source_faces = {5, 6, 7};
    data->faces[2].surface.knots_u.pop_back();
    const Error e = refused(*data);
    CHECK(e.code == ErrorCode::kKnotCount);
    CHECK(e.face == 7);
  }
  SECTION("faces that are not sewn") {
    data->faces[2].surface = plane_patch(Vec3(30, 0, -10), Vec3(0, 0, -40), Vec3(0, 60, 0));
    const Error e = refused(*data);
    CHECK(e.code == ErrorCode::kShellNotSewn);
    REQUIRE(e.values.size() == 2);
    CHECK(std::get<double>(e.values[0]) == Approx(20.0));  // the wall moved 20 off the fillet
  }
  SECTION("counts that do not match") {
    CHECK(refused(ShellData{}).code == ErrorCode::kShellNoFaces);
    data->source_faces = {0, 1};
    CHECK(refused(*data).code == ErrorCode::kShellFaceIndices);
    data->source_faces.clear();
    data->edge_count = -1;
    CHECK(refused(*data).code == ErrorCode::kShellEdgeCountNegative);
  }
}

TEST_CASE("shell: a step in one face's parameters continues on the neighbouring face") {
  const Shell sh = make_shell("flange-fillet-wall");
  // From the middle of the flange straight towards the fillet, past the shared edge.
  const SurfaceLocation from(Vec2(0.5, 0.5), 0);
  const SurfaceLocation to = sh.locate(from, Vec2(1.2, 0.5));  // 8 mm past the edge
  CHECK(to.face == 1);
  CHECK(sh.contains(to));
  // The point is on the fillet's cylinder, about 8 mm of arc from the edge.
  const Vec3 p = sh.eval1(to).p;
  CHECK(std::hypot(p.x(), p.z() + 10) == Approx(10).epsilon(1e-12));
  CHECK(std::atan2(p.x(), p.z() + 10) * 10 == Approx(8).epsilon(0.2));
  CHECK(p.y() == Approx(30));
  // Far enough to cross the fillet onto the wall.
  const SurfaceLocation wall = sh.locate(from, Vec2(2.0, 0.5));
  CHECK(wall.face == 2);
  CHECK(sh.contains(wall));
  // Past a free edge the location stays on its face, outside it.
  const SurfaceLocation off = sh.locate(from, Vec2(-0.2, 0.5));
  CHECK(off.face == 0);
  CHECK_FALSE(sh.contains(off));
}

TEST_CASE("shell: the sphere as 8 faces drapes the same net as the sphere as one face") {
  const Face one = one_patch_sphere(20.0);
  const Shell eight = make_shell("sphere-8", {{"R", 20.0}});
  // A start at the corner of three faces; both sweeps; a bounded ply.
  const Vec3 s3 = Vec3(1, 1, 1).normalized() * 20.0;
  auto pb = support::problem(1.0, Vec2(15, 15), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, s3,
                             Vec3(1, -1, 0).normalized().cross(s3).normalized(),
                             {Vec3(0, 0, 1), Vec3(0, 0, -1)});
  pb.ply.rect = Vec2(30, 30);
  auto a = drape(one, pb);
  auto b = drape(eight, pb);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  INFO("one face: " << a->metrics.nodes.mapped << " mapped; 8 faces: " << b->metrics.nodes.mapped);
  const std::size_t mapped = support::same_net(*a, *b, 1e-9 * pb.ply.d_weft);
  CHECK(mapped > 800);
  CHECK(support::seam_gaps(*b) == 0);
  // The net crossed shared edges: nodes on several faces.
  std::set<int> faces;
  for (const DrapeNode& n : b->nodes)
    if (n.mapped()) faces.insert(n.face);
  CHECK(faces.size() >= 3);
}

TEST_CASE("shell: the cloth crosses a pole that four faces share") {
  // Started off the north pole of the 8-face sphere: the ply (30 x 30 on R = 20) covers the
  // pole, where the 4 northern faces meet in their collapsed edges. A sphere has no edge: every
  // node of the ply is mapped. (The sphere as one face is compared where it maps its nodes: at
  // its own pole it stops one node.)
  const Shell eight = make_shell("sphere-8", {{"R", 20.0}});
  const Face one = one_patch_sphere(20.0);
  const Vec3 s3 = Vec3(0.3, -0.2, 1).normalized() * 20.0;
  auto pb = support::problem(1.0, Vec2(15, 15), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, s3,
                             Vec3(1, -1, 0).normalized().cross(s3).normalized(),
                             {Vec3(0, 0, 1), Vec3(0, 0, -1)});
  pb.ply.rect = Vec2(30, 30);
  auto b = drape(eight, pb);
  REQUIRE(b.ok());
  CHECK(b->metrics.nodes.mapped == 31 * 31);
  CHECK(b->metrics.nodes.outside == 0);
  CHECK(b->metrics.nodes.failed == 0);
  CHECK(b->metrics.nodes.conflict == 0);
  CHECK(b->metrics.edge_length_max_rel < 1e-12);
  std::set<int> faces;
  for (const DrapeNode& n : b->nodes)
    if (n.mapped()) faces.insert(n.face);
  CHECK(faces.size() == 4);
  auto a = drape(one, pb);
  REQUIRE(a.ok());
  // The scan resolves nodes in the same order on both: up to the one-face net's first stop,
  // the nets agree node for node.
  std::uint32_t first_stop = UINT32_MAX;
  for (const DrapeNode& n : a->nodes)
    if (n.status == NodeStatus::kOutside || n.status == NodeStatus::kFailed ||
        n.status == NodeStatus::kConflict)
      first_stop = std::min(first_stop, n.order);
  std::size_t compared = 0;
  for (const DrapeNode& n : a->nodes) {
    const DrapeNode* m = b->find(n.id);
    if (n.order >= first_stop || !n.mapped()) continue;
    ++compared;
    REQUIRE(m);
    CHECK(m->mapped());
    if ((n.point - m->point).norm() > 1e-9) FAIL_CHECK("node " << n.id.i << "," << n.id.j);
  }
  CHECK(compared > 100);
}

TEST_CASE("shell: a cylinder split along generators drapes the same net as one face") {
  for (const double angle : {180.0, 360.0}) {
    INFO("angle " << angle);
    auto fd = builtin_mold("cylinder", {{"R", 10}, {"H", 20}, {"angle", angle}});
    REQUIRE(fd.ok());
    const Face one = make_face(std::move(fd).value());
    const Shell split = make_shell("cylinder-split", {{"angle", angle}, {"parts", 2}});
    // Threads at 30 degrees to the axis, the start on the first face near the split.
    auto pb =
        support::problem(0.5, Vec2(0, 0), Vec2(std::cos(0.5), std::sin(0.5)),
                         {Vec2(-std::sin(0.5), std::cos(0.5)), Vec2(std::sin(0.5), -std::cos(0.5))},
                         Vec3(10 * std::cos(1.4), 10 * std::sin(1.4), 10), Vec3(0, 0, 1),
                         {Vec3(0, 0, 1), Vec3(0, 0, -1)});
    auto a = drape(one, pb);
    auto b = drape(split, pb);
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    const std::size_t mapped = support::same_net(*a, *b, 1e-9 * 0.5);
    CHECK(mapped > 500);
    CHECK(support::seam_gaps(*b) == 0);
  }
}

TEST_CASE("shell: a developable mold of three faces drapes as the plane it unrolls to") {
  // Flange + fillet + wall (L = 40, r = 10, Hw = 40, W = 60) unrolls to the rectangle
  // 60 x (80 + 5 pi): threads along and across the fillet stay square (every thread angle
  // pi/2), the net is the plane's node for node, and the flat pattern's area is the shell's
  // area to O(d^2) (0.1 % asked; the outline's corners and the faces' free edges are exact).
  const Shell sh = make_shell("flange-fillet-wall");
  auto fd = builtin_mold("plane", {{"W", 80 + 5 * kPi}, {"H", 60}});
  REQUIRE(fd.ok());
  const Face plane = make_face(std::move(fd).value());
  for (const double d : {1.0, 0.5}) {
    INFO("d = " << d);
    auto pb = support::problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                               Vec3(-20, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)});
    auto r = drape(sh, pb);
    REQUIRE(r.ok());
    CHECK_FALSE(r->partial);
    CHECK(r->metrics.gamma_min == Approx(kPi / 2).margin(1e-9));
    CHECK(r->metrics.gamma_max == Approx(kPi / 2).margin(1e-9));
    CHECK(r->metrics.edge_length_max_rel < 1e-12);
    CHECK(r->metrics.crease_angle_max < 1e-9);  // tangent joins
    CHECK(support::seam_gaps(*r) == 0);
    for (const auto& f : r->metrics.faces) CHECK(f.mapped > 0);
    // The unrolled plane, started at the same distance (20) from the flange's free edge.
    auto pp = pb;
    pp.start = Vec3(20, 30, 0);
    auto q = drape(plane, pp);
    REQUIRE(q.ok());
    CHECK(r->metrics.nodes.mapped == q->metrics.nodes.mapped);
    CHECK(r->metrics.nodes.outside == q->metrics.nodes.outside);
    const FlatPattern fp = flat_pattern(sh, *r);
    REQUIRE(fp.outline.size() == 1);
    CHECK(std::abs(fp.area / sh.area() - 1.0) < 1e-3);
    CHECK(fp.perimeter == Approx(2 * (80 + 5 * kPi) + 120).epsilon(1e-3));
    // Every outline point has its point on the mold.
    for (const Vec3& p : fp.outline[0].points3d) CHECK(sh.project(p).distance < 1e-9);
  }
}

TEST_CASE("shell: the cloth crosses a crease sharper than 90 degrees (a thin flange's edge)") {
  // Two planar faces folded along the Y axis like a thin flange's edge: face 0 in z = 0 for
  // -20 <= x <= 0, face 1 going back under it at 30 degrees (opening 30 degrees, crease 150).
  // With threads along and across the edge the net is known in closed form: the weft threads
  // stay lines parallel to the edge (every thread angle pi/2), and along a warp thread the
  // link that spans the edge is a chord of length d: from a node at a before the edge, the
  // next lies at b = a cos(30) + sqrt(d^2 - a^2 sin^2(30)) past it, the rest at b + k d.
  const double open = 30.0 * kDegToRad, d = 1.0, x0 = -9.5;
  const Vec3 back(-std::cos(open), 0, -std::sin(open));
  const Shell sh = hinge(Vec3(20, 0, 0), 20 * back, 20);
  auto pb = support::problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(1, 0), Vec2(-1, 0)}, Vec3(x0, 10, 0),
                             Vec3(1, 0, 0), {Vec3(1, 0, 0), Vec3(-1, 0, 0)});
  auto r = drape(sh, pb);
  REQUIRE(r.ok());
  support::check_clean_crossing(*r);
  CHECK(r->metrics.crease_angle_max == Approx(kPi - open).epsilon(1e-9));
  const double a = -x0 - 9 * d;  // the last node before the edge lies a before it
  const double b = a * std::cos(open) + std::sqrt(d * d - a * a * std::sin(open) * std::sin(open));
  std::size_t beyond = 0, checked = 0;
  double worst = 0.0;
  for (const DrapeNode& n : r->nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    const int i = static_cast<int>(std::lround(n.ply.x() / d));
    Vec3 want;
    if (i <= 9) {
      want = Vec3(x0 + i * d, n.point.y(), 0.0);
    } else {
      want = (b + (i - 10) * d) * back + Vec3(0, n.point.y(), 0);
      ++beyond;
    }
    worst = std::max(worst, (n.point - want).norm());
    // The weft threads stay parallel to the edge: y is the start's, moved by the ply's y.
    worst = std::max(worst, std::abs(std::abs(n.point.y() - 10) - std::abs(n.ply.y())));
    ++checked;
  }
  CHECK(worst < 1e-9 * d);
  CHECK(beyond > 100);                        // the cloth went round the edge
  CHECK(checked == r->metrics.nodes.mapped);  // regular nodes: the path's ply x is 0
}
