#include "nurbs_conversion.hpp"

#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>

namespace plyfit::occt {

KnotsMults compress_knots(const std::vector<double>& flat) {
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
  KnotsMults r{TColStd_Array1OfReal(1, static_cast<int>(k.size())),
               TColStd_Array1OfInteger(1, static_cast<int>(k.size()))};
  for (size_t i = 0; i < k.size(); ++i) {
    r.knots(static_cast<int>(i) + 1) = k[i];
    r.mults(static_cast<int>(i) + 1) = m[i];
  }
  return r;
}

Handle(Geom_BSplineSurface) to_occt(const NurbsSurfaceData& d) {
  const KnotsMults ku = compress_knots(d.knots_u), kv = compress_knots(d.knots_v);
  TColgp_Array2OfPnt poles(1, d.count_u, 1, d.count_v);
  for (int i = 0; i < d.count_u; ++i)
    for (int j = 0; j < d.count_v; ++j) {
      const Vec3& p = d.pole(i, j);
      poles(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
    }
  if (d.weights.empty())
    return new Geom_BSplineSurface(poles, ku.knots, kv.knots, ku.mults, kv.mults, d.degree_u,
                                   d.degree_v);
  TColStd_Array2OfReal w(1, d.count_u, 1, d.count_v);
  for (int i = 0; i < d.count_u; ++i)
    for (int j = 0; j < d.count_v; ++j) w(i + 1, j + 1) = d.weight(i, j);
  return new Geom_BSplineSurface(poles, w, ku.knots, kv.knots, ku.mults, kv.mults, d.degree_u,
                                 d.degree_v);
}

Handle(Geom_BSplineCurve) to_occt(const NurbsCurveData3& d) {
  const KnotsMults k = compress_knots(d.knots);
  const int n = static_cast<int>(d.poles.size());
  TColgp_Array1OfPnt poles(1, n);
  for (int i = 0; i < n; ++i) poles(i + 1) = gp_Pnt(d.poles[i].x(), d.poles[i].y(), d.poles[i].z());
  if (d.weights.empty()) return new Geom_BSplineCurve(poles, k.knots, k.mults, d.degree);
  TColStd_Array1OfReal w(1, n);
  for (int i = 0; i < n; ++i) w(i + 1) = d.weights[i];
  return new Geom_BSplineCurve(poles, w, k.knots, k.mults, d.degree);
}

Handle(Geom2d_BSplineCurve) to_occt(const NurbsCurveData2& d) {
  const KnotsMults k = compress_knots(d.knots);
  const int n = static_cast<int>(d.poles.size());
  TColgp_Array1OfPnt2d poles(1, n);
  for (int i = 0; i < n; ++i) poles(i + 1) = gp_Pnt2d(d.poles[i].x(), d.poles[i].y());
  if (d.weights.empty()) return new Geom2d_BSplineCurve(poles, k.knots, k.mults, d.degree);
  TColStd_Array1OfReal w(1, n);
  for (int i = 0; i < n; ++i) w(i + 1) = d.weights[i];
  return new Geom2d_BSplineCurve(poles, w, k.knots, k.mults, d.degree);
}

}  // namespace plyfit::occt
