#include "face_measure.hpp"

#include <plyfit/kernel/nurbs.hpp>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2d.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <queue>
#include <vector>

namespace plyfit::importers::occt {

namespace {

// Gauss-Kronrod 7/15 nodes and weights on [-1, 1] (QUADPACK's qk15): Kronrod nodes, the odd
// ones (1, 3, 5) and the centre are the Gauss nodes.
constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975,
                           0.417959183673469387755102040816327};

// Gauss-Legendre rules on [-1, 1] (nodes +-x with weight w) for the inner integral.
struct GaussRule {
  int half;  // node pairs
  double x[4], w[4];
};
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

// Inner rules, coarsest first: a Gauss rule on each of `pieces` equal parts of every knot span.
// Past the last, each knot span is cut adaptively (RowTable::adaptive_columns).
struct InnerRule {
  const GaussRule* gauss;
  int pieces;
};
constexpr InnerRule kInnerRules[] = {{&kGauss2, 1}, {&kGauss4, 1}, {&kGauss8, 1}};
constexpr int kInnerRuleCount = static_cast<int>(std::size(kInnerRules));
// Adaptive columns: a piece of a knot span is halved at most this many times. Halving alone
// grades the columns towards a point where the row integrand is not smooth (surf114.igs: |S_u|
// vanishes along both u edges, and the integrand bends sharply close to them), where equal
// parts converged slowly: 64 parts per span still missed 1e-10 by 70 times.
constexpr int kMaxColumnDepth = 30;
// Rows across the face on which the inner rules are compared.
constexpr int kInnerTestRows = 12;
// Shares of the requested accuracy given to the boundary integral and to each of the inner
// rule and the row table (these two are relative to a row integral; the boundary sums rows
// of both signs, about two to three times the area on the test files).
constexpr double kOuterShare = 0.5, kInnerShare = 0.1;
// Chebyshev-Lobatto points per band of the row table, nested (each set holds the previous
// one): a band takes the next set until the previous set's interpolant matches the rows at the
// new points, and is halved (at most kMaxBandDepth times) when the largest set does not.
constexpr int kBandNodes[] = {3, 5, 9, 17};
// The band's end points move this fraction of the band inwards (see lobatto()): the
// interpolant then extrapolates over as little, an error far below the accuracy asked.
constexpr double kBandInset = 1e-12;
constexpr int kMaxBandDepth = 12;
// Samples per smooth interval of a pcurve searched for crossings of knot lines, and the
// bisection steps that locate a crossing (to the last bits of the parameter).
constexpr int kCrossingSamples = 16;
constexpr int kBisectionSteps = 60;
// Budget of boundary segments for one face: past it the integration stops unconverged.
constexpr int kMaxSegments = 20000;
// The error is not driven below this multiple of the rounding of the summed contributions.
constexpr double kRoundoffFloor = 64.0 * std::numeric_limits<double>::epsilon();
// A face spans at most this many periods of a periodic surface (a valid one spans one).
constexpr double kMaxPeriods = 64.0;

// Thrown when a measure runs out of its work cap (Evaluator::budget, kMaxPeriods).
struct WorkCapReached {
  const char* what;
};

// |S_u x S_v| and points of the face's surface.
// The integration's (u, v) are the surface's, or (v, u) when `transposed`.
class Evaluator {
 public:
  virtual ~Evaluator() = default;
  virtual void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const = 0;
  double density(double u, double v) const {
    Vec3 p, a, b;
    at(u, v, p, a, b);
    return a.cross(b).norm();
  }
  Vec3 point(double u, double v) const {
    Vec3 p, a, b;
    at(u, v, p, a, b);
    return p;
  }
  mutable long count = 0;
  long budget = kMaxMeasureEvaluations;  // evaluations allowed
  bool transposed = false;

 private:
  void at(double u, double v, Vec3& p, Vec3& a, Vec3& b) const {
    if (++count > budget) throw WorkCapReached{"the integration ran out of its work cap"};
    if (transposed)
      d1(v, u, p, a, b);
    else
      d1(u, v, p, a, b);
  }
};

// OpenCASCADE's evaluation: analytic, swept, offset and periodic B-spline surfaces.
class OcctEvaluator final : public Evaluator {
 public:
  explicit OcctEvaluator(Handle(Geom_Surface) s) : s_(std::move(s)) {}
  void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const override {
    gp_Pnt P;
    gp_Vec U, V;
    s_->D1(u, v, P, U, V);
    p = Vec3(P.X(), P.Y(), P.Z());
    du = Vec3(U.X(), U.Y(), U.Z());
    dv = Vec3(V.X(), V.Y(), V.Z());
  }

 private:
  Handle(Geom_Surface) s_;
};

// The kernel's evaluation of the same B-spline: OpenCASCADE's span cache is rebuilt at every
// change of span, which the inner integrals make all the time.
class KernelEvaluator final : public Evaluator {
 public:
  explicit KernelEvaluator(NurbsSurface s) : s_(std::move(s)) {}
  void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const override {
    const SurfaceEval1 e = s_.eval1(u, v);
    p = e.p;
    du = e.du;
    dv = e.dv;
  }

 private:
  NurbsSurface s_;
};

// The kernel copy of a non-periodic B-spline, or nothing.
std::unique_ptr<Evaluator> kernel_evaluator(const Handle(Geom_BSplineSurface) & b) {
  if (b.IsNull() || b->IsUPeriodic() || b->IsVPeriodic()) return nullptr;
  auto s = NurbsSurface::create(nurbs_data(b));
  if (!s) return nullptr;
  return std::make_unique<KernelEvaluator>(std::move(s).value());
}

// Parameter values where the surface's smoothness drops (knots), along one direction.
struct Breaks {
  std::vector<double> base;  // ascending; for a periodic direction, those of one period
  double period = 0.0;       // > 0 for a periodic direction

  // The breakpoints strictly inside (lo, hi), ascending.
  void inside(double lo, double hi, std::vector<double>& out) const {
    out.clear();
    if (base.empty() || !(hi > lo)) return;
    if (period <= 0.0) {
      for (auto it = std::upper_bound(base.begin(), base.end(), lo); it != base.end() && *it < hi;
           ++it)
        out.push_back(*it);
      return;
    }
    const double first = base.front();
    if (!((hi - lo) / period <= kMaxPeriods))
      throw WorkCapReached{"the face spans more periods of its surface than any valid face"};
    for (double shift = std::floor((lo - first) / period) * period; first + shift < hi;
         shift += period)
      for (double b : base)
        if (b + shift > lo && b + shift < hi) out.push_back(b + shift);
  }
};

Breaks breaks_of(const Handle(Geom_Surface) & s, bool along_u) {
  Breaks br;
  const bool periodic = along_u ? s->IsUPeriodic() : s->IsVPeriodic();
  if (const auto b = Handle(Geom_BSplineSurface)::DownCast(s); !b.IsNull()) {
    const int n = along_u ? b->NbUKnots() : b->NbVKnots();
    for (int i = periodic ? 1 : 2; i <= (periodic ? n - 1 : n - 1); ++i)
      br.base.push_back(along_u ? b->UKnot(i) : b->VKnot(i));
    if (periodic) br.period = along_u ? b->UPeriod() : b->VPeriod();
    return br;
  }
  GeomAdaptor_Surface ad(s);
  const int n = along_u ? ad.NbUIntervals(GeomAbs_C2) : ad.NbVIntervals(GeomAbs_C2);
  if (n > 1 || periodic) {
    TColStd_Array1OfReal t(1, n + 1);
    if (along_u)
      ad.UIntervals(t, GeomAbs_C2);
    else
      ad.VIntervals(t, GeomAbs_C2);
    for (int i = periodic ? 1 : 2; i <= n; ++i) br.base.push_back(t(i));
    if (periodic) br.period = along_u ? s->UPeriod() : s->VPeriod();
  }
  return br;
}

// One boundary edge: its pcurve and the sign of its traversal.
struct EdgeRef {
  Handle(Geom2d_Curve) curve;
  double sign = 1.0;
};

// A piece of an edge's parameter range and its Gauss-Kronrod estimate.
struct Segment {
  double t0 = 0, t1 = 0;
  int edge = 0;
  double value = 0, error = 0, abs_value = 0;
  bool operator<(const Segment& o) const { return error < o.error; }
};

// Chebyshev-Lobatto point k of n on [v0, v1] (k = 0 at v0), and its barycentric weight. The
// end points are moved inside by kBandInset of the band (at least a few ulps): a band ends on
// a knot line, where a surface that is only C0 has two derivatives, and the row there must be
// the one of the band's side (the evaluator would pick one side for both bands).
double lobatto(int k, int n, double v0, double v1) {
  constexpr double kPi = 3.14159265358979323846;
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

// G(u, v) = the integral of |S_u x S_v| along u from the face's smallest u, tabulated: the
// (u, v) box is cut into columns (knot spans, each in `pieces` equal parts) and bands (knot
// spans in v, halved until the table is accurate); in each band the row integrals up to every
// column boundary are kept at Chebyshev points of v and interpolated (barycentric formula).
// G at any (u, v) is then the interpolated row up to the column holding u plus a Gauss rule
// over the rest of that column: a few evaluations instead of a whole row's.
class RowTable {
 public:
  RowTable(const Evaluator& eval, const Breaks& ub, const Breaks& vb, double u0, double u1,
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
  Breaks column_breaks() const {
    Breaks b;
    b.base.assign(cols_.begin() + 1, cols_.end() - 1);
    return b;
  }
  Breaks band_breaks() const {
    Breaks b;
    for (size_t k = 1; k < bands_.size(); ++k) b.base.push_back(bands_[k].v0);
    return b;
  }
  // Estimated relative error of G (rule and interpolation), relative to a row integral.
  double relative_error() const { return rule_error_ + table_error_; }

  double G(double u, double v) const {
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

 private:
  struct Band {
    double v0 = 0, v1 = 0;
    std::vector<double> nodes, weights;
    std::vector<double> rows;  // nodes x columns + 1: the row integral up to each boundary
  };

  // Rows across the box on which rules are compared: spread over the knot spans in v.
  static std::vector<double> test_rows(const Breaks& vb, double v0, double v1) {
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
  void adaptive_columns(const std::vector<double>& knots, const std::vector<double>& vs,
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
          worst =
              std::max(worst, std::abs(gauss(p.a, p.b, v) - gauss(p.a, m, v) - gauss(m, p.b, v)));
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
  double row_over(const std::vector<double>& knots, double v) const {
    double s = 0.0;
    for (size_t k = 0; k + 1 < knots.size(); ++k) s += gauss(knots[k], knots[k + 1], v);
    return s;
  }

  void set_columns(const std::vector<double>& knots, const InnerRule& rule) {
    rule_ = rule;
    cols_.clear();
    for (size_t k = 0; k + 1 < knots.size(); ++k)
      for (int p = 0; p < rule.pieces; ++p)
        cols_.push_back(knots[k] + (knots[k + 1] - knots[k]) * p / rule.pieces);
    cols_.push_back(knots.back());
  }

  // The integral of |S_u x S_v| along u over [a, b] at v, by the column rule.
  double gauss(double a, double b, double v) const {
    if (a == b) return 0.0;
    const GaussRule& g = *rule_.gauss;
    const double c = 0.5 * (a + b), r = 0.5 * (b - a);
    double sum = 0.0;
    for (int j = 0; j < g.half; ++j)
      sum += g.w[j] * (eval_.density(c - r * g.x[j], v) + eval_.density(c + r * g.x[j], v));
    return r * sum;
  }

  // The row integrals at v up to every column boundary (out[0] = 0).
  void row(double v, double* out) const {
    out[0] = 0.0;
    for (size_t i = 0; i + 1 < cols_.size(); ++i)
      out[i + 1] = out[i] + gauss(cols_[i], cols_[i + 1], v);
  }
  double row_total(double v) const {
    double s = 0.0;
    for (size_t i = 0; i + 1 < cols_.size(); ++i) s += gauss(cols_[i], cols_[i + 1], v);
    return s;
  }

  // Adds the band [v0, v1]: rows at nested Chebyshev-Lobatto points, more of them until the
  // interpolant of the previous set matches the rows at the new points to `tol` (relative to a
  // row integral), then the larger set is kept; or two halves when the largest set does not.
  void add_band(double v0, double v1, double tol, int depth) {
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
  static size_t locate(const std::vector<double>& xs, double x) {
    const auto it = std::upper_bound(xs.begin(), xs.end() - 1, x);
    return it == xs.begin()
               ? 0
               : std::min<size_t>(static_cast<size_t>(it - xs.begin()) - 1, xs.size() - 2);
  }
  size_t band_of(double v) const {
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

  const Evaluator& eval_;
  InnerRule rule_ = kInnerRules[0];
  std::vector<double> cols_;
  std::vector<Band> bands_;
  double rule_error_ = 0.0, table_error_ = 0.0;
  double row_scale_ = 0.0;  // the largest |row integral| of the rule test
};

// The boundary integral of G(u, v) dv by Gauss-Kronrod.
class AreaIntegrator {
 public:
  explicit AreaIntegrator(const RowTable& table) : table_(table) {}

  // QUADPACK's 15-point Gauss-Kronrod estimate of a segment (value and error).
  void integrate(const EdgeRef& e, Segment& s) const {
    const double c = 0.5 * (s.t0 + s.t1), h = 0.5 * (s.t1 - s.t0), dh = std::abs(h);
    const double fc = f(e, c);
    double resg = fc * kWg[3], resk = fc * kWgk[7], resabs = std::abs(resk);
    double fv1[7], fv2[7];
    for (int j = 0; j < 7; ++j) {
      const double x = h * kXgk[j];
      fv1[j] = f(e, c - x);
      fv2[j] = f(e, c + x);
      resk += kWgk[j] * (fv1[j] + fv2[j]);
      resabs += kWgk[j] * (std::abs(fv1[j]) + std::abs(fv2[j]));
      if (j % 2 == 1) resg += kWg[j / 2] * (fv1[j] + fv2[j]);
    }
    const double reskh = 0.5 * resk;
    double resasc = kWgk[7] * std::abs(fc - reskh);
    for (int j = 0; j < 7; ++j)
      resasc += kWgk[j] * (std::abs(fv1[j] - reskh) + std::abs(fv2[j] - reskh));
    s.value = resk * h;
    resabs *= dh;
    resasc *= dh;
    double err = std::abs((resk - resg) * h);
    if (resasc != 0.0 && err != 0.0)
      err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    if (resabs > std::numeric_limits<double>::min() / (50.0 * kEps))
      err = std::max(50.0 * kEps * resabs, err);
    s.error = err;
    s.abs_value = resabs;
  }

 private:
  // The boundary integrand: G(u(t), v(t)) v'(t), signed by the edge's traversal.
  double f(const EdgeRef& e, double t) const {
    gp_Pnt2d p;
    gp_Vec2d d;
    e.curve->D1(t, p, d);
    if (d.Y() == 0.0) return 0.0;
    return e.sign * table_.G(p.X(), p.Y()) * d.Y();
  }

  const RowTable& table_;
};

// Splits [a, b] of a pcurve where it crosses a knot line of the surface (u or v), so that the
// boundary integrand is smooth on each piece; appends the pieces to `out`.
void split_at_crossings(const Handle(Geom2d_Curve) & c, double a, double b, const Breaks& ub,
                        const Breaks& vb, int edge, std::vector<Segment>& out) {
  std::vector<double> cuts{a, b};
  Geom2dAdaptor_Curve ad(c, a, b);
  const int nint = ad.NbIntervals(GeomAbs_C2);
  if (nint > 1) {
    TColStd_Array1OfReal iv(1, nint + 1);
    ad.Intervals(iv, GeomAbs_C2);
    for (int k = 2; k <= nint; ++k) cuts.push_back(iv(k));
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> all, found;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double t0 = cuts[k], t1 = cuts[k + 1];
    if (!(t1 > t0)) continue;
    all.push_back(t0);
    gp_Pnt2d prev = c->Value(t0);
    double tp = t0;
    for (int i = 1; i <= kCrossingSamples; ++i) {
      const double t = i == kCrossingSamples ? t1 : t0 + (t1 - t0) * i / kCrossingSamples;
      const gp_Pnt2d q = c->Value(t);
      for (int dir = 0; dir < 2; ++dir) {
        const double x0 = dir == 0 ? prev.X() : prev.Y(), x1 = dir == 0 ? q.X() : q.Y();
        (dir == 0 ? ub : vb).inside(std::min(x0, x1), std::max(x0, x1), found);
        for (double knot : found) {
          // Bisection on the sign of (coordinate - knot).
          double lo = tp, hi = t;
          const bool rising = x1 > x0;
          for (int it = 0; it < kBisectionSteps; ++it) {
            const double mid = 0.5 * (lo + hi);
            if (!(mid > lo && mid < hi)) break;
            const gp_Pnt2d m = c->Value(mid);
            const double xm = dir == 0 ? m.X() : m.Y();
            if ((xm < knot) == rising)
              lo = mid;
            else
              hi = mid;
          }
          all.push_back(0.5 * (lo + hi));
        }
      }
      prev = q;
      tp = t;
    }
  }
  all.push_back(b);
  std::sort(all.begin(), all.end());
  for (size_t k = 0; k + 1 < all.size(); ++k)
    if (all[k + 1] > all[k]) out.push_back(Segment{all[k], all[k + 1], edge, 0, 0, 0});
}

// Appends the straight (u, v) segment from `a` to `b` as a boundary edge, unless they coincide.
void add_segment(const gp_Pnt2d& a, const gp_Pnt2d& b, std::vector<EdgeRef>& edges,
                 std::vector<std::pair<double, double>>& ranges) {
  const double length = a.Distance(b);
  if (!(length > 0.0)) return;
  edges.push_back(EdgeRef{new Geom2d_Line(a, gp_Dir2d(b.X() - a.X(), b.Y() - a.Y())), 1.0});
  ranges.emplace_back(0.0, length);
}

// `box`, or an empty box when a corner is not finite (a point evaluated off a broken face).
BBox3 finite_or_empty(const BBox3& box) {
  return box.empty || (box.min.allFinite() && box.max.allFinite()) ? box : BBox3{};
}

FaceMeasure fallback(const TopoDS_Face& face, double rel_tol, bool with_box) {
  FaceMeasure m;
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props, rel_tol);
  m.area = props.Mass();
  if (with_box) {
    Bnd_Box box;
    BRepBndLib::AddOptimal(face, box, Standard_False, Standard_False);
    if (!box.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      m.bbox.add(Vec3(x0, y0, z0));
      m.bbox.add(Vec3(x1, y1, z1));
    }
  }
  if (!std::isfinite(m.area)) {
    m.area = 0.0;
    m.measured = false;
    m.failure = "OpenCASCADE's integration gave no finite value";
  }
  m.bbox = finite_or_empty(m.bbox);
  return m;
}

// The box of points on the boundary (each edge sampled on every smooth interval of its pcurve)
// and of the grid points of the (u, v) box inside the boundary polygon (even-odd rule): it
// depends on the geometry alone, not on the accuracy asked of the area.
BBox3 face_box(const Evaluator& eval, const std::vector<EdgeRef>& edges,
               const std::vector<std::pair<double, double>>& ranges, double u0, double u1,
               double v0, double v1) {
  BBox3 box;
  std::vector<std::pair<Vec2, Vec2>> poly;
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto [a, b] = ranges[k];
    Geom2dAdaptor_Curve ad(edges[k].curve, a, b);
    const int nint = ad.NbIntervals(GeomAbs_C2);
    TColStd_Array1OfReal iv(1, nint + 1);
    ad.Intervals(iv, GeomAbs_C2);
    const int per = std::max(1, kBoxEdgeSamples / nint);
    Vec2 prev = Vec2::Zero();
    bool first = true;
    for (int i = 1; i <= nint; ++i)
      for (int j = (i == 1 ? 0 : 1); j <= per; ++j) {
        const gp_Pnt2d q = edges[k].curve->Value(iv(i) + (iv(i + 1) - iv(i)) * j / per);
        const Vec2 uv(q.X(), q.Y());
        box.add(eval.point(uv.x(), uv.y()));
        if (!first) poly.emplace_back(prev, uv);
        prev = uv;
        first = false;
      }
  }
  std::vector<double> xs;
  for (int r = 0; r < kBoxGrid; ++r) {
    const double v = v0 + (r + 0.5) * (v1 - v0) / kBoxGrid;
    xs.clear();
    for (const auto& [a, b] : poly)
      if ((a.y() <= v) != (b.y() <= v))
        xs.push_back(a.x() + (v - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    std::sort(xs.begin(), xs.end());
    size_t left = 0;
    for (int c = 0; c < kBoxGrid; ++c) {
      const double u = u0 + (c + 0.5) * (u1 - u0) / kBoxGrid;
      while (left < xs.size() && xs[left] < u) ++left;
      if (left % 2 == 1) box.add(eval.point(u, v));
    }
  }
  return box;
}

// The boundary, wire by wire with the edges in order along it; where an edge's pcurve does
// not start where the previous one ended (CAD files leave gaps of up to 6e-4 mm, e.g.
// PRO20359-L1.igs), a straight (u, v) segment closes the gap, so that every loop is closed
// and Green's theorem gives the area it bounds (an open loop's result would depend on the
// direction of integration).
// False when an edge has no pcurve. `transposed`: every pcurve mirrored in the line u = v.
bool boundary_of(const TopoDS_Face& face, bool transposed, std::vector<EdgeRef>& edges,
                 std::vector<std::pair<double, double>>& ranges) {
  const gp_Ax2d diagonal(gp_Pnt2d(0, 0), gp_Dir2d(1, 1));
  for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) {
    const size_t first = edges.size();
    gp_Pnt2d loop_start, last_end;
    for (const TopoDS_Edge& e : ordered_edges(TopoDS::Wire(wx.Current()), face)) {
      const TopAbs_Orientation o = e.Orientation();
      if (o != TopAbs_FORWARD && o != TopAbs_REVERSED) continue;
      double a = 0, b = 0;
      Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, a, b);
      if (c.IsNull() || !(b > a)) return false;
      if (transposed) {
        c = Handle(Geom2d_Curve)::DownCast(c->Copy());
        c->Mirror(diagonal);
      }
      const bool reversed = o == TopAbs_REVERSED;
      const gp_Pnt2d start = c->Value(reversed ? b : a), end = c->Value(reversed ? a : b);
      if (edges.size() == first)
        loop_start = start;
      else
        add_segment(last_end, start, edges, ranges);
      edges.push_back(EdgeRef{c, reversed ? -1.0 : 1.0});
      ranges.emplace_back(a, b);
      last_end = end;
    }
    if (edges.size() > first) add_segment(last_end, loop_start, edges, ranges);
  }
  return !edges.empty();
}

// The boundary integral over a row table made to `inner_tol` (relative to a row integral).
struct Pass {
  double total = 0.0, error = 0.0, magnitude = 0.0, inner_rel = 0.0;
};

// The (u, v) box of the face, its surface (for its knots) and its boundary, to integrate over.
struct Region {
  const Handle(Geom_Surface) & geometry;
  bool transposed;
  double u0, u1, v0, v1;
  const std::vector<EdgeRef>& edges;
  const std::vector<std::pair<double, double>>& ranges;
};

Pass integrate_pass(const Evaluator& eval, const Region& r, double rel_tol, double inner_tol) {
  const auto& edges = r.edges;
  const auto& ranges = r.ranges;
  const RowTable table(eval, breaks_of(r.geometry, !r.transposed),
                       breaks_of(r.geometry, r.transposed), r.u0, r.u1, r.v0, r.v1, inner_tol);
  const AreaIntegrator integrator(table);
  std::vector<Segment> segs;
  const Breaks ub = table.column_breaks(), vb = table.band_breaks();
  for (size_t k = 0; k < edges.size(); ++k)
    split_at_crossings(edges[k].curve, ranges[k].first, ranges[k].second, ub, vb,
                       static_cast<int>(k), segs);
  // Globally adaptive: the segment with the largest error estimate is halved until the
  // estimates add up to the outer share of the requested accuracy.
  std::priority_queue<Segment> queue;
  Pass p;
  p.inner_rel = table.relative_error();
  for (Segment& seg : segs) {
    integrator.integrate(edges[static_cast<size_t>(seg.edge)], seg);
    p.total += seg.value;
    p.error += seg.error;
    p.magnitude += seg.abs_value;
    queue.push(seg);
  }
  while (p.error >
             std::max(kOuterShare * rel_tol * std::abs(p.total), kRoundoffFloor * p.magnitude) &&
         static_cast<int>(queue.size()) < kMaxSegments) {
    const Segment worst = queue.top();
    queue.pop();
    const double mid = 0.5 * (worst.t0 + worst.t1);
    if (!(mid > worst.t0 && mid < worst.t1)) {
      // Cannot be halved further: keep it as it is (its error stays in the sum).
      queue.push(Segment{worst.t0, worst.t1, worst.edge, worst.value, 0.0, worst.abs_value});
      p.error -= worst.error;
      continue;
    }
    Segment a{worst.t0, mid, worst.edge, 0, 0, 0}, b{mid, worst.t1, worst.edge, 0, 0, 0};
    integrator.integrate(edges[static_cast<size_t>(a.edge)], a);
    integrator.integrate(edges[static_cast<size_t>(b.edge)], b);
    p.total += a.value + b.value - worst.value;
    p.error += a.error + b.error - worst.error;
    p.magnitude += a.abs_value + b.abs_value - worst.abs_value;
    queue.push(a);
    queue.push(b);
  }
  return p;
}

}  // namespace

NurbsSurfaceData nurbs_data(const Handle(Geom_BSplineSurface) & b) {
  NurbsSurfaceData d;
  d.degree_u = b->UDegree();
  d.degree_v = b->VDegree();
  d.count_u = b->NbUPoles();
  d.count_v = b->NbVPoles();
  TColStd_Array1OfReal ku(1, d.count_u + d.degree_u + 1), kv(1, d.count_v + d.degree_v + 1);
  b->UKnotSequence(ku);
  b->VKnotSequence(kv);
  d.knots_u.assign(ku.begin(), ku.end());
  d.knots_v.assign(kv.begin(), kv.end());
  const bool rational = b->IsURational() || b->IsVRational();
  d.poles.reserve(static_cast<size_t>(d.count_u) * d.count_v);
  for (int i = 1; i <= d.count_u; ++i)
    for (int j = 1; j <= d.count_v; ++j) {
      const gp_Pnt& p = b->Pole(i, j);
      d.poles.emplace_back(p.X(), p.Y(), p.Z());
      if (rational) d.weights.push_back(b->Weight(i, j));
    }
  return d;
}

std::vector<TopoDS_Edge> ordered_edges(const TopoDS_Wire& w, const TopoDS_Face& f) {
  std::vector<TopoDS_Edge> edges;
  int count = 0;
  for (TopoDS_Iterator it(w); it.More(); it.Next()) ++count;
  for (BRepTools_WireExplorer we(w, f); we.More(); we.Next()) edges.push_back(we.Current());
  if (static_cast<int>(edges.size()) == count) return edges;
  // The explorer could not chain every edge (a wire OpenCASCADE finds ill-connected): keep the
  // stored order, which readers write along the wire.
  edges.clear();
  for (TopoDS_Iterator it(w); it.More(); it.Next())
    if (it.Value().ShapeType() == TopAbs_EDGE) edges.push_back(TopoDS::Edge(it.Value()));
  return edges;
}

FaceMeasure measure_face(const TopoDS_Face& face, double rel_tol, bool with_box, bool transposed) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  if (s.IsNull()) return fallback(face, rel_tol, with_box);
  Handle(Geom_Surface) basis = s;
  while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(basis))
    basis = t->BasisSurface();
  Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(basis);
  if (const auto z = Handle(Geom_BezierSurface)::DownCast(basis); !z.IsNull())
    bspline = GeomConvert::SurfaceToBSplineSurface(z);
  std::unique_ptr<Evaluator> eval = kernel_evaluator(bspline);
  if (!eval) eval = std::make_unique<OcctEvaluator>(basis);
  eval->transposed = transposed;
  if (!bspline.IsNull())
    eval->budget +=
        kMeasureEvaluationsPerPatch * (bspline->NbUKnots() - 1) * (bspline->NbVKnots() - 1);
  const Handle(Geom_Surface)& geometry = bspline.IsNull() ? basis : bspline;

  std::vector<EdgeRef> edges;
  std::vector<std::pair<double, double>> ranges;
  if (!boundary_of(face, transposed, edges, ranges)) return fallback(face, rel_tol, with_box);
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (transposed) {
    std::swap(u0, v0);
    std::swap(u1, v1);
  }
  const Region region{geometry, transposed, u0, u1, v0, v1, edges, ranges};

  FaceMeasure m;
  try {
    if (with_box) m.bbox = finite_or_empty(face_box(*eval, edges, ranges, u0, u1, v0, v1));
    // The inner share assumes the boundary's rows add up to about the area; where they add up
    // to more (rows of both signs that cancel) and the table's error is what misses the
    // accuracy, the table is made again, tighter by the ratio.
    Pass pass = integrate_pass(*eval, region, rel_tol, kInnerShare * rel_tol);
    const double area = std::abs(pass.total), inner = pass.inner_rel * pass.magnitude;
    if (pass.error + inner > rel_tol * area && inner > kOuterShare * rel_tol * area &&
        pass.magnitude > area)
      pass = integrate_pass(*eval, region, rel_tol, kInnerShare * rel_tol * area / pass.magnitude);
    m.area = std::abs(pass.total);
    m.error = pass.error + pass.inner_rel * pass.magnitude;
    m.converged = m.error <= std::max(rel_tol * m.area, kRoundoffFloor * pass.magnitude);
    if (!std::isfinite(m.area) || !std::isfinite(m.error))
      throw WorkCapReached{"the integration gave no finite value"};
  } catch (const WorkCapReached& e) {
    const BBox3 box = m.bbox;  // the box alone, if made
    m = FaceMeasure{};
    m.bbox = box;
    m.measured = false;
    m.failure = e.what;
  }
  m.evaluations = eval->count;
  return m;
}

}  // namespace plyfit::importers::occt
