// face_start(): the start plyfit info suggests for one face.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/optimize.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"
#include "support/warnings.hpp"

#include <cmath>

using namespace plyfit;
using plyfit::support::builtin_surface;

TEST_CASE("search: on a face closed round along u only, the suggested base path runs along v") {
  // A tube closed round its own circle (u: t from 0 to 360 degrees), open along the ring (v).
  // A path along u would run round the tube and come back onto its start.
  const MoldSurface tube = builtin_surface(
      "torus", {{"R", 50.0}, {"r", 10.0}, {"t0", 0.0}, {"t1", 360.0}, {"angle", 90.0}});
  auto s = face_start(tube);
  REQUIRE(s);
  const SurfaceEval1 e = tube.eval1(SurfaceLocation(s->uv));
  CHECK(std::abs(s->tangent.dot(e.dv.normalized())) == Approx(1.0).margin(1e-12));
  CHECK(std::abs(s->tangent.dot(e.du.normalized())) < 1e-12);
}

TEST_CASE("search: on an open face the suggested base path runs along u") {
  const MoldSurface part = builtin_surface(
      "torus", {{"R", 50.0}, {"r", 10.0}, {"t0", -60.0}, {"t1", 60.0}, {"angle", 90.0}});
  auto s = face_start(part);
  REQUIRE(s);
  const SurfaceEval1 e = part.eval1(SurfaceLocation(s->uv));
  CHECK(std::abs(s->tangent.dot(e.du.normalized())) == Approx(1.0).margin(1e-12));
}

TEST_CASE("search: the suggested start drapes a closed tube without a slit along its base path") {
  const MoldSurface tube = builtin_surface(
      "torus", {{"R", 50.0}, {"r", 10.0}, {"t0", 0.0}, {"t1", 360.0}, {"angle", 60.0}});
  auto s = face_start(tube);
  REQUIRE(s);
  DrapeProblem pb;
  pb.ply.d_weft = pb.ply.d_warp = 2.0;
  pb.ply.base_dir = Vec2(1, 0);
  pb.ply.sweeps = {Vec2(0, 1), Vec2(0, -1)};
  pb.start = s->point;
  pb.base_normal = s->base_normal;
  pb.sweeps = {s->base_normal, -s->base_normal};
  auto r = drape(tube, pb, DrapeOptions{});
  REQUIRE(r);
  // The base path crosses the tube (along the ring) and ends at the face's edges, not on
  // itself: no base-path node overlaps, and no warning of a slit.
  CHECK(support::with_code(r->warnings, WarningCode::kPathSlit).empty());
  CHECK(r->metrics.nodes.mapped > 0);
}
