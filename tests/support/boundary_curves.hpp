#pragma once
// Ply boundaries for tests and benchmarks: circles of a surface's development, and the
// development of the built-in flange + fillet + wall shell.

#include <plyfit/kernel/boundary.hpp>

#include <cmath>
#include <functional>

namespace plyfit::support {

/// The circle of radius r about (s0, y0) in a development, mapped by `at`, as a closed curve of
/// n points.
inline BoundaryCurve circle_curve(const std::function<Vec3(double, double)>& at, double s0,
                                  double y0, double r, int n) {
  BoundaryCurve c;
  c.name = "circle";
  c.closed = true;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    c.points.push_back(at(s0 + r * std::cos(t), y0 + r * std::sin(t)));
  }
  return c;
}

/// The point of the built-in flange-fillet-wall shell (default parameters: flange z = 0 for
/// x in [-40, 0], fillet of radius 10 about x = 0, z = -10, wall x = 10) at arc length s from
/// the fillet's top and y: the shell is developable, (s, y) its development.
inline Vec3 flange_fillet_wall_at(double s, double y) {
  const double r = 10.0, quarter = 0.5 * kPi * r;
  if (s <= 0) return Vec3(s, y, 0);
  if (s <= quarter) return Vec3(r * std::sin(s / r), y, r * std::cos(s / r) - r);
  return Vec3(r, y, -r - (s - quarter));
}

}  // namespace plyfit::support
