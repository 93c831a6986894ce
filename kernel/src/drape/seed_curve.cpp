// A seed curve given as a polyline (seed_curve.hpp): projected onto the surface, then walked
// at link length.
#include "drape/seed_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace plyfit::detail {

namespace {

std::string where(const Vec3& p) {
  std::ostringstream os;
  os << p.x() << "," << p.y() << "," << p.z();
  return os.str();
}

// The place on segment a-b nearest p.
double nearest_t(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 e = b - a;
  const double ee = e.squaredNorm();
  return ee > 0.0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
}

// The parameter s in [s0, 1] where the segment a + s (b - a), inside the sphere of radius r
// about c at s0, leaves it (the larger root of |a + s e - c| = r); none when it stays inside.
std::optional<double> exit_root(const Vec3& a, const Vec3& b, const Vec3& c, double r, double s0) {
  const Vec3 e = b - a, w = a - c;
  const double ee = e.squaredNorm();
  if (!(ee > 0.0)) return std::nullopt;
  const double half_b = w.dot(e), cc = w.squaredNorm() - r * r;
  const double disc = half_b * half_b - ee * cc;
  if (disc < 0.0) return std::nullopt;
  const double s = (-half_b + std::sqrt(disc)) / ee;
  if (s < s0 || s > 1.0) return std::nullopt;
  return s;
}

}  // namespace

Result<SeedPolyline> SeedPolyline::create(const DrapeSurface& s, const DrapeProblem& pb,
                                          const Vec3& start, const Tolerances& tol) {
  const double limit = tol.seed_curve_rel * s.size();
  SeedPolyline c;
  c.closed_ = pb.seed_polyline_closed;
  for (const Vec3& p : pb.seed_polyline) {
    if (!p.allFinite())
      return Error{
          ErrorCode::kBoundaryCurvePoints, "seed-curve", {"(seed curve)", std::int64_t{0}, 0.0}};
    const Projection pr = s.project(p);
    if (!pr.ok || pr.distance > limit)
      return Error{
          ErrorCode::kSeedCurveOffMold,
          "seed-curve",
          {pr.ok ? pr.distance : std::numeric_limits<double>::infinity(), limit, where(p)}};
    c.p_.push_back(pr.point);
  }
  if (c.closed_ && c.p_.size() > 2 && (c.p_.back() - c.p_.front()).norm() <= limit)
    c.p_.pop_back();  // a closed curve that repeats its first point
  if (c.p_.size() < 2)
    return Error{ErrorCode::kBoundaryCurvePoints,
                 "seed-curve",
                 {"(seed curve)", static_cast<std::int64_t>(c.p_.size()), 1.0}};
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < c.segments(); ++k) {
    const double t = nearest_t(c.vertex(k), c.vertex(k + 1), start);
    const double dist = (c.point({k, t}) - start).norm();
    if (dist < best) {
      best = dist;
      c.start_ = {k, t};
    }
  }
  if (best > limit) return Error{ErrorCode::kSeedNotOnCurve, "seed-curve", {best, limit}};
  return c;
}

Vec3 SeedPolyline::point(const CurvePlace& at) const {
  return vertex(at.seg) + at.t * (vertex(at.seg + 1) - vertex(at.seg));
}

Vec3 SeedPolyline::tangent(const CurvePlace& at) const {
  // The segment at `at`, else the nearest one of non-zero length after it.
  for (std::size_t k = 0; k < segments(); ++k) {
    const std::size_t seg = (at.seg + k) % segments();
    const Vec3 e = vertex(seg + 1) - vertex(seg);
    if (e.norm() > 0.0) return e.normalized();
  }
  return Vec3::Zero();
}

std::optional<std::pair<Vec3, CurvePlace>> SeedPolyline::at_distance(const CurvePlace& at,
                                                                     const Vec3& centre,
                                                                     double rest,
                                                                     bool forward) const {
  const std::size_t n = segments();
  CurvePlace here = at;
  // Each segment once: a closed curve once round.
  for (std::size_t k = 0; k <= n; ++k) {
    const Vec3 a = vertex(here.seg), b = vertex(here.seg + 1);
    const auto s = forward ? exit_root(a, b, centre, rest, here.t)
                           : exit_root(b, a, centre, rest, 1.0 - here.t);
    if (s) {
      const CurvePlace got{here.seg, forward ? *s : 1.0 - *s};
      return std::make_pair(point(got), got);
    }
    if (forward) {
      if (here.seg + 1 >= n && !closed_) return std::nullopt;
      here = {(here.seg + 1) % n, 0.0};
    } else {
      if (here.seg == 0 && !closed_) return std::nullopt;
      here = {(here.seg + n - 1) % n, 1.0};
    }
  }
  return std::nullopt;
}

}  // namespace plyfit::detail
