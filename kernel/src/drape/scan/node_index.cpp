// NodeIndex: regular nodes in a sparse grid of dense blocks, path-only nodes in a small
// linear-probing hash.
#include "drape/scan/node_index.hpp"

#include "drape/scan/overlap_grid.hpp"

namespace plyfit {

using detail::mix;

std::int64_t NodeIndex::probe(const std::vector<Slot>& slots, std::uint64_t key) {
  if (slots.empty()) return -1;
  const std::size_t mask = slots.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots[h].key == key) return slots[h].value;
    if (slots[h].key == kEmpty) return -1;
  }
}

void NodeIndex::put(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key,
                    std::uint32_t value) {
  if ((count + 1) * 2 > slots.size()) {
    std::vector<Slot> old = std::move(slots);
    slots.assign(old.empty() ? 16 : old.size() * 2, Slot{kEmpty, 0});
    count = 0;
    for (const Slot& s : old)
      if (s.key != kEmpty) put(slots, count, s.key, s.value);
  }
  const std::size_t mask = slots.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots[h].key == kEmpty) {
      slots[h] = {key, value};
      ++count;
      return;
    }
  }
}

namespace {
inline std::uint64_t block_key(std::int32_t i, std::int32_t j, int bits) {
  return NodeId::regular(i >> bits, j >> bits).key();  // arithmetic shift: floor division
}
inline std::size_t block_offset(std::int32_t i, std::int32_t j, int bits) {
  const std::int32_t m = (1 << bits) - 1;
  return static_cast<std::size_t>(i & m) << bits | static_cast<std::size_t>(j & m);
}
}  // namespace

std::int64_t NodeIndex::find(const NodeId& id) const {
  if (id.is_path_only()) return probe(path_, id.key());
  const std::uint64_t bk = block_key(id.i, id.j, kBlockBits);
  if (bk != last_key_) {
    last_key_ = bk;
    last_block_ = probe(blocks_, bk);
  }
  if (last_block_ < 0) return -1;
  const std::int32_t v = cells_[static_cast<std::size_t>(last_block_) * kBlock * kBlock +
                                block_offset(id.i, id.j, kBlockBits)];
  return v;
}

void NodeIndex::insert(const NodeId& id, std::uint32_t index) {
  ++size_;
  if (id.is_path_only()) {
    put(path_, path_count_, id.key(), index);
    return;
  }
  const std::uint64_t bk = block_key(id.i, id.j, kBlockBits);
  std::int64_t b = probe(blocks_, bk);
  if (b < 0) {
    b = static_cast<std::int64_t>(block_count_);
    put(blocks_, block_count_, bk, static_cast<std::uint32_t>(b));
    cells_.resize(cells_.size() + kBlock * kBlock, -1);
  }
  last_key_ = bk;
  last_block_ = b;
  cells_[static_cast<std::size_t>(b) * kBlock * kBlock + block_offset(id.i, id.j, kBlockBits)] =
      static_cast<std::int32_t>(index);
}

std::size_t NodeIndex::memory_bytes() const {
  return blocks_.capacity() * sizeof(Slot) + cells_.capacity() * sizeof(std::int32_t) +
         path_.capacity() * sizeof(Slot);
}

}  // namespace plyfit
