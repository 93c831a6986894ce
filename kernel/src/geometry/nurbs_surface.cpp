#include <plyfit/kernel/nurbs.hpp>

#include "geometry/bspline_basis.hpp"
#include "geometry/knot_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace plyfit {

Result<NurbsSurface> NurbsSurface::create(NurbsSurfaceData data, const Tolerances& tol) {
  if (auto s = detail::check_knots(data.knots_u, data.count_u, data.degree_u, "u"); !s)
    return s.error();
  if (auto s = detail::check_knots(data.knots_v, data.count_v, data.degree_v, "v"); !s)
    return s.error();
  const size_t n = static_cast<size_t>(data.count_u) * data.count_v;
  if (data.poles.size() != n)
    return Error{ErrorCode::kPoleCount,
                 {},
                 {static_cast<std::int64_t>(data.poles.size()), std::int64_t{data.count_u},
                  std::int64_t{data.count_v}}};
  if (!data.weights.empty() && data.weights.size() != n)
    return Error{ErrorCode::kWeightCount,
                 {},
                 {static_cast<std::int64_t>(data.weights.size()), static_cast<std::int64_t>(n)}};
  for (size_t k = 0; k < n; ++k) {
    const auto at = static_cast<std::int64_t>(k);
    if (!data.poles[k].allFinite()) return Error{ErrorCode::kPoleNotFinite, {}, {at}};
    if (!data.weights.empty() && !(data.weights[k] > 0.0 && std::isfinite(data.weights[k])))
      return Error{ErrorCode::kWeightNotPositive, {}, {at}};
  }

  NurbsSurface s;
  s.data_ = std::move(data);
  const auto& d = s.data_;
  s.hpoles_.resize(4 * n);
  s.min_weight_ = 1.0;
  for (size_t k = 0; k < n; ++k) {
    const double w = d.weights.empty() ? 1.0 : d.weights[k];
    s.min_weight_ = (k == 0) ? w : std::min(s.min_weight_, w);
    s.hpoles_[4 * k + 0] = d.poles[k].x();
    s.hpoles_[4 * k + 1] = d.poles[k].y();
    s.hpoles_[4 * k + 2] = d.poles[k].z();
    s.hpoles_[4 * k + 3] = w;
    s.bbox_.add(d.poles[k]);
  }
  s.domain_ = {d.knots_u[d.degree_u], d.knots_u[d.count_u], d.knots_v[d.degree_v],
               d.knots_v[d.count_v]};
  detail::span_range(d.knots_u.data(), d.count_u - 1, d.degree_u, s.first_span_u_, s.last_span_u_);
  detail::span_range(d.knots_v.data(), d.count_v - 1, d.degree_v, s.first_span_v_, s.last_span_v_);
  const double size = std::max(s.bbox_.diagonal(), 1e-300);
  s.speed_u_ = size / s.domain_.width_u();
  s.speed_v_ = size / s.domain_.width_v();
  s.degenerate_rel_ = tol.degenerate_rel;
  s.min_weight_rel_ = tol.extension_min_weight_rel;
  s.min_weight_ *= tol.extension_min_weight_rel;
  s.build_bezier();
  s.rounding_ = s.estimate_rounding();
  return s;
}

namespace {

// Parameters where the surface's speeds are sampled for rounding(): the distinct knots of the
// domain and their spans' middles, at most kRoundingSamples (evenly picked among them), and
// the margin on the largest speed sampled (peaks between samples).
constexpr int kRoundingSamples = 33;
constexpr double kSpeedSampleMargin = 2.0;

std::vector<double> rounding_samples(const std::vector<double>& knots, double lo, double hi) {
  std::vector<double> t;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    if (knots[k] < lo || knots[k + 1] > hi || !(knots[k] < knots[k + 1])) continue;
    if (t.empty()) t.push_back(knots[k]);
    t.push_back(0.5 * (knots[k] + knots[k + 1]));
    t.push_back(knots[k + 1]);
  }
  if (t.size() <= static_cast<std::size_t>(kRoundingSamples)) return t;
  std::vector<double> picked;
  for (int k = 0; k < kRoundingSamples; ++k)
    picked.push_back(t[(t.size() - 1) * static_cast<std::size_t>(k) / (kRoundingSamples - 1)]);
  return picked;
}

}  // namespace

double NurbsSurface::estimate_rounding() const {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const auto& d = data_;
  // The parameters' spacing in 3D, |u| |Su| + |v| |Sv|, taken where it is largest.
  double lattice = 0.0;
  for (const double u : rounding_samples(d.knots_u, domain_.u0, domain_.u1))
    for (const double v : rounding_samples(d.knots_v, domain_.v0, domain_.v1)) {
      const SurfaceEval1 e = eval1(u, v);
      if (e.ok) lattice = std::max(lattice, std::abs(u) * e.du.norm() + std::abs(v) * e.dv.norm());
    }
  // The sums: every term w N (P - origin) is rounded to a few ulps of its size, and their sum
  // over the denominator's (all weights and basis values positive) is a mean of |P - origin|,
  // at most the control net's extent.
  const double sums = (d.degree_u + d.degree_v) * bbox_.diagonal();
  return kEps * (sums + kSpeedSampleMargin * lattice);
}

namespace {

// What evaluation needs of a surface, so that the fixed-degree kernels below can be free
// function templates.
struct EvalView {
  const double* U;
  const double* V;
  const double* poles;  // (x, y, z, w), stride 4
  int p, q, count_v;
  int first_u, last_u, first_v, last_v;
  const double* bezier;  // Bezier table (NurbsSurface::bezier_), or nullptr
  const double* bu;      // per u span: first knot, 1 / width
  const double* bv;
  int bezier_spans_v;
};

// Largest Bezier table a surface builds (bytes); larger surfaces sum the B-spline basis.
constexpr std::size_t kBezierMaxBytes = std::size_t{32} << 20;

// The degree pairs (p, q) with fixed-degree kernels, as keys kKeyBase p + q: the degrees CAD
// surfaces mostly have (planes, ruled and extruded surfaces, quadrics and tori, bicubic and
// biquintic free forms).
constexpr int kKeyBase = 32;
constexpr int degree_key(int p, int q) {
  return p * kKeyBase + q;
}
using FixedDegrees =
    std::integer_sequence<int, degree_key(1, 1), degree_key(1, 2), degree_key(1, 3),
                          degree_key(2, 1), degree_key(2, 2), degree_key(2, 3), degree_key(3, 1),
                          degree_key(3, 2), degree_key(3, 3), degree_key(4, 4), degree_key(5, 5)>;

template <int... Keys>
constexpr bool has_key(std::integer_sequence<int, Keys...>, int key) {
  return ((key == Keys) || ...);
}

// True for the degrees with fixed-degree kernels (see eval_homogeneous).
bool fixed_degrees(int p, int q) {
  return has_key(FixedDegrees{}, degree_key(p, q));
}

// Bezier extraction of span s (U[s] < U[s + 1]) of a degree-p knot vector: M[k][m] with
// N_{s-p+k}(u) = sum_m M[k][m] B_{m,p}(t), t = (u - U[s]) / (U[s + 1] - U[s]). Column m is
// the blossom f(U[s] x (p - m), U[s + 1] x m) of each basis function, by de Boor's algorithm
// with those arguments (convex combinations: the entries lie in [0, 1]).
void extraction(const double* U, int s, int p, double M[detail::kMaxBasis][detail::kMaxBasis]) {
  for (int m = 0; m <= p; ++m) {
    double d[detail::kMaxBasis][detail::kMaxBasis];  // d[i][k]: point i as a combination of k
    for (int i = 0; i <= p; ++i)
      for (int k = 0; k <= p; ++k) d[i][k] = (i == k) ? 1.0 : 0.0;
    for (int r = 1; r <= p; ++r) {
      const double t = (r <= p - m) ? U[s] : U[s + 1];
      for (int i = p; i >= r; --i) {
        const int g = s - p + i;
        const double alpha = (t - U[g]) / (U[g + p + 1 - r] - U[g]);
        for (int k = 0; k <= p; ++k) d[i][k] = (1.0 - alpha) * d[i - 1][k] + alpha * d[i][k];
      }
    }
    for (int k = 0; k <= p; ++k) M[k][m] = d[p][k];
  }
}

// Bernstein basis of degree P at t and its derivatives up to ND with respect to u (inv_h =
// 1 / span width): N[l][m] = d^l B_{m,P} / du^l.
template <int ND, int P>
[[gnu::always_inline]] inline void bernstein(double t, double inv_h,
                                             double N[ND + 1][detail::kMaxBasis]) {
  double B[P + 1][P + 1];  // B[j][m] = B_{m,j}(t), j <= P (de Casteljau's triangle)
  const double s = 1.0 - t;
  B[0][0] = 1.0;
  for (int j = 1; j <= P; ++j) {
    B[j][0] = s * B[j - 1][0];
    for (int m = 1; m < j; ++m) B[j][m] = s * B[j - 1][m] + t * B[j - 1][m - 1];
    B[j][j] = t * B[j - 1][j - 1];
  }
  for (int m = 0; m <= P; ++m) N[0][m] = B[P][m];
  if constexpr (ND >= 1) {
    const double f = P * inv_h;
    for (int m = 0; m <= P; ++m)
      N[1][m] = f * ((m >= 1 ? B[P - 1][m - 1] : 0.0) - (m < P ? B[P - 1][m] : 0.0));
  }
  if constexpr (ND >= 2) {
    if constexpr (P < 2) {
      for (int m = 0; m <= P; ++m) N[2][m] = 0.0;
    } else {
      const double f = P * (P - 1) * inv_h * inv_h;
      for (int m = 0; m <= P; ++m)
        N[2][m] = f * ((m >= 2 ? B[P - 2][m - 2] : 0.0) -
                       2.0 * (m >= 1 && m - 1 <= P - 2 ? B[P - 2][m - 1] : 0.0) +
                       (m <= P - 2 ? B[P - 2][m] : 0.0));
    }
  }
}

using A4 = Eigen::Array4d;

// The sums along v of a span pair's Bezier poles (patch: its Bezier table entry) with the
// v basis Nv: T[i][l] = sum_j Nv[l][j] H(i, j) for each row i of poles along u. Four-wide sums
// (Eigen packets: two SSE2 operations each), component by component the same arithmetic as
// scalar loops.
template <int ND, int P, int Q>
[[gnu::always_inline]] inline void bezier_columns(const double* patch,
                                                  const double Nv[ND + 1][detail::kMaxBasis],
                                                  A4 T[P + 1][ND + 1]) {
  for (int i = 0; i <= P; ++i) {
    for (int l = 0; l <= ND; ++l) T[i][l].setZero();
    const double* row = patch + 4 + 4 * (Q + 1) * i;
    for (int j = 0; j <= Q; ++j) {
      const A4 H = Eigen::Map<const A4>(row + 4 * j);
      for (int l = 0; l <= ND; ++l) T[i][l] += Nv[l][j] * H;
    }
  }
}

// The homogeneous sums from the sums along v (bezier_columns) and the u basis Nu.
template <int ND, bool Rational, int P>
[[gnu::always_inline]] inline void bezier_combine(const double Nu[ND + 1][detail::kMaxBasis],
                                                  const A4 T[P + 1][ND + 1], double out[][4]) {
  constexpr int NC = (ND + 1) * (ND + 2) / 2;
  A4 acc[NC];
  for (int c = 0; c < NC; ++c) acc[c].setZero();
  for (int i = 0; i <= P; ++i) {
    const double a0 = Nu[0][i];
    acc[0] += a0 * T[i][0];
    if constexpr (ND >= 1) {
      acc[1] += Nu[1][i] * T[i][0];
      acc[2] += a0 * T[i][1];
    }
    if constexpr (ND >= 2) {
      acc[3] += Nu[2][i] * T[i][0];
      acc[4] += Nu[1][i] * T[i][1];
      acc[5] += a0 * T[i][2];
    }
  }
  for (int c = 0; c < NC; ++c)
    for (int k = 0; k < 4; ++k) out[c][k] = acc[c][k];
  if constexpr (!Rational) {
    for (int c = 0; c < NC; ++c) out[c][3] = (c == 0) ? 1.0 : 0.0;
  }
}

// The Bezier table entry of span pair (iu, iv) (positions from the first spans).
template <int P, int Q>
const double* bezier_patch(const EvalView& s, int iu, int iv) {
  constexpr std::size_t kStride = 4 + 4 * (P + 1) * (Q + 1);
  return s.bezier + kStride * (static_cast<std::size_t>(iu) * s.bezier_spans_v + iv);
}

// The fixed-degree kernel on the Bezier table: the same sums as eval_fixed's, over the span
// pair's Bezier poles (already relative to the origin and weighted) with Bernstein bases.
template <int ND, bool Rational, int P, int Q>
void eval_bezier(const EvalView& s, double u, double v, double out[][4], double origin[3]) {
  const int iu = detail::find_span(s.U, s.first_u, s.last_u, u) - s.first_u;
  const int iv = detail::find_span(s.V, s.first_v, s.last_v, v) - s.first_v;
  double Nu[ND + 1][detail::kMaxBasis], Nv[ND + 1][detail::kMaxBasis];
  bernstein<ND, P>((u - s.bu[2 * iu]) * s.bu[2 * iu + 1], s.bu[2 * iu + 1], Nu);
  bernstein<ND, Q>((v - s.bv[2 * iv]) * s.bv[2 * iv + 1], s.bv[2 * iv + 1], Nv);
  const double* patch = bezier_patch<P, Q>(s, iu, iv);
  origin[0] = patch[0];
  origin[1] = patch[1];
  origin[2] = patch[2];
  A4 T[P + 1][ND + 1];
  bezier_columns<ND, P, Q>(patch, Nv, T);
  bezier_combine<ND, Rational, P>(Nu, T, out);
}

// One row i of eval_fixed's sums: T[l] = sum_j Nv[l][j] * H(i, sv - q + j) over the window
// row `row` (its q + 1 poles), H = (w (P - o), w) with o the window's origin. All four
// homogeneous components are summed even for a non-rational surface (whose fourth is then
// unused): four-wide loops vectorise, and x, y, z are the same sums.
template <int ND, bool Rational, int Q>
[[gnu::always_inline]] inline void window_row(const double* row, int q, const double* o,
                                              const double Nv[ND + 1][detail::kMaxBasis],
                                              double T[ND + 1][4]) {
  constexpr int W = 4;
  const double ox = o[0], oy = o[1], oz = o[2];
  for (int l = 0; l <= ND; ++l)
    for (int k = 0; k < W; ++k) T[l][k] = 0.0;
  for (int j = 0; j <= ((Q > 0) ? Q : q); ++j) {
    const double* Pij = row + 4 * j;
    double H[4] = {Pij[0] - ox, Pij[1] - oy, Pij[2] - oz, 1.0};
    if constexpr (Rational) {
      const double w = Pij[3];
      H[0] *= w;
      H[1] *= w;
      H[2] *= w;
      H[3] = w;
    }
    for (int l = 0; l <= ND; ++l) {
      const double b = Nv[l][j];
      for (int k = 0; k < W; ++k) T[l][k] += b * H[k];
    }
  }
}

// Adds row i's share, Nu[.][i] times its sums T (window_row), to the sums acc.
template <int ND>
[[gnu::always_inline]] inline void window_add(const double Nu[ND + 1][detail::kMaxBasis], int i,
                                              const double T[ND + 1][4], double acc[][4]) {
  const double a0 = Nu[0][i];
  for (int k = 0; k < 4; ++k) {
    acc[0][k] += a0 * T[0][k];
    if constexpr (ND >= 1) {
      acc[1][k] += Nu[1][i] * T[0][k];
      acc[2][k] += a0 * T[1][k];
    }
    if constexpr (ND >= 2) {
      acc[3][k] += Nu[2][i] * T[0][k];
      acc[4][k] += Nu[1][i] * T[1][k];
      acc[5][k] += a0 * T[2][k];
    }
  }
}

// Copies the sums to out (the weight and its derivatives 1, 0 for a non-rational surface).
template <int ND, bool Rational>
[[gnu::always_inline]] inline void window_out(const double acc[][4], double out[][4]) {
  constexpr int NC = (ND + 1) * (ND + 2) / 2;
  for (int c = 0; c < NC; ++c)
    for (int k = 0; k < 4; ++k) out[c][k] = acc[c][k];
  if constexpr (!Rational) {
    for (int c = 0; c < NC; ++c) out[c][3] = (c == 0) ? 1.0 : 0.0;
  }
}

// The first pole of span pair (su, sv)'s window: the origin of its sums.
inline const double* window_origin(const EvalView& s, int su, int sv, int p, int q) {
  return s.poles + 4 * (static_cast<size_t>(su - p) * s.count_v + (sv - q));
}

// out[c] = homogeneous derivative combination c: 0 S, 1 Su, 2 Sv, (ND=2) 3 Suu, 4 Suv, 5 Svv,
// of the surface translated by -origin, where origin is the first pole of the span's
// (p + 1) x (q + 1) window. Evaluating relative to a nearby pole keeps the rounding errors
// proportional to the size of the patch rather than to its distance from the model origin
// (derivatives are translation invariant, the point is origin + the relative point).
// P, Q > 0 fix the degrees at compile time (fully unrolled loops, the same arithmetic in the
// same order as the run-time degrees, hence the same bits); 0 means "run-time degree".
template <int ND, bool Rational, int P, int Q>
void eval_fixed(const EvalView& s, double u, double v, double out[][4], double origin[3]) {
  if constexpr (P > 0 && Q > 0) {
    if (s.bezier) return eval_bezier<ND, Rational, P, Q>(s, u, v, out, origin);
  }
  const int p = (P > 0) ? P : s.p, q = (Q > 0) ? Q : s.q;
  const int su = detail::find_span(s.U, s.first_u, s.last_u, u);
  const int sv = detail::find_span(s.V, s.first_v, s.last_v, v);
  double Nu[ND + 1][detail::kMaxBasis], Nv[ND + 1][detail::kMaxBasis];
  detail::ders_basis<ND, P>(s.U, su, p, u, Nu);
  detail::ders_basis<ND, Q>(s.V, sv, q, v, Nv);
  constexpr int NC = (ND + 1) * (ND + 2) / 2;
  // Sums in a local array (kept in registers: `out` may alias the poles for the compiler),
  // copied out at the end (docs/decisions/nurbs-evaluation.md).
  double acc[NC][4] = {};
  const double* o = window_origin(s, su, sv, p, q);
  origin[0] = o[0];
  origin[1] = o[1];
  origin[2] = o[2];
  for (int i = 0; i <= p; ++i) {
    double T[ND + 1][4];
    window_row<ND, Rational, Q>(o + 4 * static_cast<size_t>(i) * s.count_v, q, o, Nv, T);
    window_add<ND>(Nu, i, T, acc);
  }
  window_out<ND, Rational>(acc, out);
}

// The kernels by degree key: the fixed-degree one of each key of FixedDegrees, the run-time
// degree one for every other key up to the largest (a jump table, as a switch would be).
template <int ND, bool Rational>
using Kernel = void (*)(const EvalView&, double, double, double[][4], double[3]);
template <int ND, bool Rational, int... Keys>
constexpr auto kernel_table(std::integer_sequence<int, Keys...>) {
  constexpr int kLast = std::max({Keys...});
  std::array<Kernel<ND, Rational>, kLast + 1> table{};
  for (auto& k : table) k = &eval_fixed<ND, Rational, 0, 0>;
  ((table[Keys] = &eval_fixed<ND, Rational, Keys / kKeyBase, Keys % kKeyBase>), ...);
  return table;
}

// The kernel for the degrees (p, q).
template <int ND, bool Rational>
Kernel<ND, Rational> kernel_for(int p, int q) {
  static constexpr auto kTable = kernel_table<ND, Rational>(FixedDegrees{});
  const int key = degree_key(p, q);
  return key < static_cast<int>(kTable.size()) ? kTable[static_cast<std::size_t>(key)]
                                               : &eval_fixed<ND, Rational, 0, 0>;
}

}  // namespace

template <class F>
void NurbsSurface::with_view(const F& f) const {
  const EvalView s{data_.knots_u.data(),
                   data_.knots_v.data(),
                   hpoles_.data(),
                   data_.degree_u,
                   data_.degree_v,
                   data_.count_v,
                   first_span_u_,
                   last_span_u_,
                   first_span_v_,
                   last_span_v_,
                   bezier_.empty() ? nullptr : bezier_.data(),
                   bezier_u_.data(),
                   bezier_v_.data(),
                   bezier_spans_v_};
  f(s);
}

template <int ND, bool Rational>
void NurbsSurface::eval_homogeneous(double u, double v, double out[][4], double origin[3]) const {
  with_view([&](const EvalView& s) { kernel_for<ND, Rational>(s.p, s.q)(s, u, v, out, origin); });
}

void NurbsSurface::build_bezier() {
  const int p = data_.degree_u, q = data_.degree_v;
  if (!fixed_degrees(p, q)) return;
  const int nu = last_span_u_ - first_span_u_ + 1, nv = last_span_v_ - first_span_v_ + 1;
  const std::size_t stride = 4 + 4 * static_cast<std::size_t>(p + 1) * (q + 1);
  const std::size_t size = stride * static_cast<std::size_t>(nu) * nv;
  if (size * sizeof(double) > kBezierMaxBytes) return;
  const double* U = data_.knots_u.data();
  const double* V = data_.knots_v.data();
  // Extraction matrices per span (zero-width spans are never evaluated: find_span never
  // returns one).
  using Matrix = double[detail::kMaxBasis][detail::kMaxBasis];
  std::vector<std::array<std::array<double, detail::kMaxBasis>, detail::kMaxBasis>> mu(nu), mv(nv);
  bezier_u_.assign(2 * static_cast<std::size_t>(nu), 0.0);
  bezier_v_.assign(2 * static_cast<std::size_t>(nv), 0.0);
  auto extract = [](const double* K, int s, int deg, auto& out, double* span) {
    if (!(K[s] < K[s + 1])) return;
    Matrix M;
    extraction(K, s, deg, M);
    for (int k = 0; k <= deg; ++k)
      for (int m = 0; m <= deg; ++m) out[k][m] = M[k][m];
    span[0] = K[s];
    span[1] = 1.0 / (K[s + 1] - K[s]);
  };
  for (int i = 0; i < nu; ++i) extract(U, first_span_u_ + i, p, mu[i], &bezier_u_[2 * i]);
  for (int j = 0; j < nv; ++j) extract(V, first_span_v_ + j, q, mv[j], &bezier_v_[2 * j]);
  bezier_.assign(size, 0.0);
  bezier_spans_v_ = nv;
  const int cv = data_.count_v;
  for (int i = 0; i < nu; ++i) {
    const int su = first_span_u_ + i;
    if (!(U[su] < U[su + 1])) continue;
    for (int j = 0; j < nv; ++j) {
      const int sv = first_span_v_ + j;
      if (!(V[sv] < V[sv + 1])) continue;
      double* patch = &bezier_[stride * (static_cast<std::size_t>(i) * nv + j)];
      const double* o = &hpoles_[4 * (static_cast<std::size_t>(su - p) * cv + (sv - q))];
      for (int k = 0; k < 3; ++k) patch[k] = o[k];
      // H(k, l) = (w (P - origin), w) of the window, then Bezier poles: v first, then u.
      // [k][n]: along v converted; only the window's (p + 1) x (q + 1) entries are zeroed (the
      // whole array, sized for the largest degree, is 21 kB: zeroing it cost more than the sums).
      double Hv[detail::kMaxBasis][detail::kMaxBasis][4];
      for (int k = 0; k <= p; ++k)
        for (int n = 0; n <= q; ++n)
          for (int c = 0; c < 4; ++c) Hv[k][n][c] = 0.0;
      for (int k = 0; k <= p; ++k) {
        for (int l = 0; l <= q; ++l) {
          const double* P =
              &hpoles_[4 * (static_cast<std::size_t>(su - p + k) * cv + (sv - q + l))];
          const double w = P[3];
          const double H[4] = {w * (P[0] - o[0]), w * (P[1] - o[1]), w * (P[2] - o[2]), w};
          for (int n = 0; n <= q; ++n)
            for (int c = 0; c < 4; ++c) Hv[k][n][c] += mv[j][l][n] * H[c];
        }
      }
      for (int m = 0; m <= p; ++m)
        for (int n = 0; n <= q; ++n) {
          double* B = patch + 4 + 4 * ((q + 1) * m + n);
          for (int k = 0; k <= p; ++k)
            for (int c = 0; c < 4; ++c) B[c] += mu[i][k][m] * Hv[k][n][c];
        }
    }
  }
}

namespace {
inline Vec3 xyz(const double* h) {
  return Vec3(h[0], h[1], h[2]);
}
}  // namespace

Vec3 NurbsSurface::point(double u, double v) const {
  double h[1][4], o[3];
  if (rational()) {
    eval_homogeneous<0, true>(u, v, h, o);
    if (!(h[0][3] > min_weight_)) return Vec3::Zero();
    return xyz(h[0]) / h[0][3] + xyz(o);
  }
  eval_homogeneous<0, false>(u, v, h, o);
  return xyz(h[0]) + xyz(o);
}

namespace {

// r = the point and derivatives up to order ND (1: SurfaceEval1, 2: SurfaceEval2) from the
// homogeneous sums h relative to the origin pole o; for a rational surface by the quotient rule
// on homogeneous derivatives (The NURBS Book, A4.4), not ok (zero vectors) where the weight is
// not above min_weight. (r by reference: returned by value, the 2nd-order one costs a copy.)
template <int ND, bool Rational, class Eval>
void from_homogeneous(const double h[][4], const double o[3], double min_weight, Eval& r) {
  if constexpr (!Rational) {
    r.p = xyz(h[0]) + xyz(o);
    r.du = xyz(h[1]);
    r.dv = xyz(h[2]);
    if constexpr (ND >= 2) {
      r.duu = xyz(h[3]);
      r.duv = xyz(h[4]);
      r.dvv = xyz(h[5]);
    }
    return;
  }
  const double w = h[0][3];
  if (!(w > min_weight)) {
    r.p = r.du = r.dv = Vec3::Zero();
    if constexpr (ND >= 2) r.duu = r.duv = r.dvv = Vec3::Zero();
    r.ok = false;
    return;
  }
  const double iw = 1.0 / w;
  const double wu = h[1][3], wv = h[2][3];
  const Vec3 p = xyz(h[0]) * iw;
  r.du = (xyz(h[1]) - wu * p) * iw;
  r.dv = (xyz(h[2]) - wv * p) * iw;
  if constexpr (ND >= 2) {
    const double wuu = h[3][3], wuv = h[4][3], wvv = h[5][3];
    r.duu = (xyz(h[3]) - 2.0 * wu * r.du - wuu * p) * iw;
    r.duv = (xyz(h[4]) - wu * r.dv - wv * r.du - wuv * p) * iw;
    r.dvv = (xyz(h[5]) - 2.0 * wv * r.dv - wvv * p) * iw;
  }
  r.p = p + xyz(o);
}

}  // namespace

namespace {

// The point and derivatives up to order ND of a surface: `homogeneous(rational, h, o)` computes
// its homogeneous sums (std::true_type for a rational surface), from_homogeneous the rest.
template <int ND, class Eval, class Homogeneous>
Eval evaluate(bool rational, double min_weight, const Homogeneous& homogeneous) {
  double h[(ND + 1) * (ND + 2) / 2][4], o[3];
  Eval r;
  if (rational) {
    homogeneous(std::true_type{}, h, o);
    from_homogeneous<ND, true>(h, o, min_weight, r);
  } else {
    homogeneous(std::false_type{}, h, o);
    from_homogeneous<ND, false>(h, o, min_weight, r);
  }
  return r;
}

}  // namespace

SurfaceEval1 NurbsSurface::eval1(double u, double v) const {
  return evaluate<1, SurfaceEval1>(rational(), min_weight_, [&](auto rat, auto h, auto o) {
    eval_homogeneous<1, decltype(rat)::value>(u, v, h, o);
  });
}

namespace {

// find_span's span of u along u, without its search when it is `last` (a span, or -1): the
// points of a row come a knot span at a time.
inline int span_u(const EvalView& s, int last, double u) {
  if (last >= 0) {
    const bool from_first = last == s.first_u || s.U[last] <= u;
    const bool to_last = last == s.last_u || u < s.U[last + 1];
    if (from_first && to_last) return last;
  }
  return detail::find_span(s.U, s.first_u, s.last_u, u);
}

// eval1 at (us[k], v), k < n, on the Bezier table: the v basis once, the sums along v once per
// span pair (bezier_columns), then per point the u basis and the sums along u; every step the
// arithmetic of eval_bezier, hence the same bits.
template <bool Rational, int P, int Q>
void eval1_row_bezier(const EvalView& s, double v, const double* us, std::size_t n,
                      double min_weight, SurfaceEval1* out) {
  const int iv = detail::find_span(s.V, s.first_v, s.last_v, v) - s.first_v;
  double Nv[2][detail::kMaxBasis];
  bernstein<1, Q>((v - s.bv[2 * iv]) * s.bv[2 * iv + 1], s.bv[2 * iv + 1], Nv);
  A4 T[P + 1][2];
  for (auto& t : T) t[0] = t[1] = A4::Zero();  // set for the first point's span below
  const double* patch = nullptr;
  int last_iu = -1;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = us[k];
    const int iu = span_u(s, last_iu < 0 ? -1 : s.first_u + last_iu, u) - s.first_u;
    if (iu != last_iu) {
      patch = bezier_patch<P, Q>(s, iu, iv);
      bezier_columns<1, P, Q>(patch, Nv, T);
      last_iu = iu;
    }
    double Nu[2][detail::kMaxBasis];
    bernstein<1, P>((u - s.bu[2 * iu]) * s.bu[2 * iu + 1], s.bu[2 * iu + 1], Nu);
    double h[3][4];
    bezier_combine<1, Rational, P>(Nu, T, h);
    out[k].ok = true;  // as a SurfaceEval1 made by eval1; from_homogeneous sets the rest
    from_homogeneous<1, Rational>(h, patch, min_weight, out[k]);
  }
}

// eval1 at (us[k], v), k < n, summing the B-spline basis (degrees without a Bezier table):
// the v basis once, the sums along v once per knot span along u (window_row), then per point
// the u basis and the sums along u; every step eval_fixed's arithmetic, hence the same bits.
template <bool Rational>
void eval1_row_window(const EvalView& s, double v, const double* us, std::size_t n,
                      double min_weight, SurfaceEval1* out) {
  const int p = s.p, q = s.q;
  const int sv = detail::find_span(s.V, s.first_v, s.last_v, v);
  double Nv[2][detail::kMaxBasis];
  detail::ders_basis<1, 0>(s.V, sv, q, v, Nv);
  double T[detail::kMaxBasis][2][4];
  const double* o = nullptr;
  int last_su = -1;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = us[k];
    const int su = span_u(s, last_su, u);
    if (su != last_su) {
      o = window_origin(s, su, sv, p, q);
      for (int i = 0; i <= p; ++i)
        window_row<1, Rational, 0>(o + 4 * static_cast<size_t>(i) * s.count_v, q, o, Nv, T[i]);
      last_su = su;
    }
    double Nu[2][detail::kMaxBasis];
    detail::ders_basis<1, 0>(s.U, su, p, u, Nu);
    double acc[3][4] = {};
    for (int i = 0; i <= p; ++i) window_add<1>(Nu, i, T[i], acc);
    double h[3][4];
    window_out<1, Rational>(acc, h);
    out[k].ok = true;  // as a SurfaceEval1 made by eval1; from_homogeneous sets the rest
    from_homogeneous<1, Rational>(h, o, min_weight, out[k]);
  }
}

using RowKernel = void (*)(const EvalView&, double, const double*, std::size_t, double,
                           SurfaceEval1*);

// The row kernels by degree key (FixedDegrees), null for the other keys.
template <bool Rational, int... Keys>
constexpr auto row_kernel_table(std::integer_sequence<int, Keys...>) {
  constexpr int kLast = std::max({Keys...});
  std::array<RowKernel, kLast + 1> table{};
  ((table[Keys] = &eval1_row_bezier<Rational, Keys / kKeyBase, Keys % kKeyBase>), ...);
  return table;
}

template <bool Rational>
RowKernel row_kernel_for(int p, int q) {
  static constexpr auto kTable = row_kernel_table<Rational>(FixedDegrees{});
  const int key = degree_key(p, q);
  return key < static_cast<int>(kTable.size()) ? kTable[static_cast<std::size_t>(key)] : nullptr;
}

}  // namespace

void NurbsSurface::eval1_along_u(double v, const double* us, std::size_t n,
                                 SurfaceEval1* out) const {
  // The Bezier table's kernels where eval1 uses them, else the sums of the B-spline basis.
  RowKernel row = rational() ? &eval1_row_window<true> : &eval1_row_window<false>;
  if (!bezier_.empty()) {
    if (RowKernel b = rational() ? row_kernel_for<true>(data_.degree_u, data_.degree_v)
                                 : row_kernel_for<false>(data_.degree_u, data_.degree_v))
      row = b;
  }
  with_view([&](const EvalView& s) { row(s, v, us, n, min_weight_, out); });
}

bool NurbsSurface::made_from(const NurbsSurfaceData& d, const Tolerances& tol) const {
  const NurbsSurfaceData& m = data_;
  return degenerate_rel_ == tol.degenerate_rel && min_weight_rel_ == tol.extension_min_weight_rel &&
         m.degree_u == d.degree_u && m.degree_v == d.degree_v && m.count_u == d.count_u &&
         m.count_v == d.count_v && m.knots_u == d.knots_u && m.knots_v == d.knots_v &&
         m.weights == d.weights &&
         std::equal(m.poles.begin(), m.poles.end(), d.poles.begin(), d.poles.end(),
                    [](const Vec3& a, const Vec3& b) { return a == b; });
}

SurfaceEval2 NurbsSurface::eval2(double u, double v) const {
  return evaluate<2, SurfaceEval2>(rational(), min_weight_, [&](auto rat, auto h, auto o) {
    eval_homogeneous<2, decltype(rat)::value>(u, v, h, o);
  });
}

bool NurbsSurface::is_degenerate(const Vec3& du, const Vec3& dv) const {
  return du.cross(dv).norm() <= degenerate_rel_ * speed_u_ * speed_v_;
}

SurfaceNormal NurbsSurface::normal(double u, double v) const {
  SurfaceNormal out;
  const SurfaceEval2 e = eval2(u, v);
  if (!e.ok) {
    out.ok = false;
    return out;
  }
  const Vec3 c = e.du.cross(e.dv);
  if (!is_degenerate(e.du, e.dv)) {
    out.n = c.normalized();
    return out;
  }
  out.degenerate = true;
  // First-order limit: N(u + h, v) ~ h * d(Su x Sv)/du, taken towards the domain interior.
  const double su = (u <= 0.5 * (domain_.u0 + domain_.u1)) ? 1.0 : -1.0;
  const double sv = (v <= 0.5 * (domain_.v0 + domain_.v1)) ? 1.0 : -1.0;
  const Vec3 cu = su * (e.duu.cross(e.dv) + e.du.cross(e.duv));
  const Vec3 cv = sv * (e.duv.cross(e.dv) + e.du.cross(e.dvv));
  // The collapsed direction is the one whose first derivative vanishes; move across it.
  const bool dv_vanishes = e.dv.norm() * speed_u_ <= e.du.norm() * speed_v_;
  const Vec3& first = dv_vanishes ? cu : cv;
  const Vec3& second = dv_vanishes ? cv : cu;
  const double thresh = degenerate_rel_ * speed_u_ * speed_v_ *
                        std::max(1.0 / domain_.width_u(), 1.0 / domain_.width_v());
  if (first.norm() > thresh) {
    out.n = first.normalized();
    return out;
  }
  if (second.norm() > thresh) {
    out.n = second.normalized();
    return out;
  }
  // Higher-order degeneracy: average normals at nearby interior points.
  Vec3 acc = Vec3::Zero();
  for (double f : {1e-6, 1e-5, 1e-4}) {
    const double uu = u + su * f * domain_.width_u();
    const double vv = v + sv * f * domain_.width_v();
    const SurfaceEval1 n1 = eval1(uu, vv);
    const Vec3 cc = n1.du.cross(n1.dv);
    if (n1.ok && cc.norm() > 0.0 && cc.allFinite()) acc += cc.normalized();
    if (acc.norm() > 0.5) break;
  }
  if (acc.norm() > 0.0) {
    out.n = acc.normalized();
  } else {
    out.ok = false;
  }
  return out;
}

}  // namespace plyfit
