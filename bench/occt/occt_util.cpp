#include "occt_util.hpp"

#include "nurbs_conversion.hpp"

#include <Geom_BSplineSurface.hxx>
#include <Standard_Version.hxx>
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

struct OcctDistance::Surface {
  Handle(Geom_BSplineSurface) s;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

OcctDistance::OcctDistance(const NurbsSurfaceData& d) {
  auto surface = std::make_unique<Surface>();
  surface->s = occt::to_occt(d);
  surface->s->Bounds(surface->u0, surface->u1, surface->v0, surface->v1);
  s_ = std::move(surface);
}

OcctDistance::~OcctDistance() = default;

double OcctDistance::operator()(const Vec3& p, const Vec2& seed) const {
  const Handle(Geom_BSplineSurface)& s = s_->s;
  const double u0 = s_->u0, u1 = s_->u1, v0 = s_->v0, v1 = s_->v1;
  double u = std::clamp(seed.x(), u0, u1), v = std::clamp(seed.y(), v0, v1);
  gp_Pnt S;
  gp_Vec Su, Sv;
  s->D1(u, v, S, Su, Sv);
  double best = std::sqrt(S.SquareDistance(gp_Pnt(p.x(), p.y(), p.z())));
  for (int it = 0; it < kDistanceIterations; ++it) {
    const Vec3 r(p.x() - S.X(), p.y() - S.Y(), p.z() - S.Z());
    const Vec3 a(Su.X(), Su.Y(), Su.Z()), b(Sv.X(), Sv.Y(), Sv.Z());
    const double g00 = a.dot(a), g01 = a.dot(b), g11 = b.dot(b);
    const double det = g00 * g11 - g01 * g01;
    if (!(det > 0.0)) break;
    const double ra = a.dot(r), rb = b.dot(r);
    const double du = (g11 * ra - g01 * rb) / det, dv = (g00 * rb - g01 * ra) / det;
    const double un = std::clamp(u + du, u0, u1), vn = std::clamp(v + dv, v0, v1);
    s->D1(un, vn, S, Su, Sv);
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

std::string occt_version() {
  return OCC_VERSION_COMPLETE;
}

}  // namespace plyfit::bench
