// NodeIndex (kernel/src/drape_result.cpp): the map from node ids to node indices, against a
// std::map kept beside it.
#include "drape/drape.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <map>
#include <utility>

using namespace plyfit;

TEST_CASE("node index: finds every id inserted and no other") {
  // Regular ids over several 32 x 32 blocks (negative coordinates too) and path-only ids,
  // many enough that the path ids' open-addressing table grows and its probe runs collide.
  NodeIndex index;
  std::map<std::pair<std::int32_t, std::int32_t>, std::uint32_t> ref;
  std::uint32_t next = 0;
  auto add = [&](NodeId id) {
    index.insert(id, next);
    ref[{id.i, id.j}] = next++;
  };
  for (std::int32_t i = -40; i < 40; i += 3)
    for (std::int32_t j = -70; j < 20; j += 7) add(NodeId::regular(i, j));
  for (std::int32_t k = -300; k < 300; ++k) add(NodeId::path(k));
  REQUIRE(index.size() == ref.size());
  for (const auto& [ij, k] : ref) {
    const NodeId id{ij.first, ij.second};
    INFO("id (" << id.i << ", " << id.j << ")");
    CHECK(index.find(id) == static_cast<std::int64_t>(k));
  }
  // Never inserted: a regular id in no block, one in a block, a path id.
  CHECK(index.find(NodeId::regular(1000, 1000)) == -1);
  CHECK(index.find(NodeId::regular(-39, -70)) == -1);
  CHECK(index.find(NodeId::path(5000)) == -1);
}
