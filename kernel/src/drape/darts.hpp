// Private to the kernel: darts, cuts in the ply along curves on the part. The scan asks
// whether a thread link crosses a dart (such links are not enforced: the cloth on the two
// sides drapes independently); after the scan each dart's curve is carried into the ply
// through each side's cells, giving its two cut lines.
#pragma once

#include "surface/drape_surface.hpp"

#include <plyfit/kernel/drape.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace plyfit::detail {

// A dart's curve is followed on the surface at most kDartStepRel * d between points (its
// chords then sag below the surface by about (d/2)^2 / 8R: far below the link length).
inline constexpr double kDartStepRel = 0.5;
// A link crosses a dart where their projections onto the tangent plane cross and the link
// passes within kDartOffsetRel * d of the dart along the normal there: a link and a dart on
// the part meet to their chords' sag; farther apart they are on two sheets of the part.
inline constexpr double kDartOffsetRel = 0.5;
// Nodes within kDartNearRel * d of a dart's curve are tested (a node's neighbours lie within
// one link of it, two of each other; a link crossing the dart passes within half a spacing).
inline constexpr double kDartNearRel = 3.0;

/// A dart's curve on the surface, with the normals the crossing test projects along.
struct DartCurve {
  static constexpr std::uint64_t kNoLink = ~std::uint64_t{0};
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  /// Per point of a seam: the cut link (DrapeResult::link_key) whose midpoint it is, whose two
  /// ends are the cloth of its two sides (kNoLink: a point between them). Empty for a dart.
  std::vector<std::uint64_t> links;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // bounding box
  double length = 0.0;
  /// Appends a point of the surface and its unit normal (a repeated point is dropped), and,
  /// for a seam, the link it was made from.
  void add(const Vec3& p, const Vec3& n, std::uint64_t link = kNoLink);
};

/// Where a walk on the surface ended: at the face's edge (the free boundary), at a crease the
/// surface turns away at (or where no normal was found), or after its length.
enum class WalkEnd : std::uint8_t { kEdge, kCrease, kLength };
/// Appends to `c` a walk on `s` from p (not added) along dir, steps of h, at most `length`
/// long, until the face's edge or a sharp crease the surface turns away at stops it. The
/// points are kept with their normals (a dart's curve: not projected again).
WalkEnd walk_on_surface(const DrapeSurface& s, Vec3 p, Vec3 dir, double h, double length,
                        DartCurve& c);
/// The same, also ended after the first point for which `enough` holds (kLength).
WalkEnd walk_on_surface(const DrapeSurface& s, Vec3 p, Vec3 dir, double h, double length,
                        DartCurve& c, const std::function<bool(const Vec3&)>& enough);

/// The cube of side `cell` holding a point, as one key (21 bits of each integer coordinate).
struct CubeKeys {
  double cell = 1.0;
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(z & 0x1fffff);
  }
  std::int64_t at(double v) const { return static_cast<std::int64_t>(std::floor(v / cell)); }
  std::uint64_t key(const Vec3& p) const { return key(at(p.x()), at(p.y()), at(p.z())); }
  /// Calls f(key) for every cube the box [lo, hi] meets.
  template <class F>
  void in_box(const Vec3& lo, const Vec3& hi, F&& f) const {
    for (std::int64_t x = at(lo.x()); x <= at(hi.x()); ++x)
      for (std::int64_t y = at(lo.y()); y <= at(hi.y()); ++y)
        for (std::int64_t z = at(lo.z()); z <= at(hi.z()); ++z) f(key(x, y, z));
  }
  /// Calls f(key) for the 27 cubes around p, in one order.
  template <class F>
  void around(const Vec3& p, F&& f) const {
    const std::int64_t x = at(p.x()), y = at(p.y()), z = at(p.z());
    for (std::int64_t a = -1; a <= 1; ++a)
      for (std::int64_t b = -1; b <= 1; ++b)
        for (std::int64_t c = -1; c <= 1; ++c) f(key(x + a, y + b, z + c));
  }
};

/// Items by 3D position in cubes of side `cell` (a hash of their integer coordinates), added
/// one by one.
template <class T>
struct CubeGrid : CubeKeys {
  std::unordered_map<std::uint64_t, std::vector<T>> bins;
  void add(const Vec3& p, T k) { bins[key(p)].push_back(k); }
  /// Calls f(k) for the items in the 27 cubes around p (each cube's in the order added).
  template <class F>
  void around(const Vec3& p, F&& f) const {
    CubeKeys::around(p, [&](std::uint64_t c) {
      if (auto it = bins.find(c); it != bins.end())
        for (const T& k : it->second) f(k);
    });
  }
};

/// Numbers 0 .. count - 1 (a drape's nodes, points of a curve, segments of darts) by 3D
/// position in cubes of side `cell`, all given at once: one array of them by cube and an
/// open-addressing table of the cubes, two passes over them, no allocation per cube and
/// lookups without a division (docs/decisions/darts.md: what a hash map of vectors cost the
/// darts' proposals). Each cube lists its numbers in increasing order: around() and in() visit
/// the same items in the same order as a CubeGrid's to which they were added in that order.
class FrozenGrid : public CubeKeys {
 public:
  FrozenGrid() = default;
  /// The numbers k < count for which keep(k) holds, at point_of(k).
  template <class Keep, class PointOf>
  FrozenGrid(double cube, std::uint32_t count, Keep&& keep, PointOf&& point_of)
      : FrozenGrid(cube, count, [&](std::uint32_t k, auto&& emit) {
          if (keep(k)) emit(CubeKeys{cube}.key(point_of(k)));
        }) {}
  /// The numbers k < count, each in the cubes for which cubes_of(k, emit) calls emit(key).
  template <class CubesOf>
  FrozenGrid(double cube, std::uint32_t count, CubesOf&& cubes_of) {
    cell = cube;
    grow();
    for (std::uint32_t k = 0; k < count; ++k)
      cubes_of(k, [&](std::uint64_t c) {
        if (Slot* s = slot(c)) ++s->count;
      });
    std::uint32_t begin = 0;
    for (Slot& s : slots_)
      if (s.key != kEmpty) s.begin = begin, begin += s.count, s.count = 0;
    items_.resize(begin);
    for (std::uint32_t k = 0; k < count; ++k)
      cubes_of(k, [&](std::uint64_t c) {
        if (Slot* s = slot(c)) items_[s->begin + s->count++] = k;
      });
  }
  /// The numbers in one cube.
  struct Items {
    const std::uint32_t *first = nullptr, *last = nullptr;
    const std::uint32_t* begin() const { return first; }
    const std::uint32_t* end() const { return last; }
  };
  /// The numbers of the cube holding p (none: empty).
  Items in(const Vec3& p) const {
    const Slot* s = find(key(p));
    if (!s) return {};
    return {items_.data() + s->begin, items_.data() + s->begin + s->count};
  }
  /// Calls f(k) for the numbers in the 27 cubes around p (each cube's in increasing order).
  template <class F>
  void around(const Vec3& p, F&& f) const {
    CubeKeys::around(p, [&](std::uint64_t c) {
      if (const Slot* s = find(c))
        for (std::uint32_t i = s->begin; i < s->begin + s->count; ++i) f(items_[i]);
    });
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // no key has all 64 bits set
  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t begin = 0, count = 0;
  };
  // Fibonacci hashing: the product's top bits (its low bits see only the key's low bits,
  // and cubes apart along x differ only in the key's high ones).
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
  }
  // The slot of `key`, taken if it had none; the table doubles before it is half full (sized
  // by the cubes, not by the items: a dart's segment lies in a dozen cubes its neighbours share).
  Slot* slot(std::uint64_t key) {
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t i = home(key), probes = 0; probes < slots_.size();
           ++probes, i = (i + 1) & mask_) {
        if (slots_[i].key == key) return &slots_[i];
        if (slots_[i].key != kEmpty) continue;
        if (2 * (used_ + 1) > slots_.size()) break;  // grow first
        slots_[i].key = key;
        ++used_;
        return &slots_[i];
      }
      grow();
    }
    return nullptr;  // not reached: after growing, the table is less than half full
  }
  // Doubles the table (16 slots at first), the cubes taken so far placed again.
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 16 : 2 * old.size(), Slot{});
    mask_ = slots_.size() - 1;
    shift_ = 64;
    for (std::size_t n = slots_.size(); n > 1; n /= 2) --shift_;
    for (const Slot& o : old) {
      if (o.key == kEmpty) continue;
      for (std::size_t i = home(o.key), probes = 0; probes < slots_.size();
           ++probes, i = (i + 1) & mask_)
        if (slots_[i].key == kEmpty) {
          slots_[i] = o;
          break;
        }
    }
  }
  const Slot* find(std::uint64_t key) const {
    for (std::size_t i = home(key), probes = 0; probes < slots_.size();
         ++probes, i = (i + 1) & mask_) {
      if (slots_[i].key == key) return &slots_[i];
      if (slots_[i].key == kEmpty) return nullptr;
    }
    return nullptr;
  }
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> items_;
  std::size_t mask_ = 0;
  int shift_ = 60;        // 64 - log2(slots)
  std::size_t used_ = 0;  // slots taken
};
using NodeGrid = CubeGrid<std::uint32_t>;

/// The darts of a drape, on its surface, with an index of their segments.
class DartSet {
 public:
  /// The curves projected onto `s` and followed at kDartStepRel * d. Errors (blaming "dart"):
  /// a curve of fewer than 2 points or a non-finite point (kDartCurvePoints: the dart's number
  /// and its point count), a point farther from the surface than
  /// Tolerances::boundary_on_mold_rel of its size (kDartOffMold: the dart's number, the
  /// distance, the tolerance and the point).
  static Result<DartSet> create(const DrapeSurface& s, const std::vector<std::vector<Vec3>>& darts,
                                double d, const Tolerances& tol);
  /// Curves already on the surface (each of 2 points at least, with their normals), as a walk
  /// on it made them: not projected again.
  static DartSet of(std::vector<DartCurve> curves, double d);
  bool empty() const { return curves_.empty(); }
  const std::vector<DartCurve>& curves() const { return curves_; }
  /// True when p lies within kDartNearRel * d of some dart's curve.
  bool near(const Vec3& p) const;
  /// The dart whose curve passes nearest to p (-1: none within kDartNearRel * d).
  int nearest(const Vec3& p) const;
  /// True when the segment p-q (a link on the part) crosses some dart.
  bool crosses(const Vec3& p, const Vec3& q) const;

 private:
  struct Segment {
    std::uint32_t curve, k;  // points k and k + 1 of curves_[curve]
  };
  void index();
  double distance(const Segment& g, const Vec3& p) const;
  bool crosses(const DartCurve& c, std::size_t k, const Vec3& p, const Vec3& q) const;
  std::vector<DartCurve> curves_;
  double d_ = 1.0;
  std::vector<Segment> segments_;
  // Each segment (its number in segments_) in every cube of side kDartNearRel * d that its box
  // grown by that much meets: the cube holding p lists every segment within kDartNearRel * d
  // of p.
  FrozenGrid segment_cubes_;
  double segment_max_ = 0.0;  // the longest segment
};

/// The seams of a drape whose scan cut `links` (DrapeResult::link_key) where two fronts of
/// cloth met and disagreed: the links' midpoints (on the surface) in chains, each a couple of
/// spacings from the next, one curve per chain, run on half a spacing beyond its ends.
std::vector<DartCurve> seam_curves(const DrapeSurface& s, const DrapeResult& r,
                                   const std::vector<std::uint64_t>& links);

/// Each dart as the drape laid it (DrapeResult::darts): its cut lines through the cells of each
/// side (on its sheet of `s`: nodes whose normal turns 90 degrees or more from the curve's are
/// not beside it), the area between them, the links it cut; `cut_out`: per dart, the ply nodes
/// no side holds.
void lay_darts(const DrapeSurface& s, const DartSet& darts,
               const std::vector<std::uint64_t>& cut_out, const Tolerances& tol, DrapeResult& res);

}  // namespace plyfit::detail
