// The built-in propeller blade (issue 13, "failed nodes on a real blade"): a long, thin,
// twisted bicubic of 242 x 13 poles with knots clustered at the root and the tip, trimmed by
// a blade outline inside its domain; drapes on it reach every node they can.
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"

#include <catch2/catch.hpp>

#include "support/problems.hpp"

#include <algorithm>
#include <cmath>
#include "surface/face.hpp"

using namespace plyfit;

namespace {

Face blade(const std::map<std::string, double>& p = {}) {
  auto fd = builtin_mold("blade", p);
  INFO((fd.ok() ? std::string() : exporters::describe(fd.error())));
  REQUIRE(fd.ok());
  auto f = Face::create(std::move(fd).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

}  // namespace

TEST_CASE("blade: a bicubic of 242 x 13 poles, knots clustered at both ends, x = span * u") {
  const Face f = blade();
  const NurbsSurfaceData& s = f.surface().data();
  CHECK(s.degree_u == 3);
  CHECK(s.degree_v == 3);
  CHECK(s.count_u == 242);
  CHECK(s.count_v == 13);
  CHECK(s.weights.empty());
  // Knot spans along the span: the end ones over 100 times shorter than the middle ones.
  double shortest = 1.0, longest = 0.0;
  for (std::size_t k = 3; k + 4 < s.knots_u.size(); ++k) {
    const double h = s.knots_u[k + 1] - s.knots_u[k];
    shortest = std::min(shortest, h);
    longest = std::max(longest, h);
  }
  CHECK(longest > 100 * shortest);
  CHECK(s.knots_u[4] - s.knots_u[3] == shortest);
  // The poles sit at the knots' Greville abscissae along X, so x = 240 u exactly (a cubic
  // B-spline reproduces a linear function).
  for (double u : {0.0, 1e-4, 0.01, 0.3, 0.77, 0.999, 1.0})
    for (double v : {0.0, 0.4, 1.0})
      CHECK(f.eval1(Vec2(u, v)).p.x() == Approx(240.0 * u).margin(1e-12));
  // Twisted: the chord line at the root and at the tip differ by the twist (45 degrees).
  auto pitch = [&](double u) {
    const Vec3 d = f.eval1(Vec2(u, 1.0)).p - f.eval1(Vec2(u, 0.0)).p;
    return std::atan2(d.z(), d.y()) * kRadToDeg;
  };
  CHECK(pitch(0.0) - pitch(1.0) == Approx(45.0).margin(0.5));
}

TEST_CASE("blade: the outline is a trim inside the domain, not its border") {
  const Face f = blade();
  REQUIRE(f.loops().size() == 1);
  double u0 = 1, u1 = 0, v0 = 1, v1 = 0;
  for (const Vec2& p : f.loops()[0].points) {
    u0 = std::min(u0, p.x());
    u1 = std::max(u1, p.x());
    v0 = std::min(v0, p.y());
    v1 = std::max(v1, p.y());
  }
  CHECK(u0 == Approx(0.04));                // the root cut
  CHECK(u1 == Approx(0.985).margin(1e-6));  // the tip's apex
  CHECK(v0 > 0.05);
  CHECK(v1 < 0.95);
  CHECK(f.contains(SurfaceLocation(Vec2(0.5, 0.5))));
  CHECK_FALSE(f.contains(SurfaceLocation(Vec2(0.02, 0.5))));  // below the root cut
  CHECK_FALSE(f.contains(SurfaceLocation(Vec2(0.99, 0.5))));  // beyond the tip
  CHECK_FALSE(f.contains(SurfaceLocation(Vec2(0.5, 0.02))));  // past the trailing edge
  // Bad parameters are errors naming the mold.
  for (const auto& bad : std::vector<std::map<std::string, double>>{
           {{"nu", 7}}, {{"nv", 3.5}}, {{"chord", 0}}, {{"camber", -0.1}}, {{"twist", 120}}}) {
    auto fd = builtin_mold("blade", bad);
    REQUIRE_FALSE(fd.ok());
    CHECK(exporters::describe(fd.error()).find("blade") != std::string::npos);
  }
}

TEST_CASE("blade: drapes along and across the span map every node they reach") {
  const Face f = blade();
  struct Case {
    const char* what;
    Vec3 start, base_normal, sweep;
    double d;
  };
  const Case cases[] = {
      {"base path across the chord at mid-span, sweeps to root and tip", Vec3(120, 10, 5),
       Vec3(1, 0, 0), Vec3(1, 0, 0), 1.0},
      {"base path along the span, sweeps to the edges", Vec3(120, 10, 5), Vec3(0, 0.6, -0.8),
       Vec3(0, 0.8, 0.6), 1.0},
      {"base path across the chord near the tip, fine spacing", Vec3(215, 20, -5), Vec3(1, 0, 0),
       Vec3(1, 0, 0), 0.5},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    auto r = drape(f,
                   support::problem(c.d, Vec2(0, 0), Vec2(0, 1), {Vec2(1, 0), Vec2(-1, 0)}, c.start,
                                    c.base_normal, {c.sweep, -c.sweep}),
                   DrapeOptions{});
    REQUIRE(r.ok());
    const DrapeMetrics& m = r->metrics;
    CHECK(m.nodes.failed == 0);
    CHECK(m.nodes.conflict == 0);
    CHECK(m.nodes.mapped > 200);
    CHECK(m.edge_length_max_rel < 1e-9);
    CHECK(m.surface_distance_max < 1e-9 * f.size());
    // Every mapped node lies on the face, inside the outline.
    for (const DrapeNode& n : r->nodes)
      if (n.mapped()) CHECK(f.contains(n.at()));
  }
}
