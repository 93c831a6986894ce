// NodeIndex (kernel/src/drape_result.cpp): the map from node ids to node indices, against a
// std::map kept beside it.
#include "drape/drape.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace plyfit;

TEST_CASE("node index: erase removes an id and leaves every other one found") {
  // Regular ids over several 32 x 32 blocks (negative coordinates too) and path-only ids,
  // many enough that the path ids' open-addressing table grows and its probe runs collide:
  // erasing from a run must leave the ids after it found (backward shift, no tombstones).
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

  std::mt19937 rng(7);
  std::vector<std::pair<std::int32_t, std::int32_t>> ids;
  for (const auto& e : ref) ids.push_back(e.first);
  std::shuffle(ids.begin(), ids.end(), rng);
  const std::size_t half = ids.size() / 2;
  for (std::size_t n = 0; n < half; ++n) {
    const NodeId id{ids[n].first, ids[n].second};
    CHECK(index.erase(id));
    CHECK_FALSE(index.erase(id));  // gone
    ref.erase(ids[n]);
  }
  CHECK(index.size() == ref.size());
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const NodeId id{ids[n].first, ids[n].second};
    const auto it = ref.find(ids[n]);
    INFO("id (" << id.i << ", " << id.j << ")");
    CHECK(index.find(id) == (it == ref.end() ? -1 : static_cast<std::int64_t>(it->second)));
  }
  // Never inserted: a regular id in no block, one in a block, a path id.
  CHECK_FALSE(index.erase(NodeId::regular(1000, 1000)));
  CHECK_FALSE(index.erase(NodeId::regular(-39, -70)));
  CHECK_FALSE(index.erase(NodeId::path(5000)));
  // Erased ids can come back.
  index.insert(NodeId{ids[0].first, ids[0].second}, 12345);
  CHECK(index.find(NodeId{ids[0].first, ids[0].second}) == 12345);
}

TEST_CASE("node index: truncate drops the blocks added since a mark and their memory") {
  NodeIndex index;
  std::uint32_t next = 0;
  for (std::int32_t i = 0; i < 40; ++i)
    for (std::int32_t j = 0; j < 40; ++j) index.insert(NodeId::regular(i, j), next++);
  const std::size_t before = index.memory_bytes(), size = index.size();
  const NodeIndex::Mark m = index.mark();
  // Nodes in the marked blocks and in many new ones (the block table and the cells grow).
  std::vector<NodeId> added;
  for (std::int32_t i = 30; i < 600; i += 5)
    for (std::int32_t j = 30; j < 300; j += 9)
      if (index.find(NodeId::regular(i, j)) < 0) {
        added.push_back(NodeId::regular(i, j));
        index.insert(added.back(), next++);
      }
  REQUIRE(index.memory_bytes() > before);
  for (const NodeId& id : added) CHECK(index.erase(id));
  index.truncate(m);
  CHECK(index.memory_bytes() == before);
  CHECK(index.size() == size);
  std::uint32_t k = 0;
  for (std::int32_t i = 0; i < 40; ++i)
    for (std::int32_t j = 0; j < 40; ++j) CHECK(index.find(NodeId::regular(i, j)) == k++);
  for (const NodeId& id : added) CHECK(index.find(id) == -1);
  // The dropped blocks can be added again.
  index.insert(NodeId::regular(500, 250), 7);
  CHECK(index.find(NodeId::regular(500, 250)) == 7);
  CHECK(index.find(NodeId::regular(39, 39)) == 40 * 40 - 1);
}
