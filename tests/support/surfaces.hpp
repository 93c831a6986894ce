#pragma once
// Surfaces with hard parametrisations, shared by the tests and plyfit-bench.

#include <plyfit/kernel/nurbs_surface.hpp>

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

}  // namespace plyfit::support
