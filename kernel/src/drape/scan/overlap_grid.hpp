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
// on every mapped node, so what it costs per node is what matters: a few hundred
// instructions, few unpredictable branches, little memory, and little code (the scan's loop
// fills the instruction cache). What was measured: docs/decisions/overlap-grid.md.
// - Points are rounded to integer units, kCellUnits (a power of two) to a cell's edge of
//   kCellRadii * radius: a point's cell and its place in it are a shift and a mask.
// - A node is recorded in its own cell. A test reads the cells p's ball (radius and two
//   units) meets: its own and, per axis, the neighbour it lies within that of (one axis in
//   six on average), found from p's integer coordinates without a floor() or a
//   data-dependent loop per axis; one loop visits them, p's own cell last.
// - Open addressing on a cell key linear in the cell's coordinates (a neighbour's key is
//   the cell's plus a step; cells 2^21 apart share a key: that only adds candidates). The
//   cells of a block of 4 x 4 x 4 have neighbouring slots (multiplicative hashing of the
//   block): the table is megabytes, and with a slot per cell hashed apart a row of the scan
//   touches a slot on a different page per cell.
// - A cell's nodes lie in chunks of kLanes, two cache lines each: the nodes' points as 16-bit
//   integers relative to the cell's centre (structure of arrays, unused lanes far away) and
//   a pointer to the cell's previous chunk; the node indices lie apart, read only on a hit.
//   A chunk is filtered whole with SSE2 integer arithmetic (no branch per node) by a
//   distance two units wider than the ball (each integer is within half a unit of its
//   point's exact scaled coordinate, so a difference of two within one, a distance within
//   sqrt(3)); only a chunk with a node within it, rare unless the cloth comes back, goes to
//   the caller's exact test on the node's own doubles. The answer is the same as an
//   all-double test's.
class OverlapGrid {
 public:
  // Cell edge over the test radius (>= 2: the ball meets at most two cells per axis). Larger
  // cells mean fewer cells visited, more nodes per cell: 12, with two-line chunks of 16
  // lanes, took the test least time (fewer cache lines per cell of the scan's front).
  static constexpr int kCellRadii = 12;
  // A cell's edge in integer units: the radius is kCellUnits / kCellRadii = 1365.3 units. A
  // coordinate relative to its cell's centre is at most kCellUnits / 2 + 1368 = 9560 units,
  // a difference of two at most 19120 (16 bits), a squared distance 3 * 19120^2 < 2^31
  // (the sums are 32-bit).
  static constexpr int kCellBits = 14;
  static constexpr std::int64_t kCellUnits = std::int64_t{1} << kCellBits;
  // Units added to the radius in the cell-membership and filter tests (a coordinate's
  // rounding is half a unit: a difference of two within one unit per axis).
  static constexpr int kSlackUnits = 2;
  // Expected mapped nodes per occupied cell: sizes the slot table for `expected` nodes (it
  // doubles when more cells are met). The surface crosses a cell of edge kCellRadii *
  // kOverlapRel * d = 6 d at 26 to 30 nodes on average (octant and wave at 1000^2): at 12,
  // 1.07 (wave) to 1.71 (octant, closed hemisphere) probes per look-up at 1000^2 (blocks of
  // 64 slots hashed whole leave gaps); 48 (a quarter of the table) made the drape slower.
  static constexpr std::size_t kNodesPerCell = 12;

  void init(double radius, std::size_t expected) {
    const double units = static_cast<double>(kCellUnits) / kCellRadii;  // per radius
    scale_ = units / radius;
    reach_ = static_cast<std::int64_t>(std::ceil(units)) + kSlackUnits;
    thr2_ = static_cast<std::int32_t>(reach_ * reach_);
    std::size_t n = std::size_t{2} << kBlockBits;  // two blocks of slots at least (home())
    bits_ = kBlockBits + 1;
    while (n < 2 * (expected / kNodesPerCell)) {
      n *= 2;
      ++bits_;
    }
    // This thread's previous drape's slots and pages, if it left them (Spare): the same
    // memory again, not fresh pages the system must fault in and zero.
    Spare& spare = thread_spare();
    if (slots_.empty() && pages_.empty()) {
      slots_.swap(spare.slots);
      pages_.swap(spare.pages);
    }
    slots_.assign(n, Slot{0, nullptr});
    count_ = 0;
    chunks_ = 0;  // the pages are reused: new_chunk() sets every field it reads
  }
  OverlapGrid() = default;
  OverlapGrid(const OverlapGrid&) = delete;
  OverlapGrid& operator=(const OverlapGrid&) = delete;
  // Leaves the slots and up to kRetainBytes of pages to the thread's next drape.
  ~OverlapGrid() {
    Spare& spare = thread_spare();
    if (!spare.slots.empty() || !spare.pages.empty()) return;  // a nested drape's grid is there
    const std::size_t keep = kRetainBytes / sizeof(Page);
    if (pages_.size() > keep) pages_.resize(keep);
    if (slots_.capacity() * sizeof(Slot) <= kRetainBytes) spare.slots.swap(slots_);
    spare.pages.swap(pages_);
  }
  // Frees the slots and pages this thread's last drape left (tests and benchmarks that
  // measure a first drape's memory).
  static void release_thread_spare() { thread_spare() = Spare{}; }
  // Bytes this thread's spare holds.
  static std::size_t thread_spare_bytes() {
    const Spare& spare = thread_spare();
    return spare.slots.capacity() * sizeof(Slot) + spare.pages.size() * sizeof(Page);
  }
  // True if `exact(node)` holds for some recorded node within `radius` of p (3D); exact
  // receives the index given to a previous call and does the full test in doubles (it must
  // reject nodes farther than `radius`: the filter passes a little more). If it holds for
  // none, records `node` at p.
  template <class Exact>
  bool test_insert(const Vec3& p, std::uint32_t node, Exact&& exact) {
    // Per axis a: p in units relative to its cell's centre, the neighbour its ball meets
    // (side -1, 0 or +1; bit a of `both` if any), the key step and the shift of p's
    // coordinate to that neighbour.
    std::uint64_t own_key = 0, step[3];
    std::int32_t q[3], shift[3];
    unsigned both = 0;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t u = round_int(p[a] * scale_);
      const std::int64_t at = u & (kCellUnits - 1);  // place in the cell
      // +1 if at >= kCellUnits - reach_, -1 if at < reach_ (reach_ < kCellUnits / 2).
      const std::int64_t side = ((at + reach_) >> kCellBits) + ((at - reach_) >> 63);
      both |= static_cast<unsigned>(side & 1) << a;
      own_key += static_cast<std::uint64_t>(u >> kCellBits) << kKeyShift[a];
      step[a] = static_cast<std::uint64_t>(side) << kKeyShift[a];
      q[a] = static_cast<std::int32_t>(at - kCellUnits / 2);
      shift[a] = static_cast<std::int32_t>(side * kCellUnits);
    }
    // The cells the ball meets: for every subset m of `both` (bit a: the neighbour along
    // axis a), down to the empty one, p's own cell. One loop: the test's code stays small.
    std::size_t own;
    for (unsigned m = both;; m = (m - 1) & both) {
      std::uint64_t key = own_key;
      std::int32_t c[3];
      for (int a = 0; a < 3; ++a) {
        const std::int32_t in = -static_cast<std::int32_t>((m >> a) & 1);
        key += step[a] & static_cast<std::uint64_t>(static_cast<std::int64_t>(in));
        c[a] = q[a] - (shift[a] & in);
      }
      const std::size_t s = find(key);
      if (const Chunk* h = slots_[s].head;
          h != nullptr && near_in(h, at_point(filter_base(), c[0], c[1], c[2]), exact))
        return true;
      if (m == 0) {
        own = s;
        break;
      }
    }
    if (slots_[own].head == nullptr && 2 * (count_ + 1) > slots_.size()) {
      grow();
      own = find(own_key);
    }
    insert(slots_[own], own_key, q[0], q[1], q[2], node);
    return false;
  }

 private:
  static constexpr int kLanes = 16;
  // The largest coordinate relative to a cell's centre (see kCellBits).
  static constexpr double kMaxCoord =
      kCellUnits / 2 + static_cast<double>(kCellUnits) / kCellRadii + 1 + kSlackUnits;
  static_assert(2 * kMaxCoord <= 32767 && 3 * (2 * kMaxCoord) * (2 * kMaxCoord) < 2147483647.0,
                "a difference of two coordinates fits 16 bits, a squared distance 31");
  // x of an unused lane (y and z 0): its difference saturates at 16 bits, its squared
  // distance stays within 31 bits and fails the filter.
  static constexpr std::int16_t kFar = 32767;
  // Chunks are allocated in pages of kPage, never moved (no copy, no reserve beyond need). A
  // page is 192 KB: a drape of 10^4 nodes needs about 800 chunks, and pages of 4096 chunks
  // (768 KB) took it 60 B/node more peak heap (the throughput table's 100^2 rows).
  static constexpr std::uint32_t kPageBits = 10, kPage = 1u << kPageBits;
  // A cell's key: its coordinates times these, summed (wrapping).
  static constexpr int kKeyShift[3] = {42, 21, 0};
  static constexpr int kBlockBits = 6;  // slots of a block of cells
  static constexpr std::uint64_t kInBlock =
      (std::uint64_t{3} << kKeyShift[0]) | (std::uint64_t{3} << kKeyShift[1]) | 3;
  struct Chunk;
  struct Slot {
    std::uint64_t key;  // the cell's key
    Chunk* head;        // the cell's newest chunk, null for an empty slot
  };
  // Two cache lines (a pair the adjacent-line prefetcher fetches together): what the
  // filter reads.
  struct alignas(128) Chunk {
    // Points relative to the cell's centre, in units: lane t's x and y in xy[2 t] and
    // xy[2 t + 1] (one multiply-add gives four lanes' x^2 + y^2), its z in z[t].
    std::int16_t xy[2 * kLanes];
    std::int16_t z[kLanes];
    Chunk* next;          // the cell's previous (full) chunk
    std::uint32_t count;  // lanes used
    std::uint32_t id;     // this chunk's number: its node indices' place
  };
  static_assert(sizeof(Chunk) == 128, "a chunk is two cache lines");
  struct Page {
    Chunk chunk[kPage];
    std::uint32_t node[kPage][kLanes];  // the nodes of chunk[c], lane by lane
  };
  // What a grid leaves to the next one on its thread: optimize's workers and library loops
  // drape again and again on a thread, and fresh pages are faulted in and zeroed by the
  // system on every drape. Retained up to kRetainBytes of pages (a drape of about 3.5 M
  // nodes; more are freed) and a slot table of as much.
  struct Spare {
    std::vector<Slot> slots;
    std::vector<std::unique_ptr<Page>> pages;
  };
  static constexpr std::size_t kRetainBytes = std::size_t{64} << 20;
  static Spare& thread_spare() {
    thread_local Spare spare;
    return spare;
  }
#if defined(__SSE2__)
  // p's coordinates (units relative to a cell's centre) in every lane, and the filter's
  // squared distance.
  struct Filter {
    __m128i xy, z, thr;  // (x, y) pairs, z
  };
  Filter filter_base() const {
    return Filter{{}, {}, _mm_set1_epi32(thr2_)};
  }
  static Filter at_point(Filter f, std::int32_t x, std::int32_t y, std::int32_t z) {
    f.xy = _mm_set1_epi32(static_cast<std::int32_t>((static_cast<std::uint32_t>(x) & 0xffffu) |
                                                    (static_cast<std::uint32_t>(y) << 16)));
    f.z = _mm_set1_epi16(static_cast<std::int16_t>(z));
    return f;
  }
  // Bit t set if lane t of ch lies within the filter's distance of its point.
  static unsigned near_lanes(const Chunk& ch, const Filter& f) {
    const __m128i* xy = reinterpret_cast<const __m128i*>(ch.xy);
    const __m128i* zp = reinterpret_cast<const __m128i*>(ch.z);
    const __m128i zero = _mm_setzero_si128();
    unsigned near = 0;
    for (int g = 0; g < kLanes / 8; ++g) {                                 // lanes 8 g to 8 g + 7
      const __m128i a = _mm_subs_epi16(_mm_load_si128(xy + 2 * g), f.xy);  // 4 lanes
      const __m128i b = _mm_subs_epi16(_mm_load_si128(xy + 2 * g + 1), f.xy);
      const __m128i dz = _mm_sub_epi16(_mm_load_si128(zp + g), f.z);
      const __m128i za = _mm_unpacklo_epi16(dz, zero), zb = _mm_unpackhi_epi16(dz, zero);
      const __m128i lo = _mm_add_epi32(_mm_madd_epi16(a, a), _mm_madd_epi16(za, za));
      const __m128i hi = _mm_add_epi32(_mm_madd_epi16(b, b), _mm_madd_epi16(zb, zb));
      const __m128i m = _mm_packs_epi32(_mm_cmplt_epi32(lo, f.thr), _mm_cmplt_epi32(hi, f.thr));
      near |= static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi16(m, zero))) << (8 * g);
    }
    return near;
  }
#else
  struct Filter {
    std::int32_t x, y, z, thr;
  };
  Filter filter_base() const {
    return Filter{0, 0, 0, thr2_};
  }
  static Filter at_point(Filter f, std::int32_t x, std::int32_t y, std::int32_t z) {
    f.x = x;
    f.y = y;
    f.z = z;
    return f;
  }
  static unsigned near_lanes(const Chunk& ch, const Filter& f) {
    unsigned near = 0;
    for (int t = 0; t < kLanes; ++t) {
      const std::int32_t dx = std::min<std::int32_t>(ch.xy[2 * t] - f.x, 32767);
      const std::int32_t dy = ch.xy[2 * t + 1] - f.y, dz = ch.z[t] - f.z;
      near |= (dx * dx + dy * dy + dz * dz < f.thr ? 1u : 0u) << t;
    }
    return near;
  }
#endif
  // True if exact() accepts a node of the chunks from h on that the filter passes.
  template <class Exact>
  bool near_in(const Chunk* h, const Filter& f, Exact& exact) const {
    do {
      if (const unsigned near = near_lanes(*h, f);
          __builtin_expect(near != 0, 0) && exact_in(*h, near, exact))
        return true;
      h = h->next;
    } while (h != nullptr);
    return false;
  }
  // True if exact() accepts a node of lanes `near` of ch. Out of line: rare unless the cloth
  // comes back, and the test's code stays small.
  template <class Exact>
  [[gnu::noinline, gnu::cold]] bool exact_in(const Chunk& ch, unsigned near, Exact& exact) const {
    for (; near != 0; near &= near - 1)
      if (exact(node_of(ch, __builtin_ctz(near)))) return true;
    return false;
  }
  std::uint32_t node_of(const Chunk& ch, int lane) const {
    return pages_[ch.id >> kPageBits]->node[ch.id & (kPage - 1)][lane];
  }
  // v rounded to the nearest integer (the default rounding mode); |v| < 2^62.
  static std::int64_t round_int(double v) {
#if defined(__SSE2__)
    return _mm_cvtsd_si64(_mm_set_sd(v));
#else
    return std::llrint(v);
#endif
  }
  // The slot of cell key k, or the empty slot where it would go.
  std::size_t find(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = home(k);; h = (h + 1) & mask)
      if (slots_[h].head == nullptr || slots_[h].key == k) return h;
  }
  // Where the slot of cell key k is looked for first: the cells of a block of 4 x 4 x 4 (the
  // key's two low bits of each coordinate) have neighbouring slots, 64 in a row (1 KB), the
  // block's place hashed. The slots of a row of the scan then lie on few memory pages.
  std::size_t home(std::uint64_t k) const {
    const std::uint64_t block = k & ~kInBlock;
    const std::size_t in = static_cast<std::size_t>(((k >> kKeyShift[0]) & 3) << 4 |
                                                    ((k >> kKeyShift[1]) & 3) << 2 | (k & 3));
    // bits_ > kBlockBits (init): the shift stays below 64.
    const std::uint64_t at = (block * 0x9E3779B97F4A7C15ULL) >> (64 - bits_ + kBlockBits);
    return static_cast<std::size_t>(at << kBlockBits) | in;
  }
  // Records node at (x, y, z) (units, relative to the cell's centre) in the cell of key k,
  // whose slot is s (the table has room for it).
  void insert(Slot& s, std::uint64_t k, std::int32_t x, std::int32_t y, std::int32_t z,
              std::uint32_t node) {
    if (s.head == nullptr || s.head->count == kLanes) new_chunk(s, k);
    Chunk& ch = *s.head;
    const std::uint32_t t = ch.count++;
    ch.xy[2 * t] = static_cast<std::int16_t>(x);
    ch.xy[2 * t + 1] = static_cast<std::int16_t>(y);
    ch.z[t] = static_cast<std::int16_t>(z);
    pages_[ch.id >> kPageBits]->node[ch.id & (kPage - 1)][t] = node;
  }
  // A new empty chunk at the head of slot s (key k; s empty or its head full). Out of line:
  // one insertion in several takes it, and the test's code stays small.
  [[gnu::noinline]] void new_chunk(Slot& s, std::uint64_t k) {
    if (s.head == nullptr) {
      s.key = k;
      ++count_;
    }
    if (chunks_ == pages_.size() * kPage)
      pages_.push_back(std::unique_ptr<Page>(new Page));  // not zeroed: lanes are set below
    Chunk& ch = pages_[chunks_ >> kPageBits]->chunk[chunks_ & (kPage - 1)];
    for (int t = 0; t < kLanes; ++t) {
      ch.xy[2 * t] = kFar;
      ch.xy[2 * t + 1] = 0;
    }
    std::fill(std::begin(ch.z), std::end(ch.z), std::int16_t{0});
    ch.next = s.head;
    ch.count = 0;
    ch.id = chunks_++;
    s.head = &ch;
  }
  [[gnu::noinline, gnu::cold]] void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(2 * old.size(), Slot{0, nullptr});
    ++bits_;
    for (const Slot& o : old)
      if (o.head != nullptr) slots_[find(o.key)] = o;
  }
  double scale_ = 1.0;      // units per length
  std::int64_t reach_ = 0;  // the ball's radius in units, and kSlackUnits
  std::int32_t thr2_ = 0;   // its square: the filter's
  std::vector<Slot> slots_;
  int bits_ = kBlockBits + 1;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Page>> pages_;
  std::uint32_t chunks_ = 0;
};

}  // namespace plyfit::detail
