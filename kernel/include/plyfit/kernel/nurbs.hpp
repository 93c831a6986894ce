#pragma once
/// \file NURBS: rational and non-rational B-spline surfaces (eq. (3) of the paper) and curves
/// in 2D (trim curves) and 3D (threads).

#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>

#include <cstddef>
#include <vector>

namespace plyfit {

/// Plain data of a NURBS surface, as importers and constructors produce it. Validated by
/// NurbsSurface::create().
struct NurbsSurfaceData {
  int degree_u = 1;             ///< degree in u (1..25)
  int degree_v = 1;             ///< degree in v (1..25)
  int count_u = 0;              ///< number of poles along u
  int count_v = 0;              ///< number of poles along v
  std::vector<double> knots_u;  ///< flat knot vector, count_u + degree_u + 1 values
  std::vector<double> knots_v;  ///< flat knot vector, count_v + degree_v + 1 values
  std::vector<Vec3> poles;      ///< count_u * count_v poles, index i * count_v + j (i along u)
  std::vector<double> weights;  ///< empty for a non-rational surface, else one per pole (> 0)

  /// Pole (i, j).
  Vec3& pole(int i, int j) { return poles[static_cast<size_t>(i) * count_v + j]; }
  const Vec3& pole(int i, int j) const { return poles[static_cast<size_t>(i) * count_v + j]; }
  /// Weight of pole (i, j) (1 when non-rational).
  double weight(int i, int j) const {
    return weights.empty() ? 1.0 : weights[static_cast<size_t>(i) * count_v + j];
  }
};

/// Point and first partial derivatives at (u, v). `ok` is false where the surface is not
/// defined (a rational surface extended past its domain until its weight vanishes); the
/// vectors are then zero, never NaN.
struct SurfaceEval1 {
  Vec3 p, du, dv;
  bool ok = true;
};

/// Point and all partial derivatives up to second order at (u, v).
struct SurfaceEval2 {
  Vec3 p, du, dv, duu, duv, dvv;
  bool ok = true;
};

/// Unit normal at (u, v). At a degenerate point (e.g. a pole where a whole edge collapses to
/// one point) the normal is the limit from the interior and `degenerate` is set.
struct SurfaceNormal {
  Vec3 n = Vec3::UnitZ();
  bool degenerate = false;
  bool ok = true;  ///< false only if no limit could be found (then n is a placeholder)
};

/// A validated NURBS surface. Evaluation outside the parameter domain extends the end
/// polynomials of the boundary spans (the surface "extended past its edge").
class NurbsSurface {
 public:
  /// Validates `data` (knot count = poles + degree + 1, non-decreasing knots, multiplicity
  /// <= degree + 1, a non-empty domain, finite poles, positive finite weights, degree 1..25)
  /// and builds the surface. The error message names the first problem found.
  static Result<NurbsSurface> create(NurbsSurfaceData data, const Tolerances& tol = {});

  /// The plain data this surface was built from.
  const NurbsSurfaceData& data() const { return data_; }
  /// Parameter domain [U_p, U_n] x [V_q, V_m].
  const ParamDomain& domain() const { return domain_; }
  /// True when weights were given (even if all equal).
  bool rational() const { return !data_.weights.empty(); }
  /// Bounding box of the control net (contains the surface over its domain).
  const BBox3& control_bbox() const { return bbox_; }

  /// Point at (u, v).
  Vec3 point(double u, double v) const;
  /// Point and first derivatives.
  SurfaceEval1 eval1(double u, double v) const;
  /// eval1(us[k], v) for k < n into out[k], the same values; the sums along v are shared by the
  /// points of one knot span (a row of quadrature points along u costs about half).
  void eval1_along_u(double v, const double* us, std::size_t n, SurfaceEval1* out) const;
  /// Point and derivatives up to second order (exact quotient rule for rational surfaces).
  SurfaceEval2 eval2(double u, double v) const;
  /// Unit normal Su x Sv / |Su x Sv|, or its limit at a degenerate point.
  SurfaceNormal normal(double u, double v) const;
  /// True when |Su x Sv| is below the degenerate threshold at (u, v).
  bool is_degenerate(const Vec3& du, const Vec3& dv) const;
  /// True when this surface is what create(data, tol) makes: built from equal data, with the
  /// tolerances it depends on (degenerate_rel, extension_min_weight_rel) equal.
  bool made_from(const NurbsSurfaceData& data, const Tolerances& tol) const;

  /// Characteristic parametric speeds |dS/du| and |dS/dv| (control-net extent over domain
  /// width), used to scale parameter-space tolerances.
  double speed_u() const { return speed_u_; }
  double speed_v() const { return speed_v_; }
  /// What double rounding makes a point S(u, v) of the domain uncertain by (model units): the
  /// sums over the span's poles, relative to its first pole ((p + q) roundings of a weighted
  /// mean of the poles' offsets, at most the control net's extent), and the spacing of the
  /// doubles near (u, v) themselves, eps (|u| |Su| + |v| |Sv|): the surface is only known at
  /// representable parameters (u in radians around 4.7 steps by 9e-16 rad; a length parameter
  /// of 1e5 mm by 1.5e-11 mm). That spacing is taken where it is largest among the knots and
  /// the span middles, doubled for the peaks between them. Coordinates far from the origin add
  /// their own ulps where the point is used (see residual_tolerance in the solvers).
  double rounding() const { return rounding_; }

 private:
  NurbsSurface() = default;
  template <int ND, bool Rational>
  void eval_homogeneous(double u, double v, double out[][4], double origin[3]) const;
  // Calls f(view) with the evaluation view of this surface (defined in nurbs_surface.cpp).
  template <class F>
  void with_view(const F& f) const;
  void build_bezier();
  double estimate_rounding() const;

  NurbsSurfaceData data_;
  std::vector<double> hpoles_;  // poles and weights (x, y, z, w), stride 4
  ParamDomain domain_;
  BBox3 bbox_;
  int first_span_u_ = 0, last_span_u_ = 0, first_span_v_ = 0, last_span_v_ = 0;
  double speed_u_ = 1.0, speed_v_ = 1.0;
  double min_weight_ = 1.0;
  double rounding_ = 0.0;
  double degenerate_rel_ = 1e-8;
  double min_weight_rel_ = 1e-3;  // Tolerances::extension_min_weight_rel it was built with
  // Bezier form of every knot-span pair, for the degrees with fixed-degree kernels (1..3 x
  // 1..3, 4 x 4, 5 x 5), built by create() and read-only after (thread-safe): per span pair
  // the first pole of its B-spline window (the origin, padded to 4 doubles) and the
  // (p + 1) x (q + 1) homogeneous Bezier poles (w (B - origin), w). Empty for other degrees
  // or when the table would be too large; evaluation then sums the B-spline basis.
  std::vector<double> bezier_;
  std::vector<double> bezier_u_, bezier_v_;  // per span: first knot, 1 / span width
  int bezier_spans_v_ = 0;                   // spans along v (last_span_v_ - first_span_v_ + 1)
};

// ---- curves ----

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
