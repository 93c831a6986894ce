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
// `radius` (3D) of p but at least `sep` from it on the ply?": cells of edge kCellRadii *
// radius, so that the test's ball meets one cell per axis or two (2^3 at most, about 3.4 on
// average: only the cells the ball's box meets are visited); open addressing on the cell
// (collisions of the 64-bit cell hash only merge cells, which adds candidates), the entries
// of a cell chained in one vector that holds each node's point and ply position, so that the
// test reads no node and its recent entries lie together in memory (the test runs on every
// mapped node: scattered reads are what it costs).
class OverlapGrid {
 public:
  // Cell edge over the test radius (>= 2: the ball meets at most two cells per axis). Larger
  // cells mean fewer cells visited, more entries per cell.
  static constexpr double kCellRadii = 4.0;
  void init(double radius, std::size_t expected) {
    radius_ = radius;
    inv_cell_ = 1.0 / (kCellRadii * radius);
    entries_.reserve(expected);
    std::size_t n = 16;
    while (n < expected) n *= 2;
    slots_.assign(n, Slot{0, kNone});
  }
  // True if a recorded node lies within `radius` of p (3D) and at least `sep` from ply point
  // `ply` (2D).
  bool any_far_near(const Vec3& p, const Vec2& ply, double sep) const {
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<std::int64_t>(std::floor((p[a] - radius_) * inv_cell_));
      hi[a] = static_cast<std::int64_t>(std::floor((p[a] + radius_) * inv_cell_));
    }
    const double r2 = radius_ * radius_, s2 = sep * sep;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
          for (std::uint32_t e = head(key(i, j, k)); e != kNone; e = entries_[e].next) {
            const Entry& m = entries_[e];
            if ((m.p - p).squaredNorm() < r2 && (m.ply - ply).squaredNorm() >= s2) return true;
          }
    return false;
  }
  void insert(const Vec3& p, const Vec2& ply) {
    const std::uint64_t k = key(static_cast<std::int64_t>(std::floor(p.x() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.y() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.z() * inv_cell_)));
    if (2 * (count_ + 1) > slots_.size()) grow();
    Slot& s = find(k);
    if (s.head == kNone) {
      s.key = k;
      ++count_;
    }
    entries_.push_back({p, ply, s.head});
    s.head = static_cast<std::uint32_t>(entries_.size() - 1);
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Slot {
    std::uint64_t key;
    std::uint32_t head;  // first entry of the cell, kNone for an empty slot
  };
  struct Entry {
    Vec3 p;
    Vec2 ply;
    std::uint32_t next;
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
  double radius_ = 1.0, inv_cell_ = 1.0;
  std::vector<Slot> slots_;
  std::size_t count_ = 0;
  std::vector<Entry> entries_;
};

}  // namespace plyfit::detail
