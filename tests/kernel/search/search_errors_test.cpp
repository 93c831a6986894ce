// The search of initial conditions (kernel/src/search): what it refuses, by code.
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/optimize.hpp>

#include "test_util.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plyfit;

namespace {

constexpr double kR = 20.0;  // the sphere octant's radius

// The surface made of a built-in mold's data.
template <class Data, class Make>
MoldSurface made(Result<Data> data, Make make) {
  REQUIRE(data.ok());
  auto s = make(std::move(data).value());
  REQUIRE(s.ok());
  return std::move(s).value();
}

MoldSurface octant() {
  return made(builtin_mold("sphere-octant", {{"R", kR}}),
              [](FaceData d) { return MoldSurface::from_face(std::move(d)); });
}

MoldSurface sphere8() {
  return made(builtin_shell("sphere-8", {{"R", kR}}),
              [](ShellData d) { return MoldSurface::from_shell(std::move(d)); });
}

SearchScene scene(const FaceStart& fs) {
  SearchScene sc;
  sc.problem.ply.d_weft = sc.problem.ply.d_warp = kR / 10;
  sc.problem.ply.base_dir = Vec2(1, 0);
  sc.problem.ply.sweeps = {Vec2(0, 1)};
  sc.problem.start = fs.point;
  sc.problem.base_normal = fs.base_normal;
  sc.problem.sweeps = {fs.base_normal};
  return sc;
}

}  // namespace

TEST_CASE("search: the start of a face lies on it, with its normal and a tangent base path") {
  const MoldSurface face = octant();
  const auto fs = face_start(face);
  REQUIRE(fs.ok());
  // On the sphere |p| = R, the normal along p (the face's orientation tells which way), the
  // tangent square to it.
  CHECK(std::abs(fs->point.norm() - kR) <= test::kRoundoffRel * kR);
  CHECK(std::abs(std::abs(fs->normal.dot(fs->point / kR)) - 1.0) <= test::kRoundoffRel);
  CHECK(std::abs(fs->tangent.dot(fs->normal)) <= test::kRoundoffRel);
  CHECK(std::abs(fs->base_normal.dot(fs->tangent)) <= test::kRoundoffRel);
}

TEST_CASE("search: a start, the search and its candidates take one face, not a shell") {
  const MoldSurface shell = sphere8();
  const auto fs = face_start(shell);
  REQUIRE_FALSE(fs.ok());
  CHECK(fs.error().code == ErrorCode::kStartNeedsOneFace);

  const auto one = face_start(octant());
  REQUIRE(one.ok());
  OptimizeOptions o;
  o.evaluations = 1;
  const auto r = optimize(scene(*one), shell, o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kSearchNeedsOneFace);

  const auto pb = candidate_problem(scene(*one), shell, OptimizeResult{}, Candidate{});
  REQUIRE_FALSE(pb.ok());
  CHECK(pb.error().code == ErrorCode::kSearchNeedsOneFace);
}

TEST_CASE("search: a candidate whose base-path reference is normal to the face at its seed") {
  const MoldSurface face = octant();
  const auto fs = face_start(face);
  REQUIRE(fs.ok());
  Candidate c;
  c.uv = fs->uv;
  OptimizeResult r;
  r.reference = fs->normal;  // no direction along the face is left of it
  const auto bad = candidate_problem(scene(*fs), face, r, c);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::kSearchPathNormalAtSeed);
  CHECK(bad.error().input.empty());
  // Along the face it is a problem that starts at the seed.
  r.reference = fs->tangent;
  const auto good = candidate_problem(scene(*fs), face, r, c);
  REQUIRE(good.ok());
  CHECK((good->start - fs->point).norm() <= test::kRoundoffRel * kR);
}
