#pragma once
// A high-precision reference evaluation of NURBS surfaces and curves, written independently of
// the kernel (Cox-de Boor triangle and the derivative recursion of The NURBS Book eq. 2.9,
// not A2.3), in boost's 113-bit binary float. It is slow and used only to decide which of the
// kernel and OpenCASCADE is right where they disagree.

#include <plyfit/kernel/nurbs.hpp>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <array>
#include <vector>

namespace plyfit::test {

/// 113-bit mantissa (IEEE quad precision): about 1e-34 relative rounding.
using Quad = boost::multiprecision::cpp_bin_float_quad;

/// Index s of the span [U_s, U_s+1) used at t: the last span of positive length in [p, n]
/// with U_s <= t (the right-hand span at an interior knot, the last span at the domain end),
/// the convention of both the kernel and OpenCASCADE.
inline int reference_span(const std::vector<double>& U, int p, int n, double t) {
  int s = p;
  for (int i = p; i <= n; ++i)
    if (U[i] < U[i + 1] && U[i] <= t) s = i;
  return s;
}

/// ders[k][j]: k-th derivative (k = 0..2) of N_{s-p+j, p} at t, j = 0..p.
inline std::vector<std::array<Quad, 3>> reference_basis(const std::vector<double>& U, int p, int s,
                                                        double t) {
  // D[k][d][j]: k-th derivative of N_{s-p+j, d}; only j >= p - d can be non-zero.
  std::vector<std::vector<std::vector<Quad>>> D(
      3, std::vector<std::vector<Quad>>(p + 1, std::vector<Quad>(p + 2, Quad(0))));
  D[0][0][p] = 1;
  const Quad x(t);
  for (int d = 1; d <= p; ++d) {
    for (int j = p - d; j <= p; ++j) {
      const int i = s - p + j;
      const Quad den1 = Quad(U[i + d]) - Quad(U[i]);
      const Quad den2 = Quad(U[i + d + 1]) - Quad(U[i + 1]);
      for (int k = 0; k <= 2 && k <= d; ++k) {
        Quad a = 0, b = 0;
        if (k == 0) {
          if (den1 > 0) a = (x - Quad(U[i])) / den1 * D[0][d - 1][j];
          if (den2 > 0) b = (Quad(U[i + d + 1]) - x) / den2 * D[0][d - 1][j + 1];
          D[0][d][j] = a + b;
        } else {
          if (den1 > 0) a = D[k - 1][d - 1][j] / den1;
          if (den2 > 0) b = D[k - 1][d - 1][j + 1] / den2;
          D[k][d][j] = Quad(d) * (a - b);
        }
      }
    }
  }
  std::vector<std::array<Quad, 3>> r(p + 1);
  for (int j = 0; j <= p; ++j)
    for (int k = 0; k < 3; ++k) r[j][k] = D[k][p][j];
  return r;
}

/// Point and derivatives of a surface in the order p, du, dv, duu, duv, dvv.
inline std::array<Vec3, 6> reference_surface(const NurbsSurfaceData& d, double u, double v) {
  const int su = reference_span(d.knots_u, d.degree_u, d.count_u - 1, u);
  const int sv = reference_span(d.knots_v, d.degree_v, d.count_v - 1, v);
  const auto Nu = reference_basis(d.knots_u, d.degree_u, su, u);
  const auto Nv = reference_basis(d.knots_v, d.degree_v, sv, v);
  // A[c][k]: homogeneous derivative c (as above) of (w x, w y, w z, w).
  constexpr int kOrder[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
  Quad A[6][4];
  for (auto& row : A)
    for (auto& x : row) x = 0;
  for (int i = 0; i <= d.degree_u; ++i)
    for (int j = 0; j <= d.degree_v; ++j) {
      const int pi = su - d.degree_u + i, pj = sv - d.degree_v + j;
      const Quad w(d.weight(pi, pj));
      const Vec3& P = d.pole(pi, pj);
      const Quad h[4] = {w * Quad(P.x()), w * Quad(P.y()), w * Quad(P.z()), w};
      for (int c = 0; c < 6; ++c) {
        const Quad b = Nu[i][kOrder[c][0]] * Nv[j][kOrder[c][1]];
        for (int k = 0; k < 4; ++k) A[c][k] += b * h[k];
      }
    }
  std::array<Vec3, 6> r;
  for (int k = 0; k < 3; ++k) {
    const Quad& w = A[0][3];
    const Quad p = A[0][k] / w;
    const Quad pu = (A[1][k] - A[1][3] * p) / w;
    const Quad pv = (A[2][k] - A[2][3] * p) / w;
    const Quad puu = (A[3][k] - 2 * A[1][3] * pu - A[3][3] * p) / w;
    const Quad puv = (A[4][k] - A[1][3] * pv - A[2][3] * pu - A[4][3] * p) / w;
    const Quad pvv = (A[5][k] - 2 * A[2][3] * pv - A[5][3] * p) / w;
    const Quad all[6] = {p, pu, pv, puu, puv, pvv};
    for (int c = 0; c < 6; ++c) r[c][k] = static_cast<double>(all[c]);
  }
  return r;
}

/// Point, first and second derivative of a curve.
template <int Dim>
std::array<Eigen::Matrix<double, Dim, 1>, 3> reference_curve(const NurbsCurveData<Dim>& d,
                                                             double t) {
  const int n = static_cast<int>(d.poles.size());
  const int s = reference_span(d.knots, d.degree, n - 1, t);
  const auto N = reference_basis(d.knots, d.degree, s, t);
  Quad A[3][Dim + 1];
  for (auto& row : A)
    for (auto& x : row) x = 0;
  for (int j = 0; j <= d.degree; ++j) {
    const int pj = s - d.degree + j;
    const Quad w(d.weights.empty() ? 1.0 : d.weights[pj]);
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < Dim; ++c) A[k][c] += N[j][k] * w * Quad(d.poles[pj][c]);
      A[k][Dim] += N[j][k] * w;
    }
  }
  std::array<Eigen::Matrix<double, Dim, 1>, 3> r;
  for (int c = 0; c < Dim; ++c) {
    const Quad& w = A[0][Dim];
    const Quad p = A[0][c] / w;
    const Quad p1 = (A[1][c] - A[1][Dim] * p) / w;
    const Quad p2 = (A[2][c] - 2 * A[1][Dim] * p1 - A[2][Dim] * p) / w;
    r[0][c] = static_cast<double>(p);
    r[1][c] = static_cast<double>(p1);
    r[2][c] = static_cast<double>(p2);
  }
  return r;
}

}  // namespace plyfit::test
