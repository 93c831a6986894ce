#include "occt_util.hpp"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <vector>

namespace plyfit::bench {

namespace {
// Gauss-Newton iterations of the distance computation; it stops earlier once a step no
// longer shortens the distance.
constexpr int kDistanceIterations = 12;
}  // namespace

Handle(Geom_BSplineSurface) to_occt(const NurbsSurfaceData& d) {
  auto compress = [](const std::vector<double>& flat, TColStd_Array1OfReal& knots,
                     TColStd_Array1OfInteger& mults) {
    std::vector<double> k;
    std::vector<int> m;
    for (double x : flat) {
      if (!k.empty() && x == k.back()) {
        ++m.back();
      } else {
        k.push_back(x);
        m.push_back(1);
      }
    }
    knots.Resize(1, static_cast<int>(k.size()), false);
    mults.Resize(1, static_cast<int>(k.size()), false);
    for (size_t i = 0; i < k.size(); ++i) {
      knots(static_cast<int>(i) + 1) = k[i];
      mults(static_cast<int>(i) + 1) = m[i];
    }
  };
  TColStd_Array1OfReal uk(1, 1), vk(1, 1);
  TColStd_Array1OfInteger um(1, 1), vm(1, 1);
  compress(d.knots_u, uk, um);
  compress(d.knots_v, vk, vm);
  TColgp_Array2OfPnt poles(1, d.count_u, 1, d.count_v);
  TColStd_Array2OfReal w(1, d.count_u, 1, d.count_v);
  for (int i = 0; i < d.count_u; ++i)
    for (int j = 0; j < d.count_v; ++j) {
      const Vec3& p = d.pole(i, j);
      poles(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
      w(i + 1, j + 1) = d.weight(i, j);
    }
  if (d.weights.empty())
    return new Geom_BSplineSurface(poles, uk, vk, um, vm, d.degree_u, d.degree_v);
  return new Geom_BSplineSurface(poles, w, uk, vk, um, vm, d.degree_u, d.degree_v);
}

OcctDistance::OcctDistance(const NurbsSurfaceData& d) : s_(to_occt(d)) {
  s_->Bounds(u0_, u1_, v0_, v1_);
}

double OcctDistance::operator()(const Vec3& p, const Vec2& seed) const {
  double u = std::clamp(seed.x(), u0_, u1_), v = std::clamp(seed.y(), v0_, v1_);
  gp_Pnt S;
  gp_Vec Su, Sv;
  s_->D1(u, v, S, Su, Sv);
  double best = std::sqrt(S.SquareDistance(gp_Pnt(p.x(), p.y(), p.z())));
  for (int it = 0; it < kDistanceIterations; ++it) {
    const Vec3 r(p.x() - S.X(), p.y() - S.Y(), p.z() - S.Z());
    const Vec3 a(Su.X(), Su.Y(), Su.Z()), b(Sv.X(), Sv.Y(), Sv.Z());
    const double g00 = a.dot(a), g01 = a.dot(b), g11 = b.dot(b);
    const double det = g00 * g11 - g01 * g01;
    if (!(det > 0.0)) break;
    const double ra = a.dot(r), rb = b.dot(r);
    const double du = (g11 * ra - g01 * rb) / det, dv = (g00 * rb - g01 * ra) / det;
    const double un = std::clamp(u + du, u0_, u1_), vn = std::clamp(v + dv, v0_, v1_);
    s_->D1(un, vn, S, Su, Sv);
    const double dist = std::sqrt(S.SquareDistance(gp_Pnt(p.x(), p.y(), p.z())));
    u = un;
    v = vn;
    if (!(dist < best)) {
      best = std::min(best, dist);
      break;
    }
    best = dist;
  }
  return best;
}

}  // namespace plyfit::bench
