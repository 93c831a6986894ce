// Private to the kernel: a seed curve given as a polyline (SeedCurve::kCurve). The base path
// follows it: each next path point is the point of the curve at link length from the point
// before it, then put on the surface by the base-path solver in the plane through the point
// before that holds the surface normal there and the chord to the curve's point.
#pragma once

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/result.hpp>

#include "surface/drape_surface.hpp"

#include <optional>
#include <vector>

namespace plyfit::detail {

/// A place on a polyline: segment `seg` (from point seg to seg + 1), parameter t in [0, 1].
struct CurvePlace {
  std::size_t seg = 0;
  double t = 0.0;
};

/// The seed curve projected onto the surface.
class SeedPolyline {
 public:
  /// The curve of `pb` (its seed_polyline, seed_polyline_closed) projected onto `s`; the
  /// place nearest `start` (on the surface). Errors: fewer than 2 points or a non-finite one
  /// (kBoundaryCurvePoints), a point farther than Tolerances::seed_curve_rel * s.size() from
  /// the surface (kSeedCurveOffMold: distance, tolerance, where), a start farther than that
  /// from the curve (kSeedNotOnCurve: distance, tolerance). They blame "seed-curve".
  static Result<SeedPolyline> create(const DrapeSurface& s, const DrapeProblem& pb,
                                     const Vec3& start, const Tolerances& tol);

  /// The place nearest the start.
  CurvePlace start_place() const { return start_; }
  /// The curve's unit direction at `at`, towards later points.
  Vec3 tangent(const CurvePlace& at) const;
  /// The first point of the curve after `at` (towards later points when `forward`) at
  /// distance `rest` from `centre`, and its place; none when the curve ends first (a closed
  /// curve is walked once round from the start).
  std::optional<std::pair<Vec3, CurvePlace>> at_distance(const CurvePlace& at, const Vec3& centre,
                                                         double rest, bool forward) const;

 private:
  Vec3 point(const CurvePlace& at) const;
  std::size_t segments() const { return closed_ ? p_.size() : p_.size() - 1; }
  const Vec3& vertex(std::size_t k) const { return p_[k % p_.size()]; }

  std::vector<Vec3> p_;
  bool closed_ = false;
  CurvePlace start_;
};

}  // namespace plyfit::detail
