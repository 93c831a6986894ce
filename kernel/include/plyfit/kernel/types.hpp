#pragma once
/// \file Basic geometric types shared by every plyfit module.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>

namespace plyfit {

/// A 2D vector (ply coordinates or surface parameters (u, v)).
using Vec2 = Eigen::Vector2d;
/// A 3D vector or point, in model units (millimetres unless stated otherwise).
using Vec3 = Eigen::Vector3d;

/// π, and the factors that turn degrees into radians (deg * kDegToRad) and back.
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

/// Axis-aligned box in 3D.
struct BBox3 {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(0.0);
  bool empty = true;
  /// Grows the box to contain p.
  void add(const Vec3& p) {
    if (empty) {
      min = max = p;
      empty = false;
    } else {
      min = min.cwiseMin(p);
      max = max.cwiseMax(p);
    }
  }
  /// Length of the diagonal (0 for an empty box).
  double diagonal() const { return empty ? 0.0 : (max - min).norm(); }
};

/// A rectangle in the (u, v) parameter plane.
struct ParamDomain {
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
  double width_u() const { return u1 - u0; }
  double width_v() const { return v1 - v0; }
  /// True when (u, v) lies in the closed rectangle enlarged by `margin_u`, `margin_v`.
  bool contains(double u, double v, double margin_u = 0.0, double margin_v = 0.0) const {
    return u >= u0 - margin_u && u <= u1 + margin_u && v >= v0 - margin_v && v <= v1 + margin_v;
  }
};

/// 2D cross product (z component of the 3D cross product of (a, 0) and (b, 0)).
inline double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// a turned by +90 degrees (counter-clockwise).
inline Vec2 perp(const Vec2& a) {
  return Vec2(-a.y(), a.x());
}

/// Distance from p to the segment ab (2D or 3D); |p - a| when a == b.
template <typename V>
inline double segment_distance(const V& p, const V& a, const V& b) {
  const V d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

/// True when every component of v is finite.
template <typename Derived>
inline bool all_finite(const Eigen::MatrixBase<Derived>& v) {
  return v.allFinite();
}

}  // namespace plyfit
