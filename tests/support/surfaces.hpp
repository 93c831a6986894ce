#pragma once
// Surfaces with hard parametrisations, shared by the tests and plyfit-bench.

#include <plyfit/kernel/nurbs.hpp>

#include <cmath>

namespace plyfit::support {

/// A flat 20 x 20 patch [-10, 10]^2 at z = 0 with a wild parametrisation: bicubic, 7 x 7
/// poles, knot spans 1000x apart (if `knots`; else uniform on [0, 1]) and product weights
/// from 0.01 to 100 (if `weights`). The geometry is a plane, so answers are exact.
inline NurbsSurfaceData wild_plane(bool knots, bool weights) {
  NurbsSurfaceData d;
  d.degree_u = d.degree_v = 3;
  d.count_u = d.count_v = 7;
  if (knots) {
    d.knots_u = {0, 0, 0, 0, 0.001, 0.002, 1.0, 2.0, 2.0, 2.0, 2.0};
    d.knots_v = {0, 0, 0, 0, 1.0, 1000.0, 1001.0, 2000.0, 2000.0, 2000.0, 2000.0};
  } else {
    d.knots_u = d.knots_v = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  }
  const double alpha[7] = {0.1, 10, 0.1, 3, 10, 0.2, 1};
  const double beta[7] = {10, 0.1, 5, 0.1, 10, 0.1, 1};
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      d.poles.emplace_back(-10 + 20.0 * i / 6, -10 + 20.0 * j / 6, 0.0);
      if (weights) d.weights.push_back(alpha[i] * beta[j]);
    }
  return d;
}

/// A roof of two planes meeting in a C0 crease along x = 0 (degree 2 in u with a double
/// knot), 4s x 6s, slopes +-1/2, ridge at z = s: z = s - |x| / 2 for |x| <= 2s.
inline NurbsSurfaceData roof(double s) {
  NurbsSurfaceData d;
  d.degree_u = 2;
  d.degree_v = 1;
  d.count_u = 5;
  d.count_v = 2;
  d.knots_u = {0, 0, 0, 0.5, 0.5, 1, 1, 1};
  d.knots_v = {0, 0, 1, 1};
  for (Vec3 p : {Vec3(-2, 0, 0), Vec3(-1, 0, 0.5), Vec3(0, 0, 1), Vec3(1, 0, 0.5), Vec3(2, 0, 0)}) {
    d.poles.push_back(s * (p + Vec3(0, -3, 0)));
    d.poles.push_back(s * (p + Vec3(0, 3, 0)));
  }
  return d;
}

/// A non-rational bicubic quarter dome with a pole: every pole of the first row (u = 0) is the
/// apex (0, 0, h), so that edge collapses to one point; the second row lies in the plane z = h,
/// so the apex is a smooth point with the tangent plane z = h (its fan of u-derivatives spans
/// 90 degrees). The outer row has radius `size`. `transpose`: u and v swap roles (the collapsed
/// edge is v = 0); `at_end`: the rows are reversed (the collapsed edge is u = 1, or v = 1).
inline NurbsSurfaceData quarter_dome(double size, double h, bool transpose, bool at_end) {
  constexpr double kQuarter = kPi / 2;
  NurbsSurfaceData d;
  d.degree_u = d.degree_v = 3;
  d.count_u = d.count_v = 4;
  d.knots_u = d.knots_v = {0, 0, 0, 0, 1, 1, 1, 1};
  d.poles.resize(16);
  for (int i = 0; i < 4; ++i) {
    const double rho = size * i / 3.0;
    const double z = i <= 1 ? h : h - 0.3 * size * (i / 3.0) * (i / 3.0);
    for (int j = 0; j < 4; ++j) {
      const double t = kQuarter * j / 3.0;
      const int row = at_end ? 3 - i : i;
      d.pole(transpose ? j : row, transpose ? row : j) =
          Vec3(rho * std::cos(t), rho * std::sin(t), z);
    }
  }
  return d;
}

}  // namespace plyfit::support
