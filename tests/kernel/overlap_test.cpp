// The overlap test is complete (issue 13 item 4): every mapped node that lands on cloth
// already laid is flagged, on open faces too, not only on faces that close on themselves.
#include <plyfit/kernel/analytic_surfaces.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/face.hpp>

#include <catch2/catch.hpp>

#include "support/problems.hpp"

#include <cmath>
#include <string>

using namespace plyfit;
using plyfit::support::problem;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The drape's overlap criterion (scanner.hpp), restated: a node within this fraction of d
// (3D) of another at least kSeparation d away from it on the ply lies on cloth already laid.
constexpr double kNearRel = 0.5;
constexpr double kSeparation = 2.0;

// Pairs of mapped nodes that break the criterion, by brute force.
int cloth_on_cloth(const DrapeResult& r, double d) {
  int pairs = 0;
  for (std::size_t a = 0; a < r.nodes.size(); ++a) {
    const DrapeNode& p = r.nodes[a];
    if (!p.mapped()) continue;
    for (std::size_t b = a + 1; b < r.nodes.size(); ++b) {
      const DrapeNode& q = r.nodes[b];
      if (q.mapped() && (p.point - q.point).norm() < kNearRel * d &&
          (p.ply - q.ply).norm() >= kSeparation * d)
        ++pairs;
    }
  }
  return pairs;
}

}  // namespace

TEST_CASE("drape: cloth landing on cloth already laid is flagged on an open face") {
  // An open cylinder face running 450 degrees round its axis: the first quarter turn is
  // covered twice. Base path along the axis half-way round, swept both ways round: the
  // fronts lay cloth over the same quarter turn from both ends. The net is not sheared.
  for (double d : {1.0, 0.7}) {
    INFO("d = " << d);
    FaceData fd;
    fd.surface = cylinder_patch(10.0, 0.0, 2.5 * kPi, 0.0, 20.0);
    auto f = Face::create(std::move(fd));
    REQUIRE(f.ok());
    REQUIRE_FALSE(f.value().closes_on_itself());
    const double a = 1.25 * kPi;  // half-way round
    const Vec3 s3(10 * std::cos(a), 10 * std::sin(a), 10.0);
    const Vec3 t(-std::sin(a), std::cos(a), 0.0);  // round the axis, increasing angle
    auto rr = drape(f.value(), problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(1, 0), Vec2(-1, 0)}, s3, t,
                                       {t, Vec3(-t)}));
    REQUIRE(rr.ok());
    const DrapeResult& r = rr.value();
    CHECK(r.metrics.nodes.overlap > 0);
    CHECK(r.metrics.nodes.failed == 0);
    CHECK(cloth_on_cloth(r, d) == 0);
    // A full turn of cloth is laid: about the face's circumference times its height.
    CHECK(r.metrics.surface_area > 0.9 * 2 * kPi * 10 * 20);
  }
}
