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

bool NodeIndex::erase(const NodeId& id) {
  if (id.is_path_only()) {
    if (!remove(path_, path_count_, id.key())) return false;
    --size_;
    return true;
  }
  const std::int64_t b = probe(blocks_, block_key(id.i, id.j, kBlockBits));
  if (b < 0) return false;
  std::int32_t& v =
      cells_[static_cast<std::size_t>(b) * kBlock * kBlock + block_offset(id.i, id.j, kBlockBits)];
  if (v < 0) return false;
  v = -1;
  --size_;
  return true;
}

void NodeIndex::truncate(const Mark& m) {
  if (block_count_ > m.blocks) {
    std::vector<std::uint64_t> drop;
    for (const Slot& s : blocks_)
      if (s.key != kEmpty && s.value >= m.blocks) drop.push_back(s.key);
    for (const std::uint64_t k : drop) remove(blocks_, block_count_, k);  // block_count_ falls
    cells_.resize(m.blocks * kBlock * kBlock);
  }
  if (blocks_.size() > m.block_slots) {  // the table doubled since: back to its size then
    std::vector<Slot> old = std::move(blocks_);
    blocks_.assign(m.block_slots, Slot{kEmpty, 0});
    std::size_t count = 0;
    for (const Slot& s : old)
      if (s.key != kEmpty) put(blocks_, count, s.key, s.value);
  }
  if (cells_.capacity() > m.cells_capacity) {
    std::vector<std::int32_t> cells;
    cells.reserve(m.cells_capacity);
    cells.assign(cells_.begin(), cells_.end());
    cells_.swap(cells);
  }
  last_key_ = kEmpty;  // the cached block may be gone
  last_block_ = -1;
}

std::size_t NodeIndex::memory_bytes() const {
  return blocks_.capacity() * sizeof(Slot) + cells_.capacity() * sizeof(std::int32_t) +
         path_.capacity() * sizeof(Slot);
}

// Removes key: the slots after it in its run move back where their probe starts at or
// before the hole (linear probing without tombstones).
bool NodeIndex::remove(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key) {
  if (slots.empty()) return false;
  const std::size_t mask = slots.size() - 1;
  std::size_t h = mix(key) & mask;
  for (; slots[h].key != key; h = (h + 1) & mask)
    if (slots[h].key == kEmpty) return false;
  slots[h].key = kEmpty;
  --count;
  for (std::size_t j = (h + 1) & mask; slots[j].key != kEmpty; j = (j + 1) & mask) {
    const std::size_t home = mix(slots[j].key) & mask;
    if (((j - home) & mask) >= ((j - h) & mask)) {  // the hole lies on j's probe path
      slots[h] = slots[j];
      slots[j].key = kEmpty;
      h = j;
    }
  }
  return true;
}

}  // namespace plyfit
