// A seed curve given as a polyline (SeedCurve::kCurve): the base path walks it at link length.
// Against the plane section on the sphere (a great circle sampled densely), a helix on the
// cylinder against the geodesic there, and its two errors.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"

#include <cmath>

using namespace plyfit;
using plyfit::support::builtin_surface;

namespace {
constexpr double kDeg = kPi / 180.0;

DrapeProblem problem(const MoldSurface& mold, const PlyDefinition& def, double d) {
  PlySpec cloth;
  cloth.d_weft = cloth.d_warp = d;
  auto pb = ply_problem(mold, def, cloth);
  REQUIRE(pb);
  return std::move(pb).value();
}

DrapeResult drape_ok(const MoldSurface& mold, const DrapeProblem& pb) {
  auto r = drape(mold, pb, DrapeOptions{});
  INFO((r ? std::string() : std::string(to_string(r.error().code))));
  REQUIRE(r);
  return std::move(r).value();
}

// The mapped base-path nodes in path order.
std::vector<const DrapeNode*> path_nodes(const DrapeResult& r) {
  std::vector<const DrapeNode*> out;
  for (std::uint32_t k : r.base_path)
    if (r.nodes[k].mapped()) out.push_back(&r.nodes[k]);
  return out;
}

void check_links(const std::vector<const DrapeNode*>& p, double d, double rel) {
  for (std::size_t k = 1; k < p.size(); ++k)
    CHECK(std::abs((p[k]->point - p[k - 1]->point).norm() - d) < rel * d);
}

// The great circle of radius R about the origin in the plane of unit normal m, through `a`
// (on it): 2n + 1 points over a half turn either side of a, those with z >= 0 (on the
// hemisphere; one arc, since z is a sinusoid of the angle, positive at a and negative at the
// half turns).
std::vector<Vec3> great_circle(const Vec3& a, const Vec3& m, double R, int n) {
  const Vec3 e1 = a.normalized(), e2 = m.cross(e1).normalized();
  std::vector<Vec3> out;
  for (int k = -n; k <= n; ++k) {
    const double t = kPi * k / n;
    const Vec3 p = R * (std::cos(t) * e1 + std::sin(t) * e2);
    if (p.z() >= 0.0) out.push_back(p);
  }
  return out;
}

struct SphereCase {
  double R = 10.0, d = 0.25;
  MoldSurface sphere = builtin_surface("hemisphere", {{"R", 10.0}});
  PlyDefinition def;
  SphereCase() {
    const double th = 50 * kDeg, ph = 20 * kDeg;
    def.seed = R * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    def.rosette = Vec3(0, 0, 1);
    def.angle = 35 * kDeg;
  }
  // The base plane's normal: the great circle through the seed along the warp.
  Vec3 plane_normal() const {
    auto f = ply_frame(sphere, def);
    REQUIRE(f);
    return f->point.cross(f->warp).normalized();
  }
};
}  // namespace

TEST_CASE("seed curve: a file's curve equal to the plane section gives the plane case's path") {
  const SphereCase c;
  const Vec3 m = c.plane_normal();
  DrapeProblem pb = problem(c.sphere, c.def, c.d);
  const DrapeResult sec = drape_ok(c.sphere, pb);
  pb.seed_curve = SeedCurve::kCurve;
  pb.seed_polyline = great_circle(c.def.seed, m, c.R, 8000);
  const DrapeResult cur = drape_ok(c.sphere, pb);
  CHECK(cur.seed_curve == SeedCurve::kCurve);
  const auto pc = path_nodes(cur), ps = path_nodes(sec);
  REQUIRE(pc.size() > 40);
  // Each node of the curve's path is the plane case's node of the same id, on the sphere, in
  // the plane, at link length from the one before.
  std::size_t same = 0;
  for (const DrapeNode* n : pc) {
    CHECK(std::abs(n->point.norm() - c.R) < 1e-10 * c.d);
    CHECK(std::abs(m.dot(n->point)) < 1e-10 * c.d);
    const DrapeNode* s = sec.find(n->id);
    REQUIRE(s);
    CHECK((n->point - s->point).norm() < 1e-10 * c.d);
    same += (n->point - s->point).norm() < 1e-10 * c.d;
  }
  // The curve's last sample lies within one sample of the rim, where the section ends.
  CHECK(same + 2 >= ps.size());
  check_links(pc, c.d, 1e-10);
}

TEST_CASE("seed curve: a helix on the cylinder is followed; the geodesic is that helix") {
  const double R = 10.0, H = 40.0, d = 0.25;
  const MoldSurface cyl = builtin_surface("cylinder", {{"R", R}, {"H", H}, {"angle", 180.0}});
  PlyDefinition def;
  def.seed = Vec3(0, R, H / 2);
  def.rosette = Vec3(0, 0, 1);
  def.angle = 30 * kDeg;
  auto f = ply_frame(cyl, def);
  REQUIRE(f);
  // The helix through the seed along the warp: at the seed, e_phi = (-1, 0, 0), e_z = (0, 0, 1).
  const double dphi = f->warp.dot(Vec3(-1, 0, 0)) / R, dz = f->warp.dot(Vec3(0, 0, 1));
  std::vector<Vec3> helix;
  const double step = 0.005;  // arc length: chords off the helix by ~ (sin^2 30 / R) step^2 / 8
  for (double s = -60.0; s <= 60.0; s += step) {
    const double phi = kPi / 2 + dphi * s, z = H / 2 + dz * s;
    if (phi >= 0.0 && phi <= kPi && z >= 0.0 && z <= H)  // on the half cylinder
      helix.emplace_back(R * std::cos(phi), R * std::sin(phi), z);
  }
  DrapeProblem pb = problem(cyl, def, d);
  pb.seed_curve = SeedCurve::kGeodesic;
  const DrapeResult geo = drape_ok(cyl, pb);
  pb.seed_curve = SeedCurve::kCurve;
  pb.seed_polyline = helix;
  const DrapeResult cur = drape_ok(cyl, pb);
  const auto pc = path_nodes(cur);
  REQUIRE(pc.size() > 40);
  check_links(pc, d, 1e-10);
  // On the cylinder, and on the helix: unrolled, (R phi - R pi/2, z - H/2) on the line of
  // slope dz / (R dphi), to the polyline's chord offset.
  const double ka = std::pow(std::sin(def.angle), 2) / R;
  const double chord_off = ka * step * step / 8;
  const Vec2 t = Vec2(R * dphi, dz).normalized();
  for (const DrapeNode* n : pc) {
    CHECK(std::abs(std::hypot(n->point.x(), n->point.y()) - R) < 1e-10 * d);
    const Vec2 q(R * (std::atan2(n->point.y(), n->point.x()) - kPi / 2), n->point.z() - H / 2);
    CHECK(std::abs(cross2(t, q)) < 2 * chord_off + 1e-10 * d);
  }
  // The geodesic's path is the helix to its own first-step error (seed_curve_test.cpp: its
  // direction off by at most curvature x torsion x d^2, so its points off by that times their
  // distance from the seed).
  const double tau = std::sin(def.angle) * std::cos(def.angle) / R;
  for (const DrapeNode* n : pc) {
    const DrapeNode* g = geo.find(n->id);
    if (!g || !g->mapped()) continue;
    const double along = (n->point - cur.start_point).norm();
    CHECK((n->point - g->point).norm() < ka * tau * d * d * along + 2 * chord_off + 1e-10 * d);
  }
}

TEST_CASE("seed curve: a curve off the mold, a seed off the curve are errors") {
  const SphereCase c;
  const Vec3 m = c.plane_normal();
  DrapeProblem pb = problem(c.sphere, c.def, c.d);
  pb.seed_curve = SeedCurve::kCurve;
  // 1 % of the sphere's size off it: past seed_curve_rel (0.1 %).
  std::vector<Vec3> lifted = great_circle(c.def.seed, m, c.R * 1.02, 400);
  pb.seed_polyline = lifted;
  auto off = drape(c.sphere, pb, DrapeOptions{});
  REQUIRE_FALSE(off);
  CHECK(off.error().code == ErrorCode::kSeedCurveOffMold);
  // A great circle on the sphere that misses the seed.
  const Eigen::AngleAxisd turn(20 * kDeg, Vec3(0, 0, 1));
  pb.seed_polyline = great_circle(turn * c.def.seed, turn * m, c.R, 400);
  auto miss = drape(c.sphere, pb, DrapeOptions{});
  REQUIRE_FALSE(miss);
  CHECK(miss.error().code == ErrorCode::kSeedNotOnCurve);
}
