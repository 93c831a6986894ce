// A face's trims met with a ply boundary's region, in the face's (u, v).
#include "surface/bounded/bounded.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace plyfit::detail {

namespace {

// A point of the result lies on one of the face's own trim segments when it is this close to
// it, relative to the domain's width (the clipping's intersections are exact to rounding).
constexpr double kOnTrimRel = 1e-9;
// The region leaves the face whole (or takes none of it) when their areas agree to this,
// relative to the face's (u, v) area.
constexpr double kSameAreaRel = 1e-9;
// A point of a boundary loop farther than this from the face (relative to the face's size)
// lies off it: on another face of the shell.
constexpr double kOffFaceRel = 1e-6;

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
  // Repeated points first (projections clamped to the same corner): a corner repeated would
  // seem to lie between two points of one edge, each copy, and be lost.
  uv.erase(std::unique(uv.begin(), uv.end()), uv.end());
  while (uv.size() > 1 && uv.front() == uv.back()) uv.pop_back();
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

// Perimeter of a domain with no closed direction: position s in [0, 4) going round it
// counter-clockwise from (u0, v0), one unit a side.
struct Border {
  ParamDomain d;
  // The point of the border nearest q (in units of the domain's widths), as s.
  double place(const Vec2& q) const {
    const double x = std::clamp((q.x() - d.u0) / d.width_u(), 0.0, 1.0);
    const double y = std::clamp((q.y() - d.v0) / d.width_v(), 0.0, 1.0);
    const double to[4] = {y, 1.0 - x, 1.0 - y, x};  // bottom, right, top, left
    const int side = static_cast<int>(std::min_element(to, to + 4) - to);
    const double along[4] = {x, y, 1.0 - x, 1.0 - y};
    return side + along[side];
  }
  Vec2 at(double s) const {
    const int side = static_cast<int>(std::floor(s)) % 4;
    const double t = s - std::floor(s);
    const double x[4] = {t, 1.0, 1.0 - t, 0.0}, y[4] = {0.0, t, 1.0, 1.0 - t};
    return {d.u0 + x[side] * d.width_u(), d.v0 + y[side] * d.width_v()};
  }
  // The border's corners strictly between a and b, the shorter way round, in order.
  void corners_between(double a, double b, std::vector<Vec2>& out) const {
    double step = b - a;
    step -= 4.0 * std::round(step / 4.0);
    const int first =
        step > 0 ? static_cast<int>(std::floor(a)) + 1 : static_cast<int>(std::ceil(a)) - 1;
    for (int c = first; step > 0 ? c < a + step : c > a + step; c += step > 0 ? 1 : -1)
      out.push_back(at(static_cast<double>(((c % 4) + 4) % 4)));
  }
};

// The loop projected onto the face's surface, clamped to its domain and unwrapped across its
// seams (each point the copy nearest the one before). Where the loop runs off the face, the
// clamped projections lie on the domain's border only roughly (a projection onto a pole stalls
// short of it): on a face open both ways those points are put on the border and the corners
// they pass added, so that the region takes in the face up to its edges and poles.
std::vector<Vec2> loop_on_face(const Face& face, const MoldLoop& loop) {
  std::vector<Vec2> uv;
  uv.reserve(loop.points.size());
  const ParamDomain& d = face.domain();
  const bool open = !face.closed_u() && !face.closed_v();
  const Border border{d};
  const double off_face = kOffFaceRel * face.size();
  Vec2 seed = face.project(loop.points.front()).at.uv;
  std::optional<double> last_off;  // border place of the point before, when it was off the face
  for (const Vec3& p : loop.points) {
    const Projection pr = face.project_from(p, seed, false);
    Vec2 q = pr.ok ? pr.at.uv : seed;
    if (!uv.empty()) {
      if (face.closed_u()) q.x() -= d.width_u() * std::round((q.x() - uv.back().x()) / d.width_u());
      if (face.closed_v()) q.y() -= d.width_v() * std::round((q.y() - uv.back().y()) / d.width_v());
    }
    seed = face.wrap(q);
    if (open && (!pr.ok || pr.distance > off_face)) {
      const double s = border.place(q);
      if (last_off) border.corners_between(*last_off, s, uv);
      q = border.at(s);
      last_off = s;
    } else {
      last_off.reset();
    }
    uv.push_back(q);
  }
  return without_runs_on_edges(face, std::move(uv));
}

// A loop that winds round the face's closed direction `axis` (its unwrapped end a period or
// more from its start) is no polygon in (u, v): it is repeated over the periods the domain
// spans and closed along the open direction's near edge (v0 or u0; the far one when
// `far_side`), making the part of the face on that side of it. Two such loops make the band
// between them (even-odd); one makes a side, the near or the far.
bool close_winding(const Face& face, std::vector<Vec2>& uv, bool far_side) {
  const ParamDomain& d = face.domain();
  for (int axis = 0; axis < 2; ++axis) {
    const bool closed = axis == 0 ? face.closed_u() : face.closed_v();
    const bool other_open = axis == 0 ? !face.closed_v() : !face.closed_u();
    if (!closed || !other_open || uv.size() < 3) continue;
    const double period = axis == 0 ? d.width_u() : d.width_v();
    const double span = uv.back()[axis] - uv.front()[axis];
    const double turns = std::round(span / period);
    if (turns == 0.0) continue;
    const double step = turns * period;
    const int copies = static_cast<int>(std::ceil(3.0 / std::abs(turns))) + 1;
    std::vector<Vec2> out;
    out.reserve(uv.size() * static_cast<std::size_t>(2 * copies + 1) + 2);
    for (int k = -copies; k <= copies; ++k)
      for (const Vec2& p : uv) out.push_back(p + (k * step) * Vec2::Unit(axis));
    const int other = 1 - axis;
    const double edge = other == 1 ? (far_side ? d.v1 : d.v0) : (far_side ? d.u1 : d.u0);
    Vec2 a = out.back(), b = out.front();
    a[other] = edge;
    b[other] = edge;
    out.push_back(a);
    out.push_back(b);
    uv = std::move(out);
    return true;
  }
  return false;
}

// The region of the loops on the face, with its copies a period away across closed seams.
Region2 loops_region(const Face& face, const std::vector<MoldLoop>& loops, bool far_side,
                     bool& winding) {
  Region2 r, wound;  // wound: closed along an edge, spanning the periods already
  for (const auto& loop : loops) {
    std::vector<Vec2> uv = loop_on_face(face, loop);
    const bool winds = close_winding(face, uv, far_side);
    winding = winding || winds;
    (winds ? wound : r).push_back(std::move(uv));
  }
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
  // Even-odd over all loops: the list of both is their symmetric difference.
  r.insert(r.end(), wound.begin(), wound.end());
  return r;
}

// The shared edge of the face's own trim segments that point p lies on (within eps), or
// kFreeEdge; a point where two edges meet is on `want` when one of them is want.
std::int32_t edge_at(const Face& face, const Vec2& p, double eps, std::int32_t want) {
  std::int32_t found = TrimLoop::kFreeEdge;
  for (const TrimLoop& loop : face.loops()) {
    if (loop.edges.empty()) continue;
    const std::size_t n = loop.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (segment_distance(p, loop.points[i], loop.points[(i + 1) % n]) > eps) continue;
      if (loop.edges[i] == want) return want;
      found = loop.edges[i];
    }
  }
  return found;
}

// The tag of segment a -> b: the shared edge it runs along. The clipping may join several of
// the face's own collinear trim segments into one (where the region's loop runs along the
// same domain edge), so the segment's ends and middle are each tested against the edge's
// polyline, not against one of its segments.
std::int32_t tag_of(const Face& face, const Vec2& a, const Vec2& b, double eps) {
  const std::int32_t e = edge_at(face, 0.5 * (a + b), eps, TrimLoop::kFreeEdge);
  if (e == TrimLoop::kFreeEdge) return e;
  return edge_at(face, a, eps, e) == e && edge_at(face, b, eps, e) == e ? e : TrimLoop::kFreeEdge;
}

}  // namespace

FaceCut cut_face(const Face& face, const std::vector<MoldLoop>& loops, const Tolerances&,
                 bool far_side) {
  const Region2 own = face.boundary_loops();
  FaceCut out;
  const Region2 cut = intersect_regions(own, loops_region(face, loops, far_side, out.winding));
  const double whole = region_area(own), part = region_area(cut);
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
