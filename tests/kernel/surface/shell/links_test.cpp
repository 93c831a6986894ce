// How the faces of a shell join: shared edges and creases, free boundaries, the faces reached
// from one across edges no sharper than a crease angle, and the shell of some of the faces.
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/mold.hpp>
#include "geometry/analytic_surfaces.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plyfit;

namespace {

// A tangent join measures no crease beyond the rounding of the normals.
constexpr double kTangentCrease = 1e-9;
// Straight boundaries: the polyline's length is the side's, to rounding.
constexpr double kStraightLengthRel = 1e-12;

// Three planar faces W wide along Y: face 0 (-10 <= x <= 0) and face 1 (0 <= x <= 10) in the
// plane z = 0, joined flat along x = 0 (edge 0); face 2 the wall x = 10, 0 >= z >= -10, meeting
// face 1 at a 90 degree crease along x = 10, z = 0 (edge 1). Outward normals +Z, +Z, +X.
constexpr double kW = 20.0;
ShellData strip_and_wall() {
  ShellData sd;
  FaceData f0, f1, f2;
  f0.surface = plane_patch(Vec3(-10, 0, 0), Vec3(10, 0, 0), Vec3(0, kW, 0));
  f1.surface = plane_patch(Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(0, kW, 0));
  f2.surface = plane_patch(Vec3(10, 0, 0), Vec3(0, 0, -10), Vec3(0, kW, 0));
  const std::vector<Vec2> square = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  f0.loops.push_back({square, {-1, 0, -1, -1}});
  f1.loops.push_back({square, {-1, 1, -1, 0}});
  f2.loops.push_back({square, {-1, -1, -1, 1}});
  sd.faces = {f0, f1, f2};
  sd.edge_count = 2;
  sd.source_faces = {4, 7, 9};
  return sd;
}

MoldSurface shell_of(ShellData data) {
  auto s = MoldSurface::from_shell(std::move(data));
  INFO((s.ok() ? "" : exporters::describe(s.error())));
  REQUIRE(s.ok());
  return std::move(s).value();
}

}  // namespace

TEST_CASE("links: shared edges name their faces and their crease angles") {
  const MoldSurface s = shell_of(strip_and_wall());
  const std::vector<SharedEdge> edges = s.shared_edges();
  REQUIRE(edges.size() == 2);
  CHECK(std::min(edges[0].face_a, edges[0].face_b) == 0);
  CHECK(std::max(edges[0].face_a, edges[0].face_b) == 1);
  CHECK(edges[0].crease < kTangentCrease);
  CHECK(std::min(edges[1].face_a, edges[1].face_b) == 1);
  CHECK(std::max(edges[1].face_a, edges[1].face_b) == 2);
  CHECK(edges[1].crease == Approx(kPi / 2).epsilon(1e-12));

  auto one = MoldSurface::from_face(strip_and_wall().faces[0]);
  REQUIRE(one.ok());
  CHECK(one->shared_edges().empty());
}

TEST_CASE("links: connected faces stop at creases sharper than the limit") {
  const MoldSurface s = shell_of(strip_and_wall());
  using F = std::vector<std::int32_t>;
  CHECK(connected_faces(s, 0, 60 * kDegToRad) == F{0, 1});
  CHECK(connected_faces(s, 0, 89 * kDegToRad) == F{0, 1});
  CHECK(connected_faces(s, 0, 91 * kDegToRad) == F{0, 1, 2});
  CHECK(connected_faces(s, 2, 60 * kDegToRad) == F{2});
  CHECK(connected_faces(s, 2, kPi) == F{2, 1, 0});
}

TEST_CASE("links: the flange, fillet and wall join tangentially: all three are connected") {
  auto data = builtin_shell("flange-fillet-wall", {});
  REQUIRE(data.ok());
  const MoldSurface s = shell_of(std::move(data).value());
  for (const SharedEdge& e : s.shared_edges()) CHECK(e.crease < kTangentCrease);
  using F = std::vector<std::int32_t>;
  CHECK(connected_faces(s, 0, 1 * kDegToRad) == F{0, 1, 2});
  CHECK(connected_faces(s, 2, 1 * kDegToRad) == F{2, 1, 0});
}

TEST_CASE("links: a face's free boundary: runs between shared edges and their length") {
  const MoldSurface s = shell_of(strip_and_wall());
  // Face 0: three free sides in a row (one run), 10 + W + 10 long; face 1: its two sides along
  // X, apart; face 2 as face 0.
  const FreeBoundary f0 = s.free_boundary(0), f1 = s.free_boundary(1), f2 = s.free_boundary(2);
  CHECK(f0.runs == 1);
  CHECK(f0.length == Approx(20 + kW).epsilon(kStraightLengthRel));
  CHECK(f1.runs == 2);
  CHECK(f1.length == Approx(20).epsilon(kStraightLengthRel));
  CHECK(f2.runs == 1);
  CHECK(f2.length == Approx(20 + kW).epsilon(kStraightLengthRel));

  // A face alone: its whole boundary is one free run.
  auto one = MoldSurface::from_face(strip_and_wall().faces[1]);
  REQUIRE(one.ok());
  CHECK(one->free_boundary(0).runs == 1);
  CHECK(one->free_boundary(0).length == Approx(20 + 2 * kW).epsilon(kStraightLengthRel));
}

TEST_CASE("links: the shell of some faces keeps the edges between them, frees the others") {
  const ShellData all = strip_and_wall();
  const ShellData sub = sub_shell(all, {1, 2});
  CHECK(sub.edge_count == 1);
  CHECK(sub.source_faces == std::vector<int>{7, 9});
  const MoldSurface s = shell_of(sub);
  REQUIRE(s.shared_edges().size() == 1);
  CHECK(s.shared_edges()[0].crease == Approx(kPi / 2).epsilon(1e-12));
  CHECK(s.area() == Approx(2 * 10 * kW).epsilon(1e-12));
  // Face 1 of the file, now face 0: the edge to the face left out is free, one run with its
  // two sides along X.
  CHECK(s.free_boundary(0).runs == 1);
  CHECK(s.free_boundary(0).length == Approx(20 + kW).epsilon(kStraightLengthRel));

  const ShellData lone = sub_shell(all, {0, 2});
  CHECK(lone.edge_count == 0);
  const MoldSurface apart = shell_of(lone);
  CHECK(apart.shared_edges().empty());
  CHECK(apart.free_boundary(0).runs == 1);
  CHECK(apart.free_boundary(0).length == Approx(20 + 2 * kW).epsilon(kStraightLengthRel));
}
