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

/// Items by 3D position in cubes of side `cell` (a hash of their integer coordinates).
template <class T>
struct CubeGrid {
  double cell = 1.0;
  std::unordered_map<std::uint64_t, std::vector<T>> bins;
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(z & 0x1fffff);
  }
  std::int64_t at(double v) const { return static_cast<std::int64_t>(std::floor(v / cell)); }
  void add(const Vec3& p, T k) { bins[key(at(p.x()), at(p.y()), at(p.z()))].push_back(k); }
  /// Adds k to every cube the box [lo, hi] meets.
  void add_box(const Vec3& lo, const Vec3& hi, T k) {
    for (std::int64_t x = at(lo.x()); x <= at(hi.x()); ++x)
      for (std::int64_t y = at(lo.y()); y <= at(hi.y()); ++y)
        for (std::int64_t z = at(lo.z()); z <= at(hi.z()); ++z) bins[key(x, y, z)].push_back(k);
  }
  /// The items of the cube holding p (nullptr: none).
  const std::vector<T>* in(const Vec3& p) const {
    auto it = bins.find(key(at(p.x()), at(p.y()), at(p.z())));
    return it == bins.end() ? nullptr : &it->second;
  }
  /// Calls f(k) for the items in the 27 cubes around p.
  template <class F>
  void around(const Vec3& p, F&& f) const {
    const std::int64_t x = at(p.x()), y = at(p.y()), z = at(p.z());
    for (std::int64_t a = -1; a <= 1; ++a)
      for (std::int64_t b = -1; b <= 1; ++b)
        for (std::int64_t c = -1; c <= 1; ++c)
          if (auto it = bins.find(key(x + a, y + b, z + c)); it != bins.end())
            for (const T& k : it->second) f(k);
  }
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
  // Each segment in every cube of side kDartNearRel * d that its box grown by that much meets:
  // the cube holding p lists every segment within kDartNearRel * d of p.
  CubeGrid<Segment> segments_;
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
