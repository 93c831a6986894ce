// Private to the kernel: the spatial hash behind the drape's overlap test, and the hash
// mixer the node index shares.
#pragma once

#include <plyfit/kernel/types.hpp>

#include <cmath>
#include <cstdint>
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
// `radius` (3D)?": cells of edge 2 radius, so that the test's ball meets at most 2 x 2 x 2
// cells; open addressing on the cell (collisions of the 64-bit cell hash only merge cells,
// which adds candidates), the nodes of a cell chained in one vector (no allocation per node
// beyond the vectors' growth).
class OverlapGrid {
 public:
  void init(double radius, std::size_t expected) {
    inv_cell_ = 1.0 / (2.0 * radius);
    entries_.reserve(expected);
    std::size_t n = 16;
    while (n < 2 * expected) n *= 2;
    slots_.assign(n, Slot{0, kNone});
  }
  // Calls f(node) for every recorded node in the cells the ball of the test about p meets,
  // until f returns true; true if it did.
  template <class F>
  bool any_near(const Vec3& p, F&& f) const {
    std::int64_t c[3][2];
    for (int a = 0; a < 3; ++a) {
      const double x = p[a] * inv_cell_, fl = std::floor(x);
      c[a][0] = static_cast<std::int64_t>(fl);
      c[a][1] = c[a][0] + (x - fl < 0.5 ? -1 : 1);
    }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
          for (std::uint32_t e = head(key(c[0][i], c[1][j], c[2][k])); e != kNone;
               e = entries_[e].next)
            if (f(entries_[e].node)) return true;
    return false;
  }
  void insert(const Vec3& p, std::uint32_t node) {
    const std::uint64_t k = key(static_cast<std::int64_t>(std::floor(p.x() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.y() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.z() * inv_cell_)));
    if (2 * (count_ + 1) > slots_.size()) grow();
    Slot& s = find(k);
    if (s.head == kNone) {
      s.key = k;
      ++count_;
    }
    entries_.push_back({node, s.head});
    s.head = static_cast<std::uint32_t>(entries_.size() - 1);
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Slot {
    std::uint64_t key;
    std::uint32_t head;  // first entry of the cell, kNone for an empty slot
  };
  struct Entry {
    std::uint32_t node, next;
  };
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return mix(static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
               static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
               static_cast<std::uint64_t>(z));
  }
  Slot& find(std::uint64_t k) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = mix(k) & mask;; h = (h + 1) & mask)
      if (slots_[h].head == kNone || slots_[h].key == k) return slots_[h];
  }
  std::uint32_t head(std::uint64_t k) const {
    if (slots_.empty()) return kNone;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = mix(k) & mask;; h = (h + 1) & mask) {
      if (slots_[h].head == kNone) return kNone;
      if (slots_[h].key == k) return slots_[h].head;
    }
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<std::size_t>(16, 2 * old.size()), Slot{0, kNone});
    for (const Slot& o : old)
      if (o.head != kNone) find(o.key) = o;
  }
  double inv_cell_ = 1.0;
  std::vector<Slot> slots_;
  std::size_t count_ = 0;
  std::vector<Entry> entries_;
};

}  // namespace plyfit::detail
