#pragma once
// Surfaces with hard parametrisations, shared by the tests and plyfit-bench.

#include <plyfit/kernel/nurbs.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

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

/// A non-rational Bezier patch of degree p in u and v on [0, 1] x [0, 1] (no interior knot),
/// its (p + 1)^2 poles at the origin: the caller places them with pole(i, j).
inline NurbsSurfaceData bezier_patch(int p) {
  NurbsSurfaceData d;
  d.degree_u = d.degree_v = p;
  d.count_u = d.count_v = p + 1;
  d.knots_u.assign(static_cast<std::size_t>(p + 1), 0.0);
  d.knots_u.insert(d.knots_u.end(), static_cast<std::size_t>(p + 1), 1.0);
  d.knots_v = d.knots_u;
  d.poles.assign(static_cast<std::size_t>((p + 1) * (p + 1)), Vec3::Zero());
  return d;
}

/// A non-rational bicubic quarter dome with a pole: every pole of the first row (u = 0) is the
/// apex (0, 0, h), so that edge collapses to one point; the second row lies in the plane z = h,
/// so the apex is a smooth point with the tangent plane z = h (its fan of u-derivatives spans
/// 90 degrees). The outer row has radius `size`. `transpose`: u and v swap roles (the collapsed
/// edge is v = 0); `at_end`: the rows are reversed (the collapsed edge is u = 1, or v = 1).
inline NurbsSurfaceData quarter_dome(double size, double h, bool transpose, bool at_end) {
  constexpr double kQuarter = 1.5707963267948966;
  NurbsSurfaceData d = bezier_patch(3);
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

/// The surface with its u degree raised to `pu` and its v degree to `pv` (exact: the Bezier
/// degree elevation of the homogeneous poles). `s` must be one Bezier span in each direction
/// (clamped knots, no interior knot), as sphere_patch and cylinder_patch give for sweeps of
/// at most 90 degrees.
inline NurbsSurfaceData elevate_bezier(const NurbsSurfaceData& s, int pu, int pv) {
  auto binomial = [](int n, int k) {
    double b = 1.0;
    for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
    return b;
  };
  // Homogeneous poles (w x, w y, w z, w), one row per i.
  using H = Eigen::Vector4d;
  std::vector<std::vector<H>> h(static_cast<std::size_t>(s.count_u));
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      const double w = s.weight(i, j);
      h[i].push_back(H(w * s.pole(i, j).x(), w * s.pole(i, j).y(), w * s.pole(i, j).z(), w));
    }
  // Degree p to p + t of one Bezier row of poles.
  auto elevate = [&](const std::vector<H>& row, int t) {
    const int p = static_cast<int>(row.size()) - 1;
    std::vector<H> out(static_cast<std::size_t>(p + t + 1), H::Zero());
    for (int i = 0; i <= p + t; ++i)
      for (int j = std::max(0, i - t); j <= std::min(p, i); ++j)
        out[i] += binomial(p, j) * binomial(t, i - j) / binomial(p + t, i) * row[j];
    return out;
  };
  for (auto& row : h) row = elevate(row, pv - s.degree_v);  // along v
  std::vector<std::vector<H>> g(h[0].size());
  for (std::size_t j = 0; j < h[0].size(); ++j) {  // along u, column by column
    std::vector<H> col;
    for (const auto& row : h) col.push_back(row[j]);
    g[j] = elevate(col, pu - s.degree_u);
  }
  NurbsSurfaceData d;
  d.degree_u = pu;
  d.degree_v = pv;
  d.count_u = pu + 1;
  d.count_v = pv + 1;
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  d.knots_u.assign(static_cast<std::size_t>(pu + 1), u0);
  d.knots_u.insert(d.knots_u.end(), static_cast<std::size_t>(pu + 1), u1);
  d.knots_v.assign(static_cast<std::size_t>(pv + 1), v0);
  d.knots_v.insert(d.knots_v.end(), static_cast<std::size_t>(pv + 1), v1);
  for (int i = 0; i < d.count_u; ++i)
    for (int j = 0; j < d.count_v; ++j) {
      const H& q = g[j][i];
      d.poles.emplace_back(q.x() / q.w(), q.y() / q.w(), q.z() / q.w());
      d.weights.push_back(q.w());
    }
  return d;
}

/// The same surface with its knots mapped affinely onto [u0, u1] x [v0, v1] (a CAD export's
/// parameters: angles in radians, lengths from a distant origin).
inline NurbsSurfaceData remap_knots(NurbsSurfaceData d, double u0, double u1, double v0,
                                    double v1) {
  auto remap = [](std::vector<double>& k, double a, double b) {
    const double k0 = k.front(), k1 = k.back();
    for (double& x : k) x = x == k1 ? b : a + (x - k0) / (k1 - k0) * (b - a);
  };
  remap(d.knots_u, u0, u1);
  remap(d.knots_v, v0, v1);
  return d;
}

/// The same surface moved by `offset`.
inline NurbsSurfaceData translated(NurbsSurfaceData d, const Vec3& offset) {
  for (Vec3& p : d.poles) p += offset;
  return d;
}

}  // namespace plyfit::support
