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

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
// - Points are rounded to integer units, kCellUnits (a power of two) to a cell's edge of
//   kCellRadii * radius: a point's cell and its place in it are a shift and a mask.
// - A node is recorded in its own cell. A test reads the cells p's ball (radius and two
//   units) meets: its own and, per axis, the neighbour it lies within that of (one axis in
//   four on average), found from p's integer coordinates without a floor() or a
//   data-dependent loop per axis.
// - Open addressing on the cell's packed coordinates (cells 2^21 apart share a key: that
//   only adds candidates), multiplicative hashing.
// - A cell's nodes lie in chunks of kLanes: each node's point as 16-bit integers relative to
//   the cell's centre (structure of arrays, unused lanes far away) and its index. A chunk is
//   filtered whole with SSE2 integer arithmetic (no branch per node) by a distance two units
//   wider than the ball (each integer is within half a unit of its point's exact scaled
//   coordinate, so a difference of two within one, a distance within sqrt(3)); only a
//   chunk with a node within it, rare unless the cloth comes back, goes to the caller's
//   exact test on the node's own doubles. The answer is the same as an all-double test's.
class OverlapGrid {
 public:
  // Cell edge over the test radius (>= 2: the ball meets at most two cells per axis). Larger
  // cells mean fewer cells visited, more nodes per cell: 8 against 6 takes 3 % fewer
  // instructions per test, fewer cache misses and 3 % less peak heap (callgrind, wave and
  // octant at 300^2).
  static constexpr int kCellRadii = 8;
  // A cell's edge in integer units: the radius is kCellUnits / kCellRadii = 2048 units. A
  // coordinate relative to its cell's centre is at most kCellUnits / 2 + 2051 = 10243
  // units, a difference of two at most 20486 (16 bits), a squared distance 3 * 20486^2 <
  // 2^31 (the sums are 32-bit).
  static constexpr int kCellBits = 14;
  static constexpr std::int64_t kCellUnits = std::int64_t{1} << kCellBits;
  // Units added to the radius in the cell-membership and filter tests (a coordinate's
  // rounding is half a unit: a difference of two within one unit per axis).
  static constexpr int kSlackUnits = 2;
  // Expected mapped nodes per occupied cell: sizes the slot table for `expected` nodes (it
  // doubles when more cells are met). The surface crosses a cell of edge kCellRadii *
  // kOverlapRel * d = 4 d at about 10 to 28 nodes: 6 keeps the table's load low (few
  // probes per look-up).
  static constexpr std::size_t kNodesPerCell = 6;

  void init(double radius, std::size_t expected) {
    const double units = static_cast<double>(kCellUnits) / kCellRadii;  // per radius
    scale_ = units / radius;
    reach_ = static_cast<std::int64_t>(std::ceil(units)) + kSlackUnits;
    thr2_ = static_cast<std::int32_t>(reach_ * reach_);
    std::size_t n = 16;
    bits_ = 4;
    while (n < 2 * (expected / kNodesPerCell)) {
      n *= 2;
      ++bits_;
    }
    slots_.assign(n, Slot{0, kNone});
    count_ = 0;
    pages_.clear();
    chunks_ = 0;
  }
  // True if `exact(node)` holds for some recorded node within `radius` of p (3D); exact
  // receives the index given to a previous call and does the full test in doubles (it must
  // reject nodes farther than `radius`: the filter passes a little more). If it holds for
  // none, records `node` at p.
  template <class Exact>
  bool test_insert(const Vec3& p, std::uint32_t node, Exact&& exact) {
    // Per axis, p's own cell [0] and the neighbour its ball meets [1], if any (bit a of
    // `both`): the packed key part and p in units relative to the cell's centre.
    std::uint64_t kp[3][2];
    std::int32_t q[3][2];
    unsigned both = 0;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t u = round_int(p[a] * scale_);
      const std::int64_t c = u >> kCellBits, at = u & (kCellUnits - 1);  // cell, place in it
      const std::int64_t side = static_cast<std::int64_t>(at >= kCellUnits - reach_) -
                                static_cast<std::int64_t>(at < reach_);
      both |= static_cast<unsigned>(side != 0) << a;
      const int shift = (2 - a) * kKeyBits;
      kp[a][0] = (static_cast<std::uint64_t>(c) & kKeyMask) << shift;
      kp[a][1] = (static_cast<std::uint64_t>(c + side) & kKeyMask) << shift;
      q[a][0] = static_cast<std::int32_t>(at - kCellUnits / 2);
      q[a][1] = static_cast<std::int32_t>(at - kCellUnits / 2 - side * kCellUnits);
    }
    const std::uint64_t own_key = kp[0][0] | kp[1][0] | kp[2][0];
    std::size_t own = find(own_key);
    if (near_in(slots_[own].head, q[0][0], q[1][0], q[2][0], exact)) return true;
    // The other cells the ball meets: every non-empty subset of `both`.
    for (unsigned m = both; m != 0; m = (m - 1) & both) {
      const unsigned i = m & 1, j = (m >> 1) & 1, k = m >> 2;
      const std::uint32_t h = slots_[find(kp[0][i] | kp[1][j] | kp[2][k])].head;
      if (near_in(h, q[0][i], q[1][j], q[2][k], exact)) return true;
    }
    if (slots_[own].head == kNone && 2 * (count_ + 1) > slots_.size()) {
      grow();
      own = find(own_key);
    }
    insert(own, own_key, q[0][0], q[1][0], q[2][0], node);
    return false;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  static constexpr int kLanes = 8;
  // The largest coordinate relative to a cell's centre (see kCellBits).
  static constexpr double kMaxCoord =
      kCellUnits / 2 + static_cast<double>(kCellUnits) / kCellRadii + 1 + kSlackUnits;
  static_assert(2 * kMaxCoord <= 32767 && 3 * (2 * kMaxCoord) * (2 * kMaxCoord) < 2147483647.0,
                "a difference of two coordinates fits 16 bits, a squared distance 31");
  // x of an unused lane (y and z 0): its difference saturates at 16 bits, its squared
  // distance stays within 31 bits and fails the filter.
  static constexpr std::int16_t kFar = 32767;
  // Chunks are allocated in pages of kPage, never moved (no copy, no reserve beyond need).
  static constexpr std::uint32_t kPageBits = 12, kPage = 1u << kPageBits;
  static constexpr int kKeyBits = 21;
  static constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;
  struct Slot {
    std::uint64_t key;   // the cell's packed coordinates
    std::uint32_t head;  // the cell's newest chunk, kNone for an empty slot
  };
  struct Chunk {
    alignas(16) std::int16_t x[kLanes];  // points relative to the cell's centre, in units
    std::int16_t y[kLanes], z[kLanes];
    std::uint32_t node[kLanes];
    std::uint32_t next;  // the cell's previous (full) chunk
    std::int32_t count;
  };
  // True if exact() accepts a node of the chunks from h on within the filter's distance of
  // (x, y, z) (units relative to their cell's centre).
  template <class Exact>
  bool near_in(std::uint32_t h, std::int32_t x, std::int32_t y, std::int32_t z,
               Exact& exact) const {
    for (; h != kNone;) {
      const Chunk& ch = chunk(h);
      for (unsigned near = near_lanes(ch, x, y, z); near != 0; near &= near - 1)
        if (exact(ch.node[__builtin_ctz(near)])) return true;
      h = ch.next;
    }
    return false;
  }
  // Bit t set if lane t of ch lies within the filter's distance of q.
  unsigned near_lanes(const Chunk& ch, std::int32_t qx, std::int32_t qy, std::int32_t qz) const {
#if defined(__SSE2__)
    const __m128i dx = _mm_subs_epi16(_mm_load_si128(reinterpret_cast<const __m128i*>(ch.x)),
                                      _mm_set1_epi16(static_cast<std::int16_t>(qx)));
    const __m128i dy = _mm_sub_epi16(_mm_load_si128(reinterpret_cast<const __m128i*>(ch.y)),
                                     _mm_set1_epi16(static_cast<std::int16_t>(qy)));
    const __m128i dz = _mm_sub_epi16(_mm_load_si128(reinterpret_cast<const __m128i*>(ch.z)),
                                     _mm_set1_epi16(static_cast<std::int16_t>(qz)));
    const __m128i zero = _mm_setzero_si128();
    // (dx, dy) pairs and (dz, 0) pairs: one multiply-add gives dx^2 + dy^2, one dz^2.
    const __m128i lo =
        _mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(dx, dy), _mm_unpacklo_epi16(dx, dy)),
                      _mm_madd_epi16(_mm_unpacklo_epi16(dz, zero), _mm_unpacklo_epi16(dz, zero)));
    const __m128i hi =
        _mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(dx, dy), _mm_unpackhi_epi16(dx, dy)),
                      _mm_madd_epi16(_mm_unpackhi_epi16(dz, zero), _mm_unpackhi_epi16(dz, zero)));
    const __m128i thr = _mm_set1_epi32(thr2_);
    const __m128i m = _mm_packs_epi32(_mm_cmplt_epi32(lo, thr), _mm_cmplt_epi32(hi, thr));
    return static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi16(m, zero)));
#else
    unsigned near = 0;
    for (int t = 0; t < kLanes; ++t) {
      const std::int32_t dx = std::min<std::int32_t>(ch.x[t] - qx, 32767);
      const std::int32_t dy = ch.y[t] - qy, dz = ch.z[t] - qz;
      near |= (dx * dx + dy * dy + dz * dz < thr2_ ? 1u : 0u) << t;
    }
    return near;
#endif
  }
  // v rounded to the nearest integer (the default rounding mode); |v| < 2^62.
  static std::int64_t round_int(double v) {
#if defined(__SSE2__)
    return _mm_cvtsd_si64(_mm_set_sd(v));
#else
    return std::llrint(v);
#endif
  }
  const Chunk& chunk(std::uint32_t c) const {
    return pages_[c >> kPageBits][c & (kPage - 1)];
  }
  Chunk& chunk(std::uint32_t c) {
    return pages_[c >> kPageBits][c & (kPage - 1)];
  }
  // The slot of cell key k, or the empty slot where it would go.
  std::size_t find(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = (k * 0x9E3779B97F4A7C15ULL) >> (64 - bits_);; h = (h + 1) & mask)
      if (slots_[h].head == kNone || slots_[h].key == k) return h;
  }
  // Records node at (x, y, z) (units, relative to the cell's centre) in the cell of key k,
  // whose slot is `slot` (the table has room for it).
  void insert(std::size_t slot, std::uint64_t k, std::int32_t x, std::int32_t y, std::int32_t z,
              std::uint32_t node) {
    Slot& s = slots_[slot];
    if (s.head == kNone) {
      s.key = k;
      ++count_;
    }
    if (s.head == kNone || chunk(s.head).count == kLanes) s.head = new_chunk(s.head);
    Chunk& ch = chunk(s.head);
    const int t = ch.count++;
    ch.x[t] = static_cast<std::int16_t>(x);
    ch.y[t] = static_cast<std::int16_t>(y);
    ch.z[t] = static_cast<std::int16_t>(z);
    ch.node[t] = node;
  }
  std::uint32_t new_chunk(std::uint32_t next) {
    if (chunks_ == pages_.size() * kPage) pages_.push_back(std::make_unique<Chunk[]>(kPage));
    Chunk& ch = chunk(chunks_);
    std::fill(std::begin(ch.x), std::end(ch.x), kFar);
    std::fill(std::begin(ch.y), std::end(ch.y), std::int16_t{0});
    std::fill(std::begin(ch.z), std::end(ch.z), std::int16_t{0});
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
  double scale_ = 1.0;      // units per length
  std::int64_t reach_ = 0;  // the ball's radius in units, and kSlackUnits
  std::int32_t thr2_ = 0;   // its square: the filter's
  std::vector<Slot> slots_;
  int bits_ = 4;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Chunk[]>> pages_;
  std::uint32_t chunks_ = 0;
};

}  // namespace plyfit::detail
