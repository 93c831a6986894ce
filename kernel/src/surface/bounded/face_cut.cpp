// A face's trims met with a ply boundary's region, in the face's (u, v).
#include "surface/bounded/bounded.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <cmath>

namespace plyfit::detail {

namespace {

// A point of the result lies on one of the face's own trim segments when it is this close to
// it, relative to the domain's width (the clipping's intersections are exact to rounding).
constexpr double kOnTrimRel = 1e-9;
// The region leaves the face whole (or takes none of it) when their areas agree to this,
// relative to the face's (u, v) area.
constexpr double kSameAreaRel = 1e-9;

// True when a and b lie on one edge of the face's domain (clamped there by the projection:
// their coordinate equals the edge's exactly), across an open direction.
bool on_one_edge(const Face& face, const Vec2& a, const Vec2& b) {
  const ParamDomain& d = face.domain();
  const bool u = !face.closed_u() && a.x() == b.x() && (a.x() == d.u0 || a.x() == d.u1);
  const bool v = !face.closed_v() && a.y() == b.y() && (a.y() == d.v0 || a.y() == d.v1);
  return u || v;
}

// The loop without the inner points of its runs along one domain edge: where the loop leaves
// the face its points are clamped onto the domain's edges, and those runs (most of the loop on
// a face of a shell the loop only crosses) add nothing to the region within the face but
// collinear overlaps with the face's own boundary, the costliest case of the clipping.
std::vector<Vec2> without_runs_on_edges(const Face& face, std::vector<Vec2> uv) {
  const std::size_t n = uv.size();
  if (n < 4) return uv;
  std::vector<Vec2> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &prev = uv[(i + n - 1) % n], &next = uv[(i + 1) % n];
    if (on_one_edge(face, prev, uv[i]) && on_one_edge(face, uv[i], next) &&
        on_one_edge(face, prev, next))
      continue;
    out.push_back(uv[i]);
  }
  return out.size() >= 3 ? out : uv;
}

// The loop projected onto the face's surface, clamped to its domain and unwrapped across its
// seams (each point the copy nearest the one before).
std::vector<Vec2> loop_on_face(const Face& face, const MoldLoop& loop) {
  std::vector<Vec2> uv;
  uv.reserve(loop.points.size());
  const ParamDomain& d = face.domain();
  Vec2 seed = face.project(loop.points.front()).at.uv;
  for (const Vec3& p : loop.points) {
    const Projection pr = face.project_from(p, seed, false);
    Vec2 q = pr.ok ? pr.at.uv : seed;
    if (!uv.empty()) {
      if (face.closed_u()) q.x() -= d.width_u() * std::round((q.x() - uv.back().x()) / d.width_u());
      if (face.closed_v()) q.y() -= d.width_v() * std::round((q.y() - uv.back().y()) / d.width_v());
    }
    uv.push_back(q);
    seed = face.wrap(q);
  }
  return without_runs_on_edges(face, std::move(uv));
}

// The region of the loops on the face, with its copies a period away across closed seams.
Region2 loops_region(const Face& face, const std::vector<MoldLoop>& loops) {
  Region2 r;
  for (const auto& loop : loops) r.push_back(loop_on_face(face, loop));
  const ParamDomain& d = face.domain();
  for (int axis = 0; axis < 2; ++axis) {
    const bool closed = axis == 0 ? face.closed_u() : face.closed_v();
    if (!closed) continue;
    const double period = axis == 0 ? d.width_u() : d.width_v();
    Region2 shifted;
    for (double s : {-period, period})
      for (auto loop : r) {
        for (Vec2& p : loop) p[axis] += s;
        shifted.push_back(std::move(loop));
      }
    // The copies overlap the original nowhere a loop does not wind round the seam.
    r = unite_regions(r, shifted);
  }
  return r;
}

// The tag of segment a -> b: the shared edge of the face's own trim segment it lies on.
std::int32_t tag_of(const Face& face, const Vec2& a, const Vec2& b, double eps) {
  for (const TrimLoop& loop : face.loops()) {
    const std::size_t n = loop.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 &p = loop.points[i], &q = loop.points[(i + 1) % n];
      if (segment_distance(a, p, q) <= eps && segment_distance(b, p, q) <= eps)
        return loop.edges.empty() ? TrimLoop::kFreeEdge : loop.edges[i];
    }
  }
  return TrimLoop::kFreeEdge;
}

}  // namespace

FaceCut cut_face(const Face& face, const std::vector<MoldLoop>& loops, const Tolerances&) {
  const Region2 own = face.boundary_loops();
  const Region2 cut = intersect_regions(own, loops_region(face, loops));
  const double whole = region_area(own), part = region_area(cut);
  FaceCut out;
  if (part <= kSameAreaRel * whole) {
    out.kind = FaceCut::kNone;
    return out;
  }
  if (part >= (1.0 - kSameAreaRel) * whole) return out;
  out.kind = FaceCut::kPart;
  out.area = boundary_area(face.surface(), cut);
  const ParamDomain& d = face.domain();
  const double eps = kOnTrimRel * std::max(d.width_u(), d.width_v());
  const bool tagged = !face.loops().empty();
  for (const auto& points : cut) {
    TrimLoop t;
    t.points = points;
    if (tagged) {
      const std::size_t n = points.size();
      for (std::size_t i = 0; i < n; ++i)
        t.edges.push_back(tag_of(face, points[i], points[(i + 1) % n], eps));
    }
    out.loops.push_back(std::move(t));
  }
  return out;
}

}  // namespace plyfit::detail
