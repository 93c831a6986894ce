// The ply definition (seed, rosette, ply angle) against closed forms on the plate, the
// cylinder and the sphere.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"

#include <cmath>

using namespace plyfit;
using plyfit::support::builtin_surface;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

PlySpec cloth(double d) {
  PlySpec s;
  s.d_weft = s.d_warp = d;
  return s;
}

/// The bounding box of a flat pattern's outline in ply coordinates.
Vec2 outline_extent(const FlatPattern& f) {
  Vec2 lo = Vec2::Constant(1e300), hi = -lo;
  for (const auto& loop : f.outline)
    for (const Vec2& p : loop.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return hi - lo;
}
}  // namespace

TEST_CASE("ply definition: on the plate the warp runs at the ply angle from the rosette") {
  const MoldSurface plate = builtin_surface("plate");  // 100 x 60 in z = 0, normal +Z
  for (double deg : {0.0, 45.0, 90.0, -45.0, 180.0, 30.0}) {
    CAPTURE(deg);
    PlyDefinition def;
    def.seed = Vec3(50, 30, 5);  // above the plate: projected onto it
    def.rosette = Vec3(1, 0, 0.3);
    def.angle = deg * kDeg;
    auto f = ply_frame(plate, def);
    REQUIRE(f);
    CHECK((f->point - Vec3(50, 30, 0)).norm() < 1e-12);
    CHECK(f->moved == Approx(5.0));
    // Counter-clockwise seen from outside (+Z): 90 deg is normal x 0 deg = +Y.
    CHECK((f->warp - Vec3(std::cos(def.angle), std::sin(def.angle), 0)).norm() < 1e-12);
    CHECK((f->weft - f->warp.cross(Vec3::UnitZ())).norm() < 1e-12);
    CHECK(f->angle == Approx(def.angle).margin(1e-12));
  }
}

TEST_CASE("ply definition: the plate draped at 0/45/90/-45 has its outline turned by the angle") {
  const MoldSurface plate = builtin_surface("plate");
  for (double deg : {0.0, 45.0, 90.0, -45.0}) {
    CAPTURE(deg);
    PlyDefinition def;
    def.seed = Vec3(50, 30, 0);
    def.angle = deg * kDeg;
    auto pb = ply_problem(plate, def, cloth(1.0));
    REQUIRE(pb);
    auto r = drape(plate, *pb, DrapeOptions{});
    REQUIRE(r);
    CHECK_FALSE(r->partial);
    // The plate is flat: ply x along the weft, y along the warp, both exact. Its corners
    // (relative to the seed) span 100|cos| + 60|sin| along the warp, 100|sin| + 60|cos| across.
    const FlatPattern flat = flat_pattern(plate, *r);
    const double c = std::abs(std::cos(def.angle)), s = std::abs(std::sin(def.angle));
    const Vec2 ext = outline_extent(flat);
    CHECK(ext.x() == Approx(100 * s + 60 * c).margin(1e-9));
    CHECK(ext.y() == Approx(100 * c + 60 * s).margin(1e-9));
    CHECK(flat.area == Approx(6000.0).epsilon(1e-9));
    // The drape laid the warp where the definition asked.
    auto laid = draped_frame(plate, *r, def.rosette);
    REQUIRE(laid);
    CHECK(laid->angle == Approx(def.angle).margin(1e-12));
  }
}

TEST_CASE("ply definition: paper conditions turned by an angle lay the warp turned by it") {
  const MoldSurface plate = builtin_surface("plate");
  DrapeProblem pb;  // the paper's flags: base path along +X (base2d (1, 0)), sweeps +-Y
  pb.ply = cloth(1.0);
  pb.ply.base_dir = Vec2(1, 0);
  pb.ply.sweeps = {Vec2(0, 1), Vec2(0, -1)};
  pb.start = Vec3(50, 30, 0);
  pb.base_normal = Vec3(0, 1, 0);
  pb.sweeps = {Vec3(0, 1, 0), Vec3(0, -1, 0)};
  auto r0 = drape(plate, pb, DrapeOptions{});
  REQUIRE(r0);
  // Base path along +X is ply +x: the warp (ply +y) is +Y, 90 deg from a rosette along X.
  auto f0 = draped_frame(plate, *r0, Vec3::UnitX());
  REQUIRE(f0);
  CHECK(f0->angle == Approx(90 * kDeg).margin(1e-12));
  auto turned = turned_problem(plate, pb, -30 * kDeg);
  REQUIRE(turned);
  auto r1 = drape(plate, *turned, DrapeOptions{});
  REQUIRE(r1);
  auto f1 = draped_frame(plate, *r1, Vec3::UnitX());
  REQUIRE(f1);
  CHECK(f1->angle == Approx(60 * kDeg).margin(1e-12));
}

TEST_CASE("ply definition: on a cylinder the rosette is projected onto the tangent plane") {
  // Builtin cylinder: x^2 + y^2 = R^2, outward normal radial.
  const MoldSurface cyl = builtin_surface("cylinder", {{"R", 10.0}, {"H", 20.0}, {"angle", 90.0}});
  PlyDefinition def;
  const double a = 30 * kDeg;
  def.seed = Vec3(10 * std::cos(a), 10 * std::sin(a), 10);
  def.rosette = Vec3(1, 0, 0);  // projected: -sin(a) times the circle's tangent
  def.angle = 0.0;
  auto f = ply_frame(cyl, def);
  REQUIRE(f);
  const Vec3 n(std::cos(a), std::sin(a), 0);
  const Vec3 expected = (Vec3(1, 0, 0) - std::cos(a) * n).normalized();
  CHECK(std::abs(f->normal.dot(n)) == Approx(1.0).margin(1e-12));
  CHECK((f->zero - expected).norm() < 1e-12);
  CHECK((f->warp - expected).norm() < 1e-12);
}

TEST_CASE("ply definition: bad seeds, rosettes and angles are errors naming the input") {
  const MoldSurface plate = builtin_surface("plate");
  PlyDefinition def;
  def.seed = Vec3(50, 30, 0);
  SECTION("a seed far from the mold") {
    def.seed = Vec3(50, 30, 1000);
    auto f = ply_frame(plate, def);
    REQUIRE_FALSE(f);
    CHECK(f.error().code == ErrorCode::kSeedOffMold);
    CHECK(f.error().input == "seed");
  }
  SECTION("a seed not finite") {
    def.seed = Vec3(50, std::nan(""), 0);
    auto f = ply_frame(plate, def);
    REQUIRE_FALSE(f);
    CHECK(f.error().code == ErrorCode::kSeedNotFinite);
  }
  SECTION("a rosette along the normal") {
    def.rosette = Vec3(1e-5, 0, 1);
    auto f = ply_frame(plate, def);
    REQUIRE_FALSE(f);
    CHECK(f.error().code == ErrorCode::kRosetteAlongNormal);
    CHECK(f.error().input == "rosette");
  }
  SECTION("a zero rosette") {
    def.rosette = Vec3::Zero();
    auto f = ply_frame(plate, def);
    REQUIRE_FALSE(f);
    CHECK(f.error().code == ErrorCode::kRosetteZero);
  }
  SECTION("an angle out of range") {
    def.angle = 200 * kDeg;
    auto f = ply_frame(plate, def);
    REQUIRE_FALSE(f);
    CHECK(f.error().code == ErrorCode::kPlyAngleRange);
    CHECK(f.error().input == "ply-angle");
  }
}
