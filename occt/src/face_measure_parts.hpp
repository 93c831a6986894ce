#pragma once
// The pieces of measure_face() (face_measure.hpp) shared by its files: the surface evaluators,
// the knot lines, the boundary as pcurves, the row table of G(u, v) and the boundary integral.
// face_row_table.cpp tabulates G, face_boundary.cpp assembles the boundary (and the face's box),
// face_boundary_integral.cpp integrates G dv around it, face_measure.cpp puts them together.

#include "face_measure.hpp"

#include <plyfit/kernel/types.hpp>

#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace plyfit::importers::occt::measure {

// Shares of the requested accuracy given to the boundary integral and to each of the inner
// rule and the row table (these two are relative to a row integral; the boundary sums rows
// of both signs, about two to three times the area on the test files).
constexpr double kOuterShare = 0.5, kInnerShare = 0.1;
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
  // density(us[k], v) and point(us[k], v) for k < n into out[k]: the same values, by the
  // evaluator's rows where it has them (points along u at one v share work).
  void densities(double v, const double* us, int n, double* out) const {
    along_u(v, us, n, [&](int k, const SurfaceEval1& e) { out[k] = e.du.cross(e.dv).norm(); });
  }
  void points(double v, const double* us, int n, Vec3* out) const {
    along_u(v, us, n, [&](int k, const SurfaceEval1& e) { out[k] = e.p; });
  }
  mutable long count = 0;
  long budget = kMaxMeasureEvaluations;  // evaluations allowed
  bool transposed = false;

 private:
  // Rows of points along the surface's u: out[k] at (us[k], v), k < n <= kRowPoints, as d1
  // has them.
  static constexpr int kRowPoints = 16;
  virtual bool has_rows() const { return false; }
  virtual void row_d1(double, const double*, int, SurfaceEval1*) const {}
  // Calls take(k, evaluation at (us[k], v)) for k < n.
  template <class Take>
  void along_u(double v, const double* us, int n, const Take& take) const {
    SurfaceEval1 e[kRowPoints];
    if (!transposed && has_rows()) {
      charge(n);
      for (int k0 = 0; k0 < n; k0 += kRowPoints) {
        const int m = std::min(n - k0, kRowPoints);
        row_d1(v, us + k0, m, e);
        for (int k = 0; k < m; ++k) take(k0 + k, e[k]);
      }
      return;
    }
    for (int k = 0; k < n; ++k) {
      at(us[k], v, e[0].p, e[0].du, e[0].dv);
      take(k, e[0]);
    }
  }
  // Counts n evaluations; past the budget, the count stops one past it (where evaluating
  // point by point would have stopped) and the measure ends.
  void charge(long n) const {
    if (count + n > budget) {
      count = budget + 1;
      throw WorkCapReached{"the integration ran out of its work cap"};
    }
    count += n;
  }
  void at(double u, double v, Vec3& p, Vec3& a, Vec3& b) const {
    charge(1);
    if (transposed)
      d1(v, u, p, a, b);
    else
      d1(u, v, p, a, b);
  }
};

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

// Gauss-Legendre rules on [-1, 1] (nodes +-x with weight w) for the inner integral.
struct GaussRule {
  int half;  // node pairs
  double x[4], w[4];
};

// Inner rules, coarsest first: a Gauss rule on each of `pieces` equal parts of every knot span.
// Past the last, each knot span is cut adaptively (RowTable::adaptive_columns).
struct InnerRule {
  const GaussRule* gauss;
  int pieces;
};

// G(u, v) = the integral of |S_u x S_v| along u from the face's smallest u, tabulated: the
// (u, v) box is cut into columns (knot spans, each in `pieces` equal parts) and bands (knot
// spans in v, halved until the table is accurate); in each band the row integrals up to every
// column boundary are kept at Chebyshev points of v and interpolated (barycentric formula).
// G at any (u, v) is then the interpolated row up to the column holding u plus a Gauss rule
// over the rest of that column: a few evaluations instead of a whole row's.
class RowTable {
 public:
  RowTable(const Evaluator& eval, const Breaks& ub, const Breaks& vb, double u0, double u1,
           double v0, double v1, double inner_tol);

  // Interior column and band boundaries, where the boundary integrand loses smoothness.
  Breaks column_breaks() const;
  Breaks band_breaks() const;
  // Estimated relative error of G (rule and interpolation), relative to a row integral.
  double relative_error() const { return rule_error_ + table_error_; }

  double G(double u, double v) const;

 private:
  struct Band {
    double v0 = 0, v1 = 0;
    std::vector<double> nodes, weights;
    std::vector<double> rows;  // nodes x columns + 1: the row integral up to each boundary
  };

  static std::vector<double> test_rows(const Breaks& vb, double v0, double v1);
  void adaptive_columns(const std::vector<double>& knots, const std::vector<double>& vs,
                        double tol);
  double row_over(const std::vector<double>& knots, double v) const;
  void set_columns(const std::vector<double>& knots, const InnerRule& rule);
  double gauss(double a, double b, double v) const;
  void row(double v, double* out) const;
  double row_total(double v) const;
  void add_band(double v0, double v1, double tol, int depth);
  static size_t locate(const std::vector<double>& xs, double x);
  size_t band_of(double v) const;

  const Evaluator& eval_;
  InnerRule rule_{nullptr, 1};  // set by the constructor (set_columns, adaptive_columns)
  std::vector<double> cols_;
  std::vector<Band> bands_;
  double rule_error_ = 0.0, table_error_ = 0.0;
  double row_scale_ = 0.0;  // the largest |row integral| of the rule test
};

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

// Parameter values where the surface's smoothness drops (knots), along one direction.
Breaks breaks_of(const Handle(Geom_Surface) & s, bool along_u);

// The boundary integral of G over `r` with a row table made to `inner_tol`.
Pass integrate_pass(const Evaluator& eval, const Region& r, double rel_tol, double inner_tol);

// The boundary of `face` as pcurves with their parameter ranges, loops closed (see the
// definition); false when an edge has no pcurve.
bool boundary_of(const TopoDS_Face& face, bool transposed, std::vector<EdgeRef>& edges,
                 std::vector<std::pair<double, double>>& ranges);

// Splits [a, b] of a pcurve where it crosses a knot line of the surface (u or v), so that the
// boundary integrand is smooth on each piece; appends the pieces to `out`.
void split_at_crossings(const Handle(Geom2d_Curve) & c, double a, double b, const Breaks& ub,
                        const Breaks& vb, int edge, std::vector<Segment>& out);

// The box of points on the boundary and of grid points of the (u, v) box inside it.
BBox3 face_box(const Evaluator& eval, const std::vector<EdgeRef>& edges,
               const std::vector<std::pair<double, double>>& ranges, double u0, double u1,
               double v0, double v1);

}  // namespace plyfit::importers::occt::measure
