#pragma once
// Private to the kernel: the small numerical pieces shared by the geometry, the surfaces and
// the drape: the first fundamental form of a surface and the 2x2 solves on it, the damped
// step of a Newton iteration on (u, v), and the Gauss-Legendre rule.

#include <plyfit/kernel/nurbs.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

/// The floor a length, a squared length or a diagonal entry is raised to before it divides:
/// a zero one then divides to a huge finite value instead of inf or NaN.
inline constexpr double kDivisionFloor = 1e-300;

/// The first fundamental form of the derivatives in e (a SurfaceEval1 or SurfaceEval2):
/// [Su.Su, Su.Sv; Su.Sv, Sv.Sv].
template <class Eval>
Eigen::Matrix2d metric(const Eval& e) {
  Eigen::Matrix2d G;
  G << e.du.dot(e.du), e.du.dot(e.dv), e.du.dot(e.dv), e.dv.dot(e.dv);
  return G;
}

/// The components (Su.v, Sv.v) of a 3D vector v along the derivatives in e.
template <class Eval>
Vec2 metric_rhs(const Eval& e, const Vec3& v) {
  return Vec2(e.du.dot(v), e.dv.dot(v));
}

/// The (u, v) step whose image under the derivatives in e is v in the least-squares sense,
/// G^-1 (Su.v, Sv.v). Where G is singular (a pole), the step along the one derivative that
/// does not vanish; zero where neither does or the result is not finite.
inline Vec2 metric_solve(const SurfaceEval1& e, const Vec3& v) {
  const Eigen::Matrix2d G = metric(e);
  const Vec2 rhs = metric_rhs(e, v);
  const double det = G.determinant();
  if (!(std::abs(det) > 0.0)) {
    const double a = G(0, 0), b = G(1, 1);
    if (a >= b && a > 0.0) return Vec2(rhs.x() / a, 0.0);
    if (b > 0.0) return Vec2(0.0, rhs.y() / b);
    return Vec2::Zero();
  }
  const Vec2 r = G.inverse() * rhs;
  return r.allFinite() ? r : Vec2::Zero();
}

/// G^-1 rhs for a metric G whose diagonal is raised by `rel` of itself (and kDivisionFloor),
/// so that a derivative vanishing at a pole leaves G invertible; relative to each diagonal
/// entry because |Su| and |Sv| may differ by many orders of magnitude.
inline Vec2 regularised_solve(Eigen::Matrix2d G, const Vec2& rhs, double rel) {
  G(0, 0) = G(0, 0) * (1.0 + rel) + kDivisionFloor;
  G(1, 1) = G(1, 1) * (1.0 + rel) + kDivisionFloor;
  return G.inverse() * rhs;
}

/// The damped Newton (Levenberg-Marquardt) step -(H + lambda D)^-1 g on (u, v), solved in
/// Jacobi-scaled variables (x_i sqrt(D_i)): |Su| and |Sv| may differ by many orders, and the
/// damping lambda is then relative to each diagonal entry D of the Gauss-Newton matrix.
inline Vec2 damped_step(const Eigen::Matrix2d& H, const Vec2& g, const Vec2& D, double lambda) {
  const Vec2 sc(1.0 / std::sqrt(D.x()), 1.0 / std::sqrt(D.y()));
  Eigen::Matrix2d M = sc.asDiagonal() * H * sc.asDiagonal();
  M(0, 0) += lambda;
  M(1, 1) += lambda;
  return -(sc.asDiagonal() * M.fullPivLu().solve(sc.asDiagonal() * g)).eval();
}

/// The 5-point Gauss-Legendre rule on [-1, 1]: nodes and weights.
inline constexpr double kGauss5X[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
inline constexpr double kGauss5W[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                       0.4786286704993665, 0.2369268850561891};

/// The 2-point Gauss-Legendre rule on [-1, 1] (weights 1).
inline constexpr double kGauss2X[2] = {-0.5773502691896258, 0.5773502691896258};

}  // namespace plyfit::detail
