// Faces: validation, the boundary, the in/out test, evaluation and settling past a pole.
#include "surface/face.hpp"

#include "surface/poles.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace plyfit {

namespace {

// Samples per direction for the face's bounding box; a face smaller than this fraction of its
// control net's box is measured by the box (the samples may all lie on one point).
constexpr int kBoxSamples = 33;
constexpr double kMinSizeOfNet = 1e-6;
// A boundary segment shorter than this in 3D, relative to the face size, is a collapsed edge
// (a pole): no boundary of the face.
constexpr double kCollapsedRel = 1e-9;

// Drops each loop's repeated closing point (and the tag of the segment from it back to the
// start), then checks the loops: tags one per segment, at least 3 finite points.
Status normalise_loops(std::vector<TrimLoop>& loops) {
  for (std::size_t l = 0; l < loops.size(); ++l) {
    auto& loop = loops[l];
    const auto at = static_cast<std::int64_t>(l);
    if (loop.points.size() > 1 && loop.points.front() == loop.points.back()) {
      loop.points.pop_back();
      if (loop.edges.size() > loop.points.size()) loop.edges.pop_back();
    }
    if (!loop.edges.empty() && loop.edges.size() != loop.points.size())
      return Error{ErrorCode::kTrimLoopEdgeTags,
                   {},
                   {at, static_cast<std::int64_t>(loop.edges.size()),
                    static_cast<std::int64_t>(loop.points.size())}};
    if (loop.points.size() < 3) return Error{ErrorCode::kTrimLoopTooFewPoints, {}, {at}};
    for (const auto& p : loop.points)
      if (!p.allFinite()) return Error{ErrorCode::kTrimLoopNotFinite, {}, {at}};
  }
  return ok_status();
}

// True when every segment of the loop runs along the domain's border (both its ends on one
// side, to the parameter rounding): a natural boundary given as a loop (e.g. to tag a shell's
// shared edges), which bounds the whole domain, so that contains() needs only the domain test.
// Points alone do not tell: a loop cut from the domain by an isoparametric line has all its
// points on the border and a segment across it.
bool on_domain_border(const TrimLoop& loop, const ParamDomain& d, const Tolerances& tol) {
  const double eu = tol.param_rel * d.width_u(), ev = tol.param_rel * d.width_v();
  const auto sides = [&](const Vec2& p) {  // bit k: on side k (u0, u1, v0, v1)
    return (std::abs(p.x() - d.u0) <= eu ? 1 : 0) | (std::abs(p.x() - d.u1) <= eu ? 2 : 0) |
           (std::abs(p.y() - d.v0) <= ev ? 4 : 0) | (std::abs(p.y() - d.v1) <= ev ? 8 : 0);
  };
  const std::size_t n = loop.points.size();
  for (std::size_t i = 0; i < n; ++i)
    if ((sides(loop.points[i]) & sides(loop.points[(i + 1) % n])) == 0) return false;
  return true;
}

// The loop of largest (u, v) area: the outer one of a face with holes.
int largest_loop(const std::vector<TrimLoop>& loops) {
  int outer = -1;
  double best = -1.0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const double a = std::abs(signed_area(loops[l].points));
    if (a > best) {
      best = a;
      outer = static_cast<int>(l);
    }
  }
  return outer;
}

// The face's surface: the one its producer built when it was made from `data` and `tol` (so
// not built twice), else built here.
Result<std::shared_ptr<const NurbsSurface>> surface_of(FaceData& data, const Tolerances& tol) {
  if (data.built && data.built->made_from(data.surface, tol)) return std::move(data.built);
  auto surf = NurbsSurface::create(std::move(data.surface), tol);
  if (!surf) return surf.error();
  return std::make_shared<const NurbsSurface>(std::move(surf).value());
}

}  // namespace

Result<Face> Face::create(FaceData data, const Tolerances& tol) {
  auto surf = surface_of(data, tol);
  if (!surf) return surf.error();
  if (auto st = normalise_loops(data.loops); !st) return st.error();
  Face f;
  f.surface_ = std::move(surf).value();
  f.tol_ = tol;
  f.reversed_ = data.reversed;
  f.closed_u_ = data.closed_u;
  f.closed_v_ = data.closed_v;
  f.name_ = std::move(data.name);
  f.loops_ = std::move(data.loops);
  f.build_slabs();
  f.natural_ = f.loops_.size() == 1 && on_domain_border(f.loops_[0], f.domain(), tol);
  if (f.loops_.size() > 1) f.outer_ = largest_loop(f.loops_);
  if (auto st = f.measure(data.area); !st) return st.error();
  f.poles_ = detail::find_poles(f);
  return f;
}

Status Face::measure(double given_area) {
  // Bounding box from samples on the face (control boxes can be far larger).
  for (const auto& s : sample_face(*this, kBoxSamples)) bbox_.add(s.second);
  if (bbox_.empty) return Error{ErrorCode::kFaceEmpty};
  size_ = std::max(bbox_.diagonal(), surface_->control_bbox().diagonal() * kMinSizeOfNet);
  if (!(size_ > 0.0)) return Error{ErrorCode::kFaceZeroSize};
  area_ = given_area > 0.0 ? given_area : compute_area();
  return ok_status();
}

SurfaceLocation Face::settle(const SurfaceLocation& at, const Vec3& p, double reach) const {
  if (poles_.empty() || contains(at.uv)) return at;
  const Vec2 w = wrap(at.uv);
  for (const Pole& e : poles_) {
    // Only past this pole's collapsed edge: where Newton crossed the pole.
    const double past = e.u_fixed ? w.x() - e.at.uv.x() : w.y() - e.at.uv.y();
    if (past * e.inward >= 0.0) continue;
    const auto loc = detail::locate_through_pole(*this, e, p, tol_);
    if (!loc || !contains(loc->uv)) continue;
    const SurfaceEval1 ev = eval1(*loc);
    if (ev.ok && (ev.p - p).norm() <= reach) return {loc->uv, at.face};
  }
  return at;
}

std::vector<std::vector<Vec2>> Face::boundary_loops() const {
  std::vector<std::vector<Vec2>> out;
  if (loops_.empty()) {
    const auto& d = domain();
    out.push_back({Vec2(d.u0, d.v0), Vec2(d.u1, d.v0), Vec2(d.u1, d.v1), Vec2(d.u0, d.v1)});
    return out;
  }
  for (const auto& l : loops_) out.push_back(l.points);
  return out;
}

std::vector<BoundaryLoop> Face::boundary() const {
  std::vector<BoundaryLoop> out;
  const auto& d = domain();
  // On-seam test: rounding of the domain's bounds.
  const double eu = d.width_u() * tol_.param_rel, ev = d.width_v() * tol_.param_rel;
  auto on = [](double x, double y, double e) { return std::abs(x - y) <= e; };
  for (const auto& loop : boundary_loops()) {
    BoundaryLoop b;
    const size_t n = loop.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2 a = loop[k], c = loop[(k + 1) % n];
      b.points.emplace_back(a);
      BoundaryLoop::Kind kind = BoundaryLoop::kEdge;
      if ((closed_u_ && ((on(a.x(), d.u0, eu) && on(c.x(), d.u0, eu)) ||
                         (on(a.x(), d.u1, eu) && on(c.x(), d.u1, eu)))) ||
          (closed_v_ && ((on(a.y(), d.v0, ev) && on(c.y(), d.v0, ev)) ||
                         (on(a.y(), d.v1, ev) && on(c.y(), d.v1, ev))))) {
        kind = BoundaryLoop::kSeam;
      } else {
        const SurfaceEval1 ea = eval1(a), em = eval1(0.5 * (a + c)), ec = eval1(c);
        const double len = (em.p - ea.p).norm() + (ec.p - em.p).norm();
        if (ea.ok && em.ok && ec.ok && len <= kCollapsedRel * size_)
          kind = BoundaryLoop::kCollapsed;
      }
      b.kinds.push_back(kind);
    }
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace plyfit
