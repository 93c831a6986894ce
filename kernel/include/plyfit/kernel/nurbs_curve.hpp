#pragma once
/// \file Rational and non-rational B-spline curves in 2D (trim curves) and 3D (threads).

#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/types.hpp>

#include <vector>

namespace plyfit {

/// Plain data of a NURBS curve in Dim dimensions.
template <int Dim>
struct NurbsCurveData {
  using Point = Eigen::Matrix<double, Dim, 1>;
  int degree = 1;               ///< 1..25
  std::vector<double> knots;    ///< flat knot vector, poles + degree + 1 values
  std::vector<Point> poles;     ///< control points
  std::vector<double> weights;  ///< empty for a non-rational curve, else one per pole (> 0)
};

/// Point and first two derivatives of a curve; `ok` false where an extended rational curve
/// is undefined (vectors then zero).
template <int Dim>
struct CurveEval {
  Eigen::Matrix<double, Dim, 1> p, d1, d2;
  bool ok = true;
};

/// A validated NURBS curve. Evaluation outside the domain extends the end polynomials.
template <int Dim>
class NurbsCurve {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;
  /// Validates `data` with the same rules as NurbsSurface::create().
  static Result<NurbsCurve> create(NurbsCurveData<Dim> data);

  const NurbsCurveData<Dim>& data() const { return data_; }
  double t0() const { return t0_; }  ///< start of the parameter domain
  double t1() const { return t1_; }  ///< end of the parameter domain
  bool rational() const { return !data_.weights.empty(); }

  /// Point at t.
  Point point(double t) const;
  /// Point and derivatives up to second order (exact quotient rule when rational).
  CurveEval<Dim> eval2(double t) const;
  /// Polyline through curve points, including every knot, whose chords deviate from the curve
  /// by at most `chord_tol` (adaptive bisection, depth-capped).
  std::vector<Point> tessellate(double chord_tol) const;

 private:
  NurbsCurve() = default;
  NurbsCurveData<Dim> data_;
  std::vector<double> hpoles_;  // poles and weights (x, y[, z], w), stride Dim + 1
  double t0_ = 0.0, t1_ = 1.0;
  int first_span_ = 0, last_span_ = 0;
};

using NurbsCurve2 = NurbsCurve<2>;
using NurbsCurve3 = NurbsCurve<3>;
using NurbsCurveData2 = NurbsCurveData<2>;
using NurbsCurveData3 = NurbsCurveData<3>;

/// Global cubic interpolation (The NURBS Book, A9.1) through `points` with chord-length
/// parameters and averaged knots; the curve passes through every point exactly (to
/// rounding). Two points give a line, three a quadratic. Error if fewer than two points or
/// two consecutive points coincide.
Result<NurbsCurve3> interpolate_cubic(const std::vector<Vec3>& points);

/// Degree-1 B-spline through `points` with chord-length parameters.
Result<NurbsCurve3> polyline_curve(const std::vector<Vec3>& points);

}  // namespace plyfit
