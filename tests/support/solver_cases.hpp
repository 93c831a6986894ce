#pragma once
// Valid configurations for the mapping solvers, built independently of them (bisection along
// surface curves), shared by the property tests and plyfit-bench.

#include "surface/face.hpp"

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace plyfit::support {

/// Both points p of the sphere |p| = R at distance d from its points a and b, in closed form:
/// p.a = p.b = (2R^2 - d^2)/2, so p = alpha a + beta b + t n with n normal to a and b.
inline std::pair<Vec3, Vec3> sphere_points_at(const Vec3& a, const Vec3& b, double R, double d) {
  const double k = (2 * R * R - d * d) / 2, aa = a.dot(a), ab = a.dot(b), bb = b.dot(b);
  const double det = aa * bb - ab * ab;
  const Vec3 p0 = a * ((k * bb - k * ab) / det) + b * ((k * aa - k * ab) / det);
  const Vec3 n = a.cross(b).normalized();
  const double t = std::sqrt(R * R - p0.squaredNorm());
  return {p0 + t * n, p0 - t * n};
}

/// A point at 3D distance r from S(uv0) along the surface curve uv0 + t dir (t > 0), by
/// bisection; false if none is found or it is off the face.
inline bool point_at_distance(const Face& f, const Vec2& uv0, const Vec2& dir, double r,
                              Vec2& out) {
  constexpr int kGrow = 200, kBisect = 200;  // bracket growth and bisection caps
  const Vec3 p0 = f.eval1(uv0).p;
  double lo = 0.0, hi = 1e-6;
  for (int k = 0; k < kGrow && (f.eval1(uv0 + hi * dir).p - p0).norm() < r; ++k) hi *= 1.5;
  if ((f.eval1(uv0 + hi * dir).p - p0).norm() < r) return false;
  for (int k = 0; k < kBisect; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((f.eval1(uv0 + mid * dir).p - p0).norm() < r ? lo : hi) = mid;
  }
  out = uv0 + 0.5 * (lo + hi) * dir;
  return f.contains(out);
}

/// One configuration as the drape meets it: a known cell corner c with neighbours a and b at
/// distance d from it (thread angle at c between 0.5 and pi - 0.5 rad); the unknown node p
/// lies at distance d from a and b on the side of line ab away from c (`side`). `guess` is
/// the parallelogram guess ua + ub - uc. For solvers 1 and 3, c is the known point, with a
/// base plane through c (tilted about the direction c -> a) and `travel` along it.
struct SolverCase {
  Vec3 c, a, b;
  Vec2 uc, ua, ub;
  double side = 1.0;
  Vec2 guess;
  Vec3 plane_normal;
  Vec3 travel;
};

/// n configurations on the inner 70% of the face's domain, spacing d.
inline std::vector<SolverCase> make_solver_cases(const Face& f, double d, int n, unsigned seed) {
  std::mt19937_64 gen(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen); };
  std::vector<SolverCase> out;
  const auto& dom = f.domain();
  for (int tries = 0; static_cast<int>(out.size()) < n && tries < 4 * n; ++tries) {
    SolverCase k;
    k.uc = Vec2(dom.u0 + dom.width_u() * uni(0.15, 0.85), dom.v0 + dom.width_v() * uni(0.15, 0.85));
    const SurfaceEval1 ec = f.eval1(k.uc);
    auto uvdir = [&](double t) {
      return Vec2(std::cos(t) / ec.du.norm(), std::sin(t) / ec.dv.norm());
    };
    const double t1 = uni(0, 2 * kPi), t2 = t1 + uni(0.5, kPi - 0.5);
    if (!point_at_distance(f, k.uc, uvdir(t1), d, k.ua)) continue;
    if (!point_at_distance(f, k.uc, uvdir(t2), d, k.ub)) continue;
    k.c = ec.p;
    k.a = f.eval1(k.ua).p;
    k.b = f.eval1(k.ub).p;
    const Vec3 nrm = f.normal(k.uc).n;
    k.side = nrm.dot((k.b - k.a).cross(k.c - k.a)) > 0 ? -1.0 : 1.0;
    k.guess = k.ua + k.ub - k.uc;
    const Vec3 w = (k.a - k.c).normalized();
    const double psi = uni(-1.0, 1.0);
    k.plane_normal = (std::cos(psi) * nrm.cross(w) + std::sin(psi) * nrm).normalized();
    const Vec3 along = k.plane_normal.cross(nrm);
    k.travel = along.dot(w) > 0 ? along : Vec3(-along);
    out.push_back(k);
  }
  return out;
}

}  // namespace plyfit::support
