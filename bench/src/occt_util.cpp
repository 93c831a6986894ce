#include "occt_util.hpp"

#include "nurbs_conversion.hpp"

#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>

namespace plyfit::bench {

namespace {
// Gauss-Newton iterations of the distance computation; it stops earlier once a step no
// longer shortens the distance.
constexpr int kDistanceIterations = 12;
}  // namespace

OcctDistance::OcctDistance(const NurbsSurfaceData& d) : s_(occt::to_occt(d)) {
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
