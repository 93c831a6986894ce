// A start for a drape of one face (optimize.hpp: face_start).
#include "surface/face.hpp"

#include <plyfit/kernel/optimize.hpp>

#include <cmath>
#include <limits>

namespace plyfit {

namespace {

// The uv grid searched for a point inside the trims when the centre is not (per direction).
constexpr int kFaceSearchGrid = 129;
// Below this fraction of |S_v|, S_u is taken for a collapsed edge (a pole): the base path then
// runs along v.
constexpr double kCollapsedTangentRel = 1e-9;

}  // namespace

Result<FaceStart> face_start(const MoldSurface& surface) {
  const auto* one = dynamic_cast<const Face*>(&surface.impl());
  if (!one) return Error{ErrorCode::kStartNeedsOneFace};
  const Face& face = *one;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& loop : face.boundary_loops())
    for (const Vec2& q : loop) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  if (!(lo.x() <= hi.x() && lo.y() <= hi.y())) return Error{ErrorCode::kStartFaceNoBoundary};
  const Vec2 centre = 0.5 * (lo + hi);
  Vec2 span = hi - lo;
  for (int a = 0; a < 2; ++a)
    if (!(span[a] > 0)) span[a] = 1.0;
  FaceStart s;
  s.uv = centre;
  if (!face.contains(centre)) {
    // The contained grid point nearest the centre (distances in fractions of the span).
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kFaceSearchGrid; ++i)
      for (int j = 0; j < kFaceSearchGrid; ++j) {
        const Vec2 q = lo + Vec2((i + 0.5) / kFaceSearchGrid * span.x(),
                                 (j + 0.5) / kFaceSearchGrid * span.y());
        const double d = (q - centre).cwiseQuotient(span).norm();
        if (d < best && face.contains(q)) {
          best = d;
          s.uv = q;
        }
      }
    if (!std::isfinite(best)) return Error{ErrorCode::kStartFaceNoInsidePoint};
  }
  const SurfaceEval1 e = face.eval1(s.uv);
  s.point = e.p;
  s.normal = face.normal(s.uv).n;
  // The base path along u, on the tangent plane; along v where u degenerates, or where the
  // face closes round along u only (a full cylinder or tube): a path round the face comes
  // back onto its own start and leaves a slit, a path across it lets both sweeps go round.
  const bool across_closed_u = face.closed_u() && !face.closed_v();
  Vec3 t = e.du.norm() > e.dv.norm() * kCollapsedTangentRel && !across_closed_u ? e.du : e.dv;
  t -= t.dot(s.normal) * s.normal;
  if (!(t.norm() > 0)) return Error{ErrorCode::kStartFaceNoTangent};
  s.tangent = t.normalized();
  // (t, n x t) turns about +n like (base2d, sweep2d) = ((1, 0), (0, 1)) about +z.
  s.base_normal = s.normal.cross(s.tangent).normalized();
  return s;
}

}  // namespace plyfit
