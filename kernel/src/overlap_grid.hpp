// Private to the kernel: the spatial hash behind the drape's overlap test, and the hash
// mixer the node index shares.
#pragma once

#include <plyfit/kernel/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <vector>

namespace plyfit::detail {

inline std::uint64_t mix(std::uint64_t k) {  // splitmix64 finaliser
  k ^= k >> 30;
  k *= 0xbf58476d1ce4e5b9ULL;
  k ^= k >> 27;
  k *= 0x94d049bb133111ebULL;
  return k ^ (k >> 31);
}

// Spatial hash of mapped nodes for the overlap test "is there a recorded node within
// `radius` (3D) of p that the caller's exact test accepts? If not, record p". The test runs
// on every mapped node, so what it costs per node is what matters (issue 13: at most 10 % of
// the drape): a few hundred instructions, few unpredictable branches, little memory.
// - Cells of edge kCellRadii * radius: the test's ball meets one cell per axis or two (2^3
//   at most, about 2.4 on average); only those are visited, found from p's own cell and
//   where p lies in it. Open addressing on the cell's packed coordinates (cells 2^21 apart
//   share a key: that only adds candidates), multiplicative hashing.
// - A cell's nodes lie in chunks of kLanes: each node's point as floats relative to the
//   cell's corner (structure of arrays, unused lanes far away) and its index. A chunk is
//   filtered whole with vector arithmetic (GCC/Clang vector extensions: no branch per node)
//   by a float distance a little wider than the ball (kFloatSlack); only a chunk with a node
//   within it, rare unless the cloth comes back, goes to the caller's exact test on the
//   node's own doubles. The answer is the same as an all-double test's.
class OverlapGrid {
 public:
  // Cell edge over the test radius (>= 2: the ball meets at most two cells per axis). Larger
  // cells mean fewer cells visited, more nodes per cell; per node tested, 6 against 4 (3.4
  // cells visited) takes 3 % fewer instructions and a third fewer mispredicted branches
  // (callgrind), and 3 against 4 14 % more instructions.
  static constexpr double kCellRadii = 6.0;
  // The float filter passes every node within radius * (1 + kFloatSlack) of p. A float
  // coordinate relative to its cell's corner (at most (kCellRadii + 1) * radius) is within
  // 2^-24 of that of the double; the filter's float distance is therefore within about
  // 1e-6 * radius of the true one, far inside this slack.
  static constexpr double kFloatSlack = 1e-4;
  // Expected mapped nodes per occupied cell: sizes the slot table for `expected` nodes (it
  // doubles when more cells are met). The surface crosses a cell of edge kCellRadii *
  // kOverlapRel * d = 3 d at about 6 to 16 nodes.
  static constexpr std::size_t kNodesPerCell = 6;

  void init(double radius, std::size_t expected) {
    radius_ = radius;
    edge_ = kCellRadii * radius;
    inv_cell_ = 1.0 / edge_;
    reach_ = (1 + kFloatSlack) / kCellRadii;  // the ball's radius in cell edges, and a hair
    std::size_t n = 16;
    bits_ = 4;
    while (n < 2 * (expected / kNodesPerCell)) {
      n *= 2;
      ++bits_;
    }
    slots_.assign(n, Slot{0, kNone});
  }
  // True if `exact(node)` holds for some recorded node within `radius` of p (3D); exact
  // receives the index given to a previous call and does the full test in doubles (it must
  // reject nodes farther than `radius`: the filter passes a little more). If it holds for
  // none, records `node` at p.
  template <class Exact>
  bool test_insert(const Vec3& p, std::uint32_t node, Exact&& exact) {
    std::int64_t c[3], lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double t = p[a] * inv_cell_;
      c[a] = floor_int(t);
      const double f = t - static_cast<double>(c[a]);  // in [0, 1)
      lo[a] = c[a] - (f < reach_ ? 1 : 0);
      hi[a] = c[a] + (f + reach_ >= 1.0 ? 1 : 0);
    }
    const float r2 = static_cast<float>(radius_ * radius_ * (1 + kFloatSlack));
    std::size_t own = 0;  // the slot of p's cell (among those visited)
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const std::size_t slot = find(key(i, j, k));
          own = i == c[0] && j == c[1] && k == c[2] ? slot : own;
          std::uint32_t h = slots_[slot].head;
          if (h == kNone) continue;
          const V4 x = splat(static_cast<float>(p.x() - static_cast<double>(i) * edge_));
          const V4 y = splat(static_cast<float>(p.y() - static_cast<double>(j) * edge_));
          const V4 z = splat(static_cast<float>(p.z() - static_cast<double>(k) * edge_));
          const V4 rr = splat(r2);
          for (; h != kNone; h = chunk(h).next) {
            const Chunk& ch = chunk(h);
            const V4 dx = ch.x - x, dy = ch.y - y, dz = ch.z - z;
            const M4 near = dx * dx + dy * dy + dz * dz < rr;
            if ((near[0] | near[1] | near[2] | near[3]) == 0) continue;
            for (int t = 0; t < ch.count; ++t)
              if (near[t] && exact(ch.node[t])) return true;
          }
        }
    insert(c, own, p, node);
    return false;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  static constexpr int kLanes = 4;
  typedef float V4 __attribute__((vector_size(16)));
  typedef std::int32_t M4 __attribute__((vector_size(16)));
  // Coordinate of an unused lane: its squared distance stays finite and fails the filter.
  static constexpr float kFar = 1e15f;
  // Chunks are allocated in pages of kPage, never moved (no copy, no reserve beyond need).
  static constexpr std::uint32_t kPageBits = 12, kPage = 1u << kPageBits;
  static constexpr int kKeyBits = 21;
  struct Slot {
    std::uint64_t key;   // the cell's packed coordinates
    std::uint32_t head;  // the cell's newest chunk, kNone for an empty slot
  };
  struct Chunk {
    V4 x, y, z;  // points relative to the cell's corner
    std::uint32_t node[kLanes];
    std::uint32_t next;  // the cell's previous (full) chunk
    int count;
  };
  static V4 splat(float v) { return V4{v, v, v, v}; }
  static std::int64_t floor_int(double t) {
    const auto i = static_cast<std::int64_t>(t);
    return i - (t < static_cast<double>(i) ? 1 : 0);
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::uint64_t m = (std::uint64_t{1} << kKeyBits) - 1;
    return (static_cast<std::uint64_t>(x) & m) << (2 * kKeyBits) |
           (static_cast<std::uint64_t>(y) & m) << kKeyBits | (static_cast<std::uint64_t>(z) & m);
  }
  const Chunk& chunk(std::uint32_t c) const { return pages_[c >> kPageBits][c & (kPage - 1)]; }
  Chunk& chunk(std::uint32_t c) { return pages_[c >> kPageBits][c & (kPage - 1)]; }
  // The slot of cell key k, or the empty slot where it would go.
  std::size_t find(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = (k * 0x9E3779B97F4A7C15ULL) >> (64 - bits_);; h = (h + 1) & mask)
      if (slots_[h].head == kNone || slots_[h].key == k) return h;
  }
  // Records node at p in cell c, whose slot (found by the test) is `slot`.
  void insert(const std::int64_t c[3], std::size_t slot, const Vec3& p, std::uint32_t node) {
    const std::uint64_t k = key(c[0], c[1], c[2]);
    if (slots_[slot].head == kNone && 2 * (count_ + 1) > slots_.size()) {
      grow();
      slot = find(k);
    }
    Slot& s = slots_[slot];
    if (s.head == kNone) {
      s.key = k;
      ++count_;
    }
    if (s.head == kNone || chunk(s.head).count == kLanes) s.head = new_chunk(s.head);
    Chunk& ch = chunk(s.head);
    const int t = ch.count++;
    ch.x[t] = static_cast<float>(p.x() - static_cast<double>(c[0]) * edge_);
    ch.y[t] = static_cast<float>(p.y() - static_cast<double>(c[1]) * edge_);
    ch.z[t] = static_cast<float>(p.z() - static_cast<double>(c[2]) * edge_);
    ch.node[t] = node;
  }
  std::uint32_t new_chunk(std::uint32_t next) {
    if (chunks_ == pages_.size() * kPage) pages_.push_back(std::make_unique<Chunk[]>(kPage));
    Chunk& ch = chunk(chunks_);
    ch.x = ch.y = ch.z = splat(kFar);
    ch.next = next;
    ch.count = 0;
    return chunks_++;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(2 * old.size(), Slot{0, kNone});
    ++bits_;
    for (const Slot& o : old)
      if (o.head != kNone) slots_[find(o.key)] = o;
  }
  double radius_ = 1.0, edge_ = 1.0, inv_cell_ = 1.0, reach_ = 0.25;
  std::vector<Slot> slots_;
  int bits_ = 4;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Chunk[]>> pages_;
  std::uint32_t chunks_ = 0;
};

}  // namespace plyfit::detail
