#include <plyfit/kernel/nurbs.hpp>

#include "geometry/bspline_basis.hpp"
#include "geometry/knot_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace plyfit {

template <int Dim>
Result<NurbsCurve<Dim>> NurbsCurve<Dim>::create(NurbsCurveData<Dim> data) {
  const int n = static_cast<int>(data.poles.size());
  if (auto s = detail::check_knots(data.knots, n, data.degree, "curve"); !s) return s.error();
  if (!data.weights.empty() && data.weights.size() != data.poles.size())
    return Error{ErrorCode::kCurveWeightCount,
                 {},
                 {static_cast<std::int64_t>(data.weights.size()), std::int64_t{n}}};
  NurbsCurve c;
  c.hpoles_.resize(static_cast<size_t>(n) * (Dim + 1));
  for (int k = 0; k < n; ++k) {
    if (!data.poles[k].allFinite())
      return Error{ErrorCode::kCurvePoleNotFinite, {}, {std::int64_t{k}}};
    const double w = data.weights.empty() ? 1.0 : data.weights[k];
    if (!(w > 0.0 && std::isfinite(w)))
      return Error{ErrorCode::kCurveWeightNotPositive, {}, {std::int64_t{k}}};
    for (int d = 0; d < Dim; ++d) c.hpoles_[k * (Dim + 1) + d] = data.poles[k][d];
    c.hpoles_[k * (Dim + 1) + Dim] = w;
  }
  c.t0_ = data.knots[data.degree];
  c.t1_ = data.knots[n];
  detail::span_range(data.knots.data(), n - 1, data.degree, c.first_span_, c.last_span_);
  c.data_ = std::move(data);
  return c;
}

template <int Dim>
CurveEval<Dim> NurbsCurve<Dim>::eval2(double t) const {
  const int p = data_.degree;
  const double* U = data_.knots.data();
  const int s = detail::find_span(U, first_span_, last_span_, t);
  double N[3][detail::kMaxBasis];
  detail::ders_basis<2>(U, s, p, t, N);
  // Homogeneous sums of (w (P - O), w) relative to the first pole O of the span, so that
  // rounding stays proportional to the curve's size, not to its distance from the origin.
  const double* O = &hpoles_[static_cast<size_t>(s - p) * (Dim + 1)];
  double h[3][Dim + 1] = {};
  for (int j = 0; j <= p; ++j) {
    const double* P = &hpoles_[static_cast<size_t>(s - p + j) * (Dim + 1)];
    double H[Dim + 1];
    for (int d = 0; d < Dim; ++d) H[d] = P[Dim] * (P[d] - O[d]);
    H[Dim] = P[Dim];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d <= Dim; ++d) h[k][d] += N[k][j] * H[d];
  }
  CurveEval<Dim> r;
  Point A0, A1, A2;
  for (int d = 0; d < Dim; ++d) {
    A0[d] = h[0][d];
    A1[d] = h[1][d];
    A2[d] = h[2][d];
  }
  const double w = h[0][Dim];
  if (!(w > 0.0)) {
    r.p = r.d1 = r.d2 = Point::Zero();
    r.ok = false;
    return r;
  }
  const Point rel = A0 / w;
  r.d1 = (A1 - h[1][Dim] * rel) / w;
  r.d2 = (A2 - 2.0 * h[1][Dim] * r.d1 - h[2][Dim] * rel) / w;
  for (int d = 0; d < Dim; ++d) r.p[d] = rel[d] + O[d];
  return r;
}

template <int Dim>
typename NurbsCurve<Dim>::Point NurbsCurve<Dim>::point(double t) const {
  return eval2(t).p;
}

template <int Dim>
std::vector<typename NurbsCurve<Dim>::Point> NurbsCurve<Dim>::tessellate(double chord_tol) const {
  std::vector<Point> out;
  const std::vector<double> breaks = detail::breakpoints(data_.knots, t0_, t1_);
  const int kMaxDepth = 16;  // at most 2^16 chords per knot span
  struct Seg {
    double a, b;
    Point pa, pb;
    int depth;
  };
  out.push_back(point(breaks.front()));
  std::vector<Seg> stack;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    // Start every span with at least 2 * degree chords so that inflections are seen.
    const int n0 = 2 * data_.degree;
    for (int k = n0 - 1; k >= 0; --k) {
      const double a = breaks[i] + (breaks[i + 1] - breaks[i]) * k / n0;
      const double b = breaks[i] + (breaks[i + 1] - breaks[i]) * (k + 1) / n0;
      stack.push_back({a, b, point(a), point(b), 0});
    }
    while (!stack.empty()) {
      Seg s = stack.back();
      stack.pop_back();
      const double m = 0.5 * (s.a + s.b);
      const Point pm = point(m);
      const Point chord_mid = 0.5 * (s.pa + s.pb);
      if ((pm - chord_mid).norm() > chord_tol && s.depth < kMaxDepth) {
        stack.push_back({m, s.b, pm, s.pb, s.depth + 1});
        stack.push_back({s.a, m, s.pa, pm, s.depth + 1});
      } else {
        out.push_back(s.pb);
      }
    }
  }
  return out;
}

template class NurbsCurve<2>;
template class NurbsCurve<3>;

namespace {

std::vector<double> chord_params(const std::vector<Vec3>& pts, Status& st) {
  std::vector<double> t(pts.size(), 0.0);
  double total = 0.0;
  for (size_t i = 1; i < pts.size(); ++i) {
    const double d = (pts[i] - pts[i - 1]).norm();
    if (!(d > 0.0)) {
      st = Error{ErrorCode::kInterpolationPointsCoincide,
                 {},
                 {static_cast<std::int64_t>(i) - 1, static_cast<std::int64_t>(i)}};
      return t;
    }
    total += d;
    t[i] = total;
  }
  for (auto& x : t) x /= total;
  t.back() = 1.0;
  return t;
}

}  // namespace

Result<NurbsCurve3> polyline_curve(const std::vector<Vec3>& points) {
  if (points.size() < 2) return Error{ErrorCode::kPolylineTooFewPoints};
  Status st = ok_status();
  const auto t = chord_params(points, st);
  if (!st) return st.error();
  NurbsCurveData3 d;
  d.degree = 1;
  d.poles = points;
  d.knots.push_back(0.0);
  for (double x : t) d.knots.push_back(x);
  d.knots.push_back(1.0);
  return NurbsCurve3::create(std::move(d));
}

Result<NurbsCurve3> interpolate_cubic(const std::vector<Vec3>& points) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return Error{ErrorCode::kInterpolationTooFewPoints};
  if (n == 2) return polyline_curve(points);
  const int p = std::min(3, n - 1);
  Status st = ok_status();
  const auto t = chord_params(points, st);
  if (!st) return st.error();
  NurbsCurveData3 d;
  d.degree = p;
  d.knots.assign(p + 1, 0.0);
  for (int j = 1; j <= n - 1 - p; ++j) {  // knot averaging (eq. 9.8)
    double s = 0.0;
    for (int i = j; i < j + p; ++i) s += t[i];
    d.knots.push_back(s / p);
  }
  d.knots.insert(d.knots.end(), p + 1, 1.0);
  // Collocation matrix: row k has non-zeros in columns span-p .. span. Banded, totally
  // positive, so Gaussian elimination without pivoting is stable (de Boor).
  const int bw = p;  // half bandwidth
  std::vector<double> A(static_cast<size_t>(n) * (2 * bw + 1), 0.0);
  auto at = [&](int r, int c) -> double& {
    return A[static_cast<size_t>(r) * (2 * bw + 1) + (c - r + bw)];
  };
  int first = 0, last = 0;
  detail::span_range(d.knots.data(), n - 1, p, first, last);
  for (int k = 0; k < n; ++k) {
    const int s = detail::find_span(d.knots.data(), first, last, t[k]);
    double N[1][detail::kMaxBasis];
    detail::ders_basis<0>(d.knots.data(), s, p, t[k], N);
    for (int j = 0; j <= p; ++j) {
      const int c = s - p + j;
      if (std::abs(c - k) > bw) {
        if (N[0][j] != 0.0)
          return Error{ErrorCode::kInternal, {}, {"the interpolation matrix is not banded"}};
        continue;
      }
      at(k, c) = N[0][j];
    }
  }
  std::vector<Vec3> rhs = points;
  for (int k = 0; k < n; ++k) {
    const double piv = at(k, k);
    if (!(std::abs(piv) > 0.0)) return Error{ErrorCode::kInterpolationSingular};
    for (int r = k + 1; r <= std::min(n - 1, k + bw); ++r) {
      const double f = at(r, k) / piv;
      if (f == 0.0) continue;
      for (int c = k; c <= std::min(n - 1, k + bw); ++c) at(r, c) -= f * at(k, c);
      rhs[r] -= f * rhs[k];
    }
  }
  d.poles.assign(n, Vec3::Zero());
  for (int k = n - 1; k >= 0; --k) {
    Vec3 s = rhs[k];
    for (int c = k + 1; c <= std::min(n - 1, k + bw); ++c) s -= at(k, c) * d.poles[c];
    d.poles[k] = s / at(k, k);
  }
  return NurbsCurve3::create(std::move(d));
}

}  // namespace plyfit
