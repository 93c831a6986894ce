#include "face_measure_parts.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <type_traits>
#include <vector>

namespace plyfit::importers::occt::measure {

namespace {

// Gauss-Legendre rules on [-1, 1] for the inner integral.
constexpr GaussRule kGauss2 = {1, {0.577350269189625764509148780502}, {1.0}};
constexpr GaussRule kGauss4 = {
    2,
    {0.339981043584856264802665759103, 0.861136311594052575223946488893},
    {0.652145154862546142626936050778, 0.347854845137453857373063949222}};
constexpr GaussRule kGauss8 = {
    4,
    {0.183434642495649804939476142360, 0.525532409916328985817739049189,
     0.796666477413626739591553936476, 0.960289856497536231683560868569},
    {0.362683783378361982965150449277, 0.313706645877887287337962201987,
     0.222381034453374470544355994426, 0.101228536290376259152531354310}};

// Inner rules, coarsest first (InnerRule).
constexpr InnerRule kInnerRules[] = {{&kGauss2, 1}, {&kGauss4, 1}, {&kGauss8, 1}};
constexpr int kInnerRuleCount = static_cast<int>(std::size(kInnerRules));
// Adaptive columns: a piece of a knot span is halved at most this many times. Halving alone
// grades the columns towards a point where the row integrand is not smooth (surf114.igs: |S_u|
// vanishes along both u edges, and the integrand bends sharply close to them), where equal
// parts converged slowly: 64 parts per span still missed 1e-10 by 70 times.
constexpr int kMaxColumnDepth = 30;
// Rows across the face on which the inner rules are compared.
constexpr int kInnerTestRows = 12;
// Chebyshev-Lobatto points per band of the row table, nested (each set holds the previous
// one): a band takes the next set until the previous set's interpolant matches the rows at the
// new points, and is halved (at most kMaxBandDepth times) when the largest set does not.
constexpr int kBandNodes[] = {3, 5, 9, 17};
// The band's end points move this fraction of the band inwards (see lobatto()): the
// interpolant then extrapolates over as little, an error far below the accuracy asked.
constexpr double kBandInset = 1e-12;
constexpr int kMaxBandDepth = 12;

// Chebyshev-Lobatto point k of n on [v0, v1] (k = 0 at v0), and its barycentric weight. The
// end points are moved inside by kBandInset of the band (at least a few ulps): a band ends on
// a knot line, where a surface that is only C0 has two derivatives, and the row there must be
// the one of the band's side (the evaluator would pick one side for both bands).
double lobatto(int k, int n, double v0, double v1) {
  const double inset =
      std::max(kBandInset * (v1 - v0),
               4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(v0), std::abs(v1)));
  const double a = v0 + inset, b = v1 - inset;
  return 0.5 * (a + b) - 0.5 * (b - a) * std::cos(k * kPi / (n - 1));
}
double lobatto_weight(int k, int n) {
  return (k % 2 ? -1.0 : 1.0) * (k == 0 || k == n - 1 ? 0.5 : 1.0);
}

// The coefficients c_k (sum 1) of the barycentric interpolation at v over `nodes`.
void barycentric(const std::vector<double>& nodes, const std::vector<double>& weights, double v,
                 std::vector<double>& c) {
  c.assign(nodes.size(), 0.0);
  for (size_t k = 0; k < nodes.size(); ++k)
    if (v == nodes[k]) {
      c[k] = 1.0;
      return;
    }
  double den = 0.0;
  for (size_t k = 0; k < nodes.size(); ++k) {
    c[k] = weights[k] / (v - nodes[k]);
    den += c[k];
  }
  for (double& x : c) x /= den;
}

}  // namespace

RowTable::RowTable(const Evaluator& eval, const Breaks& ub, const Breaks& vb, double u0, double u1,
                   double v0, double v1, double inner_tol)
    : eval_(eval) {
  // Columns: the coarsest rule whose rows agree with the next finer one.
  std::vector<double> knots;
  ub.inside(u0, u1, knots);
  knots.insert(knots.begin(), u0);
  knots.push_back(u1);
  std::vector<double> vs = test_rows(vb, v0, v1);
  std::vector<double> prev;
  rule_error_ = 0.0;
  bool uniform = false;
  for (int level = 0; level < kInnerRuleCount; ++level) {
    set_columns(knots, kInnerRules[level]);
    std::vector<double> cur;
    double scale = 0.0;
    for (double v : vs) {
      cur.push_back(row_total(v));
      scale = std::max(scale, std::abs(cur.back()));
    }
    row_scale_ = scale;
    if (!prev.empty()) {
      double diff = 0.0;
      for (size_t k = 0; k < cur.size(); ++k) diff = std::max(diff, std::abs(cur[k] - prev[k]));
      rule_error_ = scale > 0.0 ? diff / scale : 0.0;
      if (rule_error_ <= inner_tol) {
        set_columns(knots, kInnerRules[level - 1]);
        uniform = true;
        break;
      }
    }
    prev = std::move(cur);
  }
  if (!uniform) adaptive_columns(knots, vs, inner_tol);
  // Bands: the knot spans in v, each halved until interpolation between its Chebyshev
  // points matches direct rows.
  std::vector<double> vk;
  vb.inside(v0, v1, vk);
  vk.insert(vk.begin(), v0);
  vk.push_back(v1);
  for (size_t k = 0; k + 1 < vk.size(); ++k) add_band(vk[k], vk[k + 1], inner_tol, 0);
}

// Interior column and band boundaries, where the boundary integrand loses smoothness.
Breaks RowTable::column_breaks() const {
  Breaks b;
  b.base.assign(cols_.begin() + 1, cols_.end() - 1);
  return b;
}

Breaks RowTable::band_breaks() const {
  Breaks b;
  for (size_t k = 1; k < bands_.size(); ++k) b.base.push_back(bands_[k].v0);
  return b;
}

double RowTable::G(double u, double v) const {
  const size_t i = locate(cols_, u);
  const Band& b = bands_[band_of(v)];
  // Barycentric interpolation of the row up to column boundary i.
  const size_t m = b.nodes.size(), stride = cols_.size();
  double num = 0.0, den = 0.0, exact = 0.0;
  bool hit = false;
  for (size_t k = 0; k < m; ++k) {
    const double d = v - b.nodes[k];
    if (d == 0.0) {
      exact = b.rows[k * stride + i];
      hit = true;
      break;
    }
    const double w = b.weights[k] / d;
    num += w * b.rows[k * stride + i];
    den += w;
  }
  const double s = hit ? exact : num / den;
  return s + gauss(cols_[i], u, v);
}

// Rows across the box on which rules are compared: spread over the knot spans in v.
std::vector<double> RowTable::test_rows(const Breaks& vb, double v0, double v1) {
  std::vector<double> vk;
  vb.inside(v0, v1, vk);
  vk.insert(vk.begin(), v0);
  vk.push_back(v1);
  const int spans = static_cast<int>(vk.size()) - 1;
  const int rows = std::min(spans * 2, kInnerTestRows);
  std::vector<double> vs;
  for (int r = 0; r < rows; ++r) {
    const double f = (r + 0.5) / rows * spans;
    const int k = std::min(static_cast<int>(f), spans - 1);
    vs.push_back(vk[static_cast<size_t>(k)] +
                 (f - k) * (vk[static_cast<size_t>(k) + 1] - vk[static_cast<size_t>(k)]));
  }
  return vs;
}

// Columns cut per knot span: a piece whose Gauss rule differs from the sum over its two
// halves, on any test row, by more than its share of `tol` (its part of the u range; relative
// to the largest row) is halved, up to kMaxColumnDepth times; else its halves are columns.
// The rule error is the sum of those differences over the columns kept (a bound of the
// coarser rule's error, so of the halves' too).
void RowTable::adaptive_columns(const std::vector<double>& knots, const std::vector<double>& vs,
                                double tol) {
  rule_ = InnerRule{&kGauss8, 1};
  cols_.clear();
  rule_error_ = 0.0;
  double scale = 0.0;
  for (double v : vs) scale = std::max(scale, std::abs(row_over(knots, v)));
  row_scale_ = scale;
  const double width = knots.back() - knots.front();
  struct Piece {
    double a, b;
    int depth;
  };
  for (size_t k = 0; k + 1 < knots.size(); ++k) {
    std::vector<Piece> stack = {{knots[k], knots[k + 1], 0}};
    while (!stack.empty()) {  // depth first, the left half on top: columns in order
      const Piece p = stack.back();
      stack.pop_back();
      const double m = 0.5 * (p.a + p.b);
      double worst = 0.0;
      for (double v : vs)
        worst = std::max(worst, std::abs(gauss(p.a, p.b, v) - gauss(p.a, m, v) - gauss(m, p.b, v)));
      const double rel = scale > 0.0 ? worst / scale : 0.0;
      if (rel > tol * (p.b - p.a) / width && p.depth < kMaxColumnDepth && m > p.a && m < p.b) {
        stack.push_back({m, p.b, p.depth + 1});
        stack.push_back({p.a, m, p.depth + 1});
        continue;
      }
      cols_.push_back(p.a);
      if (m > p.a && m < p.b) cols_.push_back(m);
      rule_error_ += rel;
    }
  }
  cols_.push_back(knots.back());
}

// The row integral at v over the knot spans, by the current rule on each whole span.
double RowTable::row_over(const std::vector<double>& knots, double v) const {
  double s = 0.0;
  for (size_t k = 0; k + 1 < knots.size(); ++k) s += gauss(knots[k], knots[k + 1], v);
  return s;
}

void RowTable::set_columns(const std::vector<double>& knots, const InnerRule& rule) {
  rule_ = rule;
  cols_.clear();
  for (size_t k = 0; k + 1 < knots.size(); ++k)
    for (int p = 0; p < rule.pieces; ++p)
      cols_.push_back(knots[k] + (knots[k + 1] - knots[k]) * p / rule.pieces);
  cols_.push_back(knots.back());
}

// The integral of |S_u x S_v| along u over [a, b] at v, by the column rule.
double RowTable::gauss(double a, double b, double v) const {
  if (a == b) return 0.0;
  const GaussRule& g = *rule_.gauss;
  const double c = 0.5 * (a + b), r = 0.5 * (b - a);
  constexpr std::size_t kPoints = 2 * std::extent_v<decltype(GaussRule::x)>;
  double us[kPoints], d[kPoints];
  for (int j = 0; j < g.half; ++j) {
    us[2 * j] = c - r * g.x[j];
    us[2 * j + 1] = c + r * g.x[j];
  }
  eval_.densities(v, us, 2 * g.half, d);
  double sum = 0.0;
  for (int j = 0; j < g.half; ++j) sum += g.w[j] * (d[2 * j] + d[2 * j + 1]);
  return r * sum;
}

// The row integrals at v up to every column boundary (out[0] = 0).
void RowTable::row(double v, double* out) const {
  out[0] = 0.0;
  for (size_t i = 0; i + 1 < cols_.size(); ++i)
    out[i + 1] = out[i] + gauss(cols_[i], cols_[i + 1], v);
}

double RowTable::row_total(double v) const {
  double s = 0.0;
  for (size_t i = 0; i + 1 < cols_.size(); ++i) s += gauss(cols_[i], cols_[i + 1], v);
  return s;
}

// Adds the band [v0, v1]: rows at nested Chebyshev-Lobatto points, more of them until the
// interpolant of the previous set matches the rows at the new points to `tol` (relative to a
// row integral), then the larger set is kept; or two halves when the largest set does not.
void RowTable::add_band(double v0, double v1, double tol, int depth) {
  const size_t stride = cols_.size();
  std::vector<double> coef;
  Band b;
  double rel = 0.0;
  for (size_t level = 0; level < std::size(kBandNodes); ++level) {
    const int n = kBandNodes[level];
    Band next;
    next.v0 = v0;
    next.v1 = v1;
    next.rows.resize(static_cast<size_t>(n) * stride);
    const int step = level == 0 ? 1 : (n - 1) / (kBandNodes[level - 1] - 1);
    double worst = 0.0;
    for (int k = 0; k < n; ++k) {
      next.nodes.push_back(lobatto(k, n, v0, v1));
      next.weights.push_back(lobatto_weight(k, n));
      double* out = &next.rows[static_cast<size_t>(k) * stride];
      if (level > 0 && k % step == 0) {
        // A point of the previous set: its row is known.
        const size_t old = static_cast<size_t>(k / step);
        std::copy_n(&b.rows[old * stride], stride, out);
        continue;
      }
      row(next.nodes.back(), out);
      if (level == 0) continue;
      barycentric(b.nodes, b.weights, next.nodes.back(), coef);
      for (size_t i = 0; i < stride; ++i) {
        double interp = 0.0;
        for (size_t j = 0; j < coef.size(); ++j) interp += coef[j] * b.rows[j * stride + i];
        worst = std::max(worst, std::abs(interp - out[i]));
      }
    }
    b = std::move(next);
    if (level == 0) continue;
    // Relative to the largest row across the face: a band where the rows vanish (along a
    // collapsed edge) is as accurate as it needs to be when its error is small against the
    // face's rows, not against its own.
    rel = row_scale_ > 0.0 ? worst / row_scale_ : 0.0;
    if (rel <= tol) break;
  }
  const double mid = 0.5 * (v0 + v1);
  if (rel > tol && depth < kMaxBandDepth && mid > v0 && mid < v1) {
    add_band(v0, mid, tol, depth + 1);
    add_band(mid, v1, tol, depth + 1);
    return;
  }
  table_error_ = std::max(table_error_, rel);
  bands_.push_back(std::move(b));
}

// The index i of the interval [x_i, x_(i+1)) of sorted `xs` holding x, clamped to the ends.
size_t RowTable::locate(const std::vector<double>& xs, double x) {
  const auto it = std::upper_bound(xs.begin(), xs.end() - 1, x);
  return it == xs.begin()
             ? 0
             : std::min<size_t>(static_cast<size_t>(it - xs.begin()) - 1, xs.size() - 2);
}

size_t RowTable::band_of(double v) const {
  size_t lo = 0, hi = bands_.size();
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (bands_[mid].v0 <= v)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

}  // namespace plyfit::importers::occt::measure
