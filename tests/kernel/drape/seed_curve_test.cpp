// The geodesic seed curve against closed forms: great circles on the sphere (the plane section
// through the normal), helices on the cylinder, straight lines in the cone's development.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"

#include <cmath>

using namespace plyfit;
using plyfit::support::builtin_surface;

namespace {
constexpr double kDeg = kPi / 180.0;

DrapeResult drape_ply(const MoldSurface& mold, const PlyDefinition& def, double d, SeedCurve c) {
  PlySpec cloth;
  cloth.d_weft = cloth.d_warp = d;
  auto pb = ply_problem(mold, def, cloth);
  REQUIRE(pb);
  pb->seed_curve = c;
  auto r = drape(mold, *pb, DrapeOptions{});
  REQUIRE(r);
  return std::move(r).value();
}

std::vector<Vec3> path_points(const DrapeResult& r) {
  std::vector<Vec3> out;
  for (std::uint32_t k : r.base_path)
    if (r.nodes[k].mapped()) out.push_back(r.nodes[k].point);
  return out;
}

/// Largest |distance from the line through a and b| of the points q (2D).
double off_line(const std::vector<Vec2>& q) {
  const Vec2 a = q.front(), t = (q.back() - q.front()).normalized();
  double worst = 0.0;
  for (const Vec2& p : q) worst = std::max(worst, std::abs(cross2(t, p - a)));
  return worst;
}

/// Every consecutive pair of path points at the link length, to `rel` of it.
void check_links(const std::vector<Vec3>& p, double d, double rel) {
  for (std::size_t k = 1; k < p.size(); ++k)
    CHECK(std::abs((p[k] - p[k - 1]).norm() - d) < rel * d);
}
}  // namespace

TEST_CASE("seed curve: on the sphere the geodesic is the great circle, the plane section") {
  const double R = 10.0, d = 0.25;
  const MoldSurface sphere = builtin_surface("hemisphere", {{"R", R}});
  PlyDefinition def;
  const double th = 50 * kDeg, ph = 20 * kDeg;
  def.seed = R * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  def.rosette = Vec3(0, 0, 1);
  def.angle = 35 * kDeg;
  const DrapeResult geo = drape_ply(sphere, def, d, SeedCurve::kGeodesic);
  const DrapeResult sec = drape_ply(sphere, def, d, SeedCurve::kPlane);
  const std::vector<Vec3> pg = path_points(geo), ps = path_points(sec);
  REQUIRE(pg.size() > 40);
  REQUIRE(pg.size() == ps.size());
  // The great circle's plane: through the centre, the seed and the warp there.
  auto f = ply_frame(sphere, def);
  REQUIRE(f);
  const Vec3 m = f->point.cross(f->warp).normalized();
  for (std::size_t k = 0; k < pg.size(); ++k) {
    CHECK(std::abs(m.dot(pg[k])) < 1e-10 * d);
    CHECK(std::abs(pg[k].norm() - R) < 1e-10 * d);
    CHECK((pg[k] - ps[k]).norm() < 1e-10 * d);
  }
  check_links(pg, d, 1e-10);
  CHECK(geo.metrics.base_plane_max_rel < 1e-10);
}

TEST_CASE("seed curve: on the cylinder the geodesic is a helix and the ply lies unsheared") {
  const double R = 10.0, H = 40.0;
  const MoldSurface cyl = builtin_surface("cylinder", {{"R", R}, {"H", H}, {"angle", 180.0}});
  PlyDefinition def;
  def.seed = Vec3(0, R, H / 2);
  def.rosette = Vec3(0, 0, 1);  // 0 deg along the axis
  def.angle = 30 * kDeg;
  std::vector<double> shear, area_err;
  for (double d : {0.5, 0.25}) {
    const DrapeResult geo = drape_ply(cyl, def, d, SeedCurve::kGeodesic);
    const std::vector<Vec3> p = path_points(geo);
    REQUIRE(p.size() > 40);
    check_links(p, d, 1e-10);
    CHECK(geo.metrics.base_plane_max_rel < 1e-10);
    // Unrolled, (R phi, z) of a helix lie on one straight line.
    std::vector<Vec2> flat;
    for (const Vec3& x : p) flat.emplace_back(R * std::atan2(x.y(), x.x()), x.z());
    CHECK(off_line(flat) < 1e-9 * d);
    // At the ply angle from the axis, to the second order of the first step (it leaves the
    // seed in the normal plane of the warp: off the helix by curvature x torsion x d^2 / 6).
    const Vec2 t = (flat.back() - flat.front()).normalized();
    const double ka = std::pow(std::sin(def.angle), 2) / R;
    const double tau = std::sin(def.angle) * std::cos(def.angle) / R;
    CHECK(std::abs(std::atan2(std::abs(t.x()), std::abs(t.y())) - def.angle) < ka * tau * d * d);
    shear.push_back(geo.metrics.shear_max);
    area_err.push_back(std::abs(flat_pattern(cyl, geo).area / (kPi * R * H) - 1.0));
  }
  // The cylinder is developable: the ply laid from a helix is its isometric image up to the
  // threads' chords (second order in d / R): no shear and the face's area in the limit.
  CAPTURE(shear[0], shear[1], area_err[0], area_err[1]);
  CHECK(shear[0] < 0.01 * kDeg);
  CHECK(shear[1] < shear[0] / 3.0);
  CHECK(area_err[0] < 2e-4);
  CHECK(area_err[1] < area_err[0] / 3.0);
  // The plane section at the same angle is no geodesic: the ply shears far past any lock.
  const DrapeResult sec = drape_ply(cyl, def, 0.5, SeedCurve::kPlane);
  CHECK(sec.metrics.shear_max > 10 * kDeg);
}

TEST_CASE("seed curve: on the cone the geodesic is straight in the development, to order d^2") {
  // Cone about Z: radius 20 at z = 0, 10 at z = 15; apex at z = 30.
  const double r0 = 20.0, r1 = 10.0, H = 15.0;
  const MoldSurface cone =
      builtin_surface("cone", {{"r0", r0}, {"r1", r1}, {"H", H}, {"angle", 180.0}});
  const double za = r0 * H / (r0 - r1);
  const double sin_b = r0 / std::hypot(r0, za);
  auto developed = [&](const Vec3& x) {
    const double rho = std::hypot(std::hypot(x.x(), x.y()), za - x.z());
    const double psi = std::atan2(x.y(), x.x()) * sin_b;
    return Vec2(rho * std::cos(psi), rho * std::sin(psi));
  };
  PlyDefinition def;
  def.seed = Vec3(0, 15.0, 7.5);
  def.rosette = Vec3(0, 0, 1);
  def.angle = 60 * kDeg;
  std::vector<double> err;
  for (double d : {0.4, 0.2}) {
    const DrapeResult geo = drape_ply(cone, def, d, SeedCurve::kGeodesic);
    const std::vector<Vec3> p = path_points(geo);
    REQUIRE(p.size() > 30);
    check_links(p, d, 1e-10);
    std::vector<Vec2> q;
    for (const Vec3& x : p) q.push_back(developed(x));
    err.push_back(off_line(q));
    CHECK(geo.metrics.base_plane_max_rel < 1e-10);
  }
  CAPTURE(err[0], err[1]);
  CHECK(err[0] < 1e-3);
  CHECK(err[1] < err[0] / 3.0);  // second order: a quarter of it at half the link
}

TEST_CASE("seed curve: across the flange, fillet and wall the geodesic is straight unrolled") {
  // The L-shaped shell (flange z = 0, x <= 0; fillet of radius r about x = 0, z = -r; wall
  // x = r) is developable: unrolled along its profile (s: x on the flange, r theta on the
  // fillet, r pi / 2 + (-r - z) down the wall; y kept) a geodesic is a straight line, here at
  // the ply angle from the rosette across the fillet. Every base-path point lies on the shell
  // and at the link length from the one before, to 1e-10 d, on all three faces; the links that
  // cross a change of curvature (flange to fillet, fillet to wall) bend the path off the line
  // by an amount that falls with d (0.74, 0.37, 0.084 um at d = 0.5, 0.25, 0.125 mm).
  const double r = 10.0;
  auto data = builtin_shell("flange-fillet-wall", {});
  REQUIRE(data);
  auto shell = MoldSurface::from_shell(std::move(data).value());
  REQUIRE(shell);
  PlyDefinition def;
  def.seed = Vec3(-20, 15, 0);
  def.rosette = Vec3(1, 0, 0);
  def.angle = 30 * kDeg;  // the warp 30 degrees off +X: across the fillet, up in Y
  std::vector<double> off;
  for (double d : {0.5, 0.125}) {
    CAPTURE(d);
    const DrapeResult geo = drape_ply(*shell, def, d, SeedCurve::kGeodesic);
    const std::vector<Vec3> p = path_points(geo);
    std::vector<Vec2> flat;
    int on_fillet = 0, on_wall = 0;
    for (const Vec3& x : p) {
      CHECK(shell->project(x).distance < 1e-10 * d);
      double s = x.x();
      if (x.x() > 0 && x.z() > -r) {
        s = r * std::atan2(x.x(), x.z() + r);
        ++on_fillet;
      } else if (x.x() > 0) {
        s = r * kPi / 2 + (-r - x.z());
        ++on_wall;
      }
      flat.emplace_back(s, x.y());
    }
    CHECK(on_fillet > 30);
    CHECK(on_wall > 30);
    check_links(p, d, 1e-10);
    CHECK(geo.metrics.base_plane_max_rel < 1e-10);
    const Vec2 t = (flat.back() - flat.front()).normalized();
    CHECK(std::abs(std::atan2(std::abs(t.y()), std::abs(t.x())) - 30 * kDeg) < 1e-3 * kDeg);
    off.push_back(off_line(flat));
    CHECK(off.back() < 2e-3 * d);
  }
  // At least first order in d.
  CAPTURE(off[0], off[1]);
  CHECK(off[1] < off[0] / 4);
}
