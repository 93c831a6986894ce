#include <plyfit/kernel/ply.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plyfit;

namespace {
Ply make(PlySpec s) {
  auto p = Ply::create(std::move(s));
  REQUIRE(p.ok());
  return std::move(p).value();
}
// Path node k: at `pos`, on the link from `from` along `dir` that it splits. Returns it.
const PathNode* check_split(Ply& p, int k, Vec2 pos, NodeId from, ThreadDir dir) {
  INFO("path node " << k);
  const PathNode* n = p.path_node(k);
  REQUIRE(n);
  CHECK(n->pos.x() == Approx(pos.x()));
  CHECK(n->pos.y() == Approx(pos.y()));
  REQUIRE(n->link_from);
  CHECK(*n->link_from == from);
  CHECK(n->link_dir == dir);
  return n;
}
}  // namespace

TEST_CASE("ply: auxiliary points where the path crosses threads, with split links (Fig. 7)") {
  PlySpec s;
  s.d_weft = 1.0;
  s.d_warp = 2.0;
  s.start = Vec2(0.25, 0.5);  // inside a cell: a free path point
  s.base_dir = Vec2(1.0, 0.5);
  s.sweeps = {Vec2(0, 1)};
  Ply p = make(s);
  const PathNode* n0 = p.path_node(0);
  REQUIRE(n0);
  CHECK(n0->id.is_path_only());
  CHECK_FALSE(n0->link_from);
  // Ahead: the path y = 0.5 + (x - 0.25) / 2 crosses x = 1 at y = 0.875 (a warp link split),
  // x = 2 at y = 1.375, y = 2 at x = 3.25 (a weft link split), x = 3, ...
  const PathNode* n1 =
      check_split(p, 1, Vec2(1.0, 0.875), NodeId::regular(1, 0), ThreadDir::kPlusY);
  check_split(p, 4, Vec2(3.25, 2.0), NodeId::regular(3, 1), ThreadDir::kPlusX);
  // The warp link (1,0)-(1,1) is split: from (1,0) the neighbour is path node 1 at 0.875.
  auto up = p.neighbour(1, 0, ThreadDir::kPlusY);
  REQUIRE(up);
  CHECK(up->id == n1->id);
  CHECK(up->rest == Approx(0.875));
  auto down = p.neighbour(1, 1, ThreadDir::kMinusY);
  REQUIRE(down);
  CHECK(down->id == n1->id);
  CHECK(down->rest == Approx(2.0 - 0.875));
  // A link the path does not cross keeps its rest length.
  auto right = p.neighbour(1, 0, ThreadDir::kPlusX);
  REQUIRE(right);
  CHECK(right->id == NodeId::regular(2, 0));
  CHECK(right->rest == Approx(1.0));
  // The path node's thread neighbours are the two ends of the link it splits.
  const auto tn = p.thread_neighbours(n1->id);
  REQUIRE(tn.size() == 2);
  CHECK(tn[0].n.id == NodeId::regular(1, 0));
  CHECK(tn[1].n.id == NodeId::regular(1, 1));
  CHECK(tn[0].n.rest + tn[1].n.rest == Approx(2.0));
  // Half-planes and the sweep distance along (0, 1).
  CHECK(p.side(Vec2(0, 5)) == 1);
  CHECK(p.side(Vec2(5, 0)) == -1);
  CHECK(p.sweep_for_side(1) == 0);
  CHECK(p.sweep_for_side(-1) == -1);
  CHECK(p.sweep_distance(Vec2(2.25, 3.5)) == Approx(2.0));
}

TEST_CASE("ply: a path through crossings or along a thread uses the regular nodes") {
  PlySpec s;
  s.start = Vec2(15, 0);
  s.base_dir = Vec2(1, 1);  // the paper's case (c): Y = X - 15
  s.sweeps = {Vec2(-1, 1)};
  Ply p = make(s);
  CHECK(p.path_node(0)->id == NodeId::regular(15, 0));
  for (int k = 1; k <= 5; ++k) CHECK(p.path_node(k)->id == NodeId::regular(15 + k, k));
  CHECK(p.path_node(-3)->id == NodeId::regular(12, -3));
  CHECK(p.path_index_of(18, 3) == std::optional<std::int32_t>(3));
  CHECK_FALSE(p.path_index_of(18, 4));
  PlySpec t;
  t.start = Vec2(0, 0);
  t.base_dir = Vec2(1, 0);  // along weft thread 0 (the paper's case (a))
  t.sweeps = {Vec2(0, 1)};
  Ply q = make(t);
  for (int k = -3; k <= 3; ++k) CHECK(q.path_node(k)->id == NodeId::regular(k, 0));
}

TEST_CASE("ply: the rectangle bounds the path and the cloth") {
  PlySpec s;
  s.rect = Vec2(70, 70);
  s.start = Vec2(0, 0);
  s.base_dir = Vec2(0, 1);
  s.sweeps = {Vec2(1, 0)};
  Ply p = make(s);
  CHECK(p.path_node(70));
  CHECK_FALSE(p.path_node(71));
  CHECK_FALSE(p.path_node(-1));
  CHECK(p.on_ply(Vec2(70, 70)));
  CHECK_FALSE(p.on_ply(Vec2(70.5, 3)));
}

TEST_CASE("ply: invalid specifications are errors that say why") {
  PlySpec s;
  s.sweeps = {Vec2(0, 1)};
  auto bad = s;
  bad.d_weft = 0.0;
  CHECK(Ply::create(bad).error().code == ErrorCode::kSpacingNotPositive);
  bad = s;
  bad.sweeps = {Vec2(2, 0)};
  CHECK(Ply::create(bad).error().code == ErrorCode::kSweepAlongPath);
  bad = s;
  bad.sweeps = {Vec2(0, 1), Vec2(1, 1)};
  CHECK(Ply::create(bad).error().code == ErrorCode::kSweepsSameSide);
  bad = s;
  bad.rect = Vec2(10, 10);
  bad.start = Vec2(11, 2);
  CHECK(Ply::create(bad).error().code == ErrorCode::kStart2dOffPly);
  bad = s;
  bad.base_dir = Vec2(0, 0);
  CHECK(Ply::create(bad).error().code == ErrorCode::kBaseDirZero);
  bad = s;
  bad.sweeps.clear();
  CHECK(Ply::create(bad).error().code == ErrorCode::kNoSweep);
}
