#pragma once
// B-spline basis functions and their derivatives (Piegl & Tiller, The NURBS Book, A2.1-A2.3),
// on fixed-size stack arrays so that evaluation never allocates.

#include <algorithm>
#include <vector>

namespace plyfit::detail {

/// Highest degree the kernel accepts (OpenCASCADE's limit).
constexpr int kMaxDegree = 25;
constexpr int kMaxBasis = kMaxDegree + 1;

/// The distinct knot values in [a, b] (a sorted knot vector's breakpoints there): the ends of
/// the polynomial pieces of a curve or surface over its domain.
inline std::vector<double> breakpoints(const std::vector<double>& knots, double a, double b) {
  std::vector<double> out;
  for (double k : knots)
    if (k >= a && k <= b && (out.empty() || k > out.back())) out.push_back(k);
  return out;
}

/// Span index s in [first, last] with U[s] <= u < U[s+1]; parameters outside the domain get
/// the first or last non-degenerate span, so evaluation there extends the end polynomials.
/// `first_span`/`last_span` are the first and last spans of positive length.
inline int find_span(const double* U, int first_span, int last_span, double u) {
  if (u >= U[last_span]) return last_span;
  if (u < U[first_span + 1]) return first_span;
  // Now U[first_span] <= u < U[last_span]: the span is the largest s in [first_span,
  // last_span] with U[s] <= u. Branch-free bisection (the comparison becomes a conditional
  // move): random parameters would mispredict about half of the branches of a plain one.
  const double* base = U + first_span;
  int len = last_span - first_span + 1;
  while (len > 1) {
    const int half = len / 2;
    base = (base[half] <= u) ? base + half : base;
    len -= half;
  }
  return static_cast<int>(base - U);
}

// GCC 12 cannot see that the column index of `a` below stays <= k - 1 < ND + 1 and warns
// about reading the (zero-initialised) array; the bound is the algorithm's (A2.3).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
/// ders[k][j], k = 0..nd, j = 0..p: the k-th derivative of the non-zero basis functions
/// N_{span-p+j, p} at u (A2.3). nd <= 2. With P > 0 the degree is the compile-time P (`p` is
/// then ignored) and every loop has a fixed trip count; the arithmetic is the same, operation
/// for operation, so the results are bit-for-bit those of the run-time degree.
template <int ND, int P = 0>
inline void ders_basis(const double* U, int span, int p_runtime, double u,
                       double ders[ND + 1][kMaxBasis]) {
  const int p = (P > 0) ? P : p_runtime;
  constexpr int M = (P > 0) ? P + 1 : kMaxBasis;
  double left[M], right[M];
  double ndu[M][M];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // knot differences (lower triangle)
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  if constexpr (ND == 1) {
    // A2.3 for the first derivative only: ders[1][r] = p (N_{r-1,p-1} / d_{r-1} -
    // N_{r,p-1} / d_r) with d_r = ndu[p][r], each reciprocal 1 / d_r computed once instead of
    // twice (A2.3 forms it as a[.][0] for r + 1 and as -a[.][1] for r: the same bits).
    double inv[M];
    for (int r = 0; r < p; ++r) inv[r] = 1.0 / ndu[p][r];
    const double f = p;
    for (int r = 0; r <= p; ++r) {
      double d = (r >= 1) ? inv[r - 1] * ndu[r - 1][p - 1] : 0.0;
      if (r <= p - 1) d -= inv[r] * ndu[r][p - 1];
      ders[1][r] = d * f;
    }
  } else if constexpr (ND > 1) {
    const int nd = std::min(ND, p);
    for (int k = nd + 1; k <= ND; ++k)
      for (int j = 0; j <= p; ++j) ders[k][j] = 0.0;
    double a[2][ND + 1] = {};  // columns 0..k, k <= ND
    for (int r = 0; r <= p; ++r) {
      int s1 = 0, s2 = 1;
      a[0][0] = 1.0;
      for (int k = 1; k <= nd; ++k) {
        double d = 0.0;
        const int rk = r - k, pk = p - k;
        if (r >= k) {
          a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
          d = a[s2][0] * ndu[rk][pk];
        }
        const int j1 = (rk >= -1) ? 1 : -rk;
        const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
        for (int j = j1; j <= j2; ++j) {
          a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
          d += a[s2][j] * ndu[rk + j][pk];
        }
        if (r <= pk) {
          a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
          d += a[s2][k] * ndu[r][pk];
        }
        ders[k][r] = d;
        std::swap(s1, s2);
      }
    }
    double f = p;
    for (int k = 1; k <= nd; ++k) {
      for (int j = 0; j <= p; ++j) ders[k][j] *= f;
      f *= (p - k);
    }
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

/// First and last spans of positive length in [p, n] (n = number of poles - 1).
inline void span_range(const double* U, int n, int p, int& first, int& last) {
  first = p;
  while (first < n && !(U[first] < U[first + 1])) ++first;
  last = n;
  while (last > p && !(U[last] < U[last + 1])) --last;
}

}  // namespace plyfit::detail
