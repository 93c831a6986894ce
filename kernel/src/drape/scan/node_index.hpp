#pragma once
/// \file NodeIndex: the map from a node's id to its position in DrapeResult::nodes.

#include <plyfit/kernel/ply.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace plyfit {

/// Map from NodeId to node index. Regular nodes live in a sparse grid of dense 32 x 32
/// blocks (neighbours share a block; a few bytes per node), path-only nodes in a small hash;
/// memory grows with the nodes reached, never with the size of the ply.
class NodeIndex {
 public:
  /// Index of `id`, or -1.
  std::int64_t find(const NodeId& id) const;
  /// Inserts id -> index (id must be absent).
  void insert(const NodeId& id, std::uint32_t index);
  std::size_t size() const { return size_; }
  std::size_t memory_bytes() const;

 private:
  static constexpr int kBlockBits = 5;
  static constexpr int kBlock = 1 << kBlockBits;  // 32 x 32 nodes per block
  struct Slot {
    std::uint64_t key;
    std::uint32_t value;
  };
  // The key of NodeId::path(INT32_MIN): no node has it (path indices stay within
  // +-Ply::kMaxPathNodes). (All ones would be the key of regular node (-1, -1).)
  static constexpr std::uint64_t kEmpty = (std::uint64_t{0x7fffffff} << 32) | 0x80000000u;
  static std::int64_t probe(const std::vector<Slot>& slots, std::uint64_t key);
  static void put(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key,
                  std::uint32_t value);
  std::vector<Slot> blocks_;  // block key -> block number
  std::size_t block_count_ = 0;
  std::vector<std::int32_t> cells_;  // kBlock^2 entries per block, -1 = absent
  std::vector<Slot> path_;           // path-only node key -> index
  std::size_t path_count_ = 0;
  std::size_t size_ = 0;
  mutable std::uint64_t last_key_ = kEmpty;  // one-entry cache of the last block looked up
  mutable std::int64_t last_block_ = -1;
};

}  // namespace plyfit
