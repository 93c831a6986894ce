// Boundary curves as closed loops on the mold: chained end to end, divided, projected, offset.
#include "surface/bounded/bounded.hpp"
#include "surface/shell/shell.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <string>

namespace plyfit::detail {

namespace {

// Probes that decide which side of a loop its region lies on (offset_loops): how many points
// of the loop vote, and how far across it (relative to the loop's mean segment) they look.
constexpr int kSideVotes = 9;
constexpr double kSideProbeSegments = 0.5;
// A probe point lies on the mold when within this share of the probe's length of it (the
// surface's curvature puts a point of the tangent plane at about k probe^2 / 2).
constexpr double kSideProbeReach = 0.25;
// Two segments of an offset loop cross where they come within this share of its mean segment
// (both lie on the mold: crossing chords of a curved surface pass at about k L^2 / 8).
constexpr double kCrossingTouch = 0.05;
// An offset point lies on the mold when its projection is within this share of the offset (a
// point of the tangent plane lies about k offset^2 / 2 off a surface of curvature k).
constexpr double kOffsetOnMold = 0.25;
// A boundary point is projected from the previous one's place on its face when it lies this
// close to that face (relative to the mold's size: on it, to a chord's sagitta), else onto the
// whole mold (which samples every face).
constexpr double kOnFaceRel = 1e-5;

const Face* face_of(const MoldSurface& mold, std::int32_t k) {
  if (const auto* f = dynamic_cast<const Face*>(&mold.impl())) return f;
  if (const auto* sh = dynamic_cast<const Shell*>(&mold.impl())) return &sh->face(k);
  return nullptr;
}

// p projected onto the mold, continued from the previous point's projection where it can be.
Projection project_near(const MoldSurface& mold, const Vec3& p, const Projection& prev,
                        double close) {
  if (prev.ok)
    if (const Face* f = face_of(mold, prev.at.face)) {
      Projection q = f->project_from(p, prev.at.uv, true);
      if (q.ok && q.distance <= close) {
        q.at.face = prev.at.face;
        return q;
      }
    }
  return mold.project(p);
}

std::string point_text(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.6g, %.6g, %.6g", p.x(), p.y(), p.z());
  return buf;
}

Status check_curve(const BoundaryCurve& c) {
  bool finite = true;
  for (const Vec3& p : c.points) finite = finite && p.allFinite();
  const std::size_t need = c.closed ? 3 : 2;
  if (!finite || c.points.size() < need)
    return Error{ErrorCode::kBoundaryCurvePoints,
                 "boundary",
                 {c.name, static_cast<std::int64_t>(c.points.size()), finite ? 1.0 : 0.0}};
  return ok_status();
}

// Appends curve k to the chain, reversed when `reversed`, without a first point that repeats
// the chain's last (within `gap`: CAD curves meet to their modelling tolerance, not exactly).
void append(MoldLoop& chain, const BoundaryCurve& c, int k, bool reversed, double gap) {
  const std::size_t n = c.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = c.points[reversed ? n - 1 - i : i];
    if (i == 0 && !chain.points.empty() && (p - chain.points.back()).norm() <= gap) continue;
    chain.points.push_back(p);
    chain.curve.push_back(k);
  }
}

// Drops a last point that repeats the first (within `gap`).
void drop_closing_point(MoldLoop& loop, double gap) {
  if (loop.points.size() > 2 && (loop.points.front() - loop.points.back()).norm() <= gap) {
    loop.points.pop_back();
    loop.curve.pop_back();
  }
}

// Chains the open curve `first` with the unused open curves until it closes on itself.
Result<MoldLoop> chain_from(const PlyBoundary& b, int first, std::vector<bool>& used, double gap) {
  MoldLoop chain;
  append(chain, b.curves[static_cast<std::size_t>(first)], first, false, gap);
  used[static_cast<std::size_t>(first)] = true;
  for (std::size_t step = 0; step <= b.curves.size(); ++step) {
    const Vec3 end = chain.points.back();
    double best = std::numeric_limits<double>::infinity();
    int next = -1;
    bool reversed = false;
    for (std::size_t k = 0; k < b.curves.size(); ++k) {
      const auto& c = b.curves[k];
      if (used[k] || c.closed) continue;
      const double df = (c.points.front() - end).norm(), db = (c.points.back() - end).norm();
      if (std::min(df, db) < best) {
        best = std::min(df, db);
        next = static_cast<int>(k);
        reversed = db < df;
      }
    }
    const double close = (chain.points.front() - end).norm();
    if (close <= gap && close <= best) {
      drop_closing_point(chain, gap);
      return chain;
    }
    if (best > gap) {
      const int at = chain.curve.back();
      return Error{ErrorCode::kBoundaryGap,
                   "boundary",
                   {b.curves[static_cast<std::size_t>(at)].name, point_text(end),
                    std::min(best, close), gap}};
    }
    append(chain, b.curves[static_cast<std::size_t>(next)], next, reversed, gap);
    used[static_cast<std::size_t>(next)] = true;
  }
  return Error{ErrorCode::kInternal};
}

}  // namespace

Result<std::vector<MoldLoop>> chain_curves(const PlyBoundary& boundary, double gap) {
  if (boundary.curves.empty()) return Error{ErrorCode::kBoundaryEmpty, "boundary"};
  for (const auto& c : boundary.curves)
    if (auto st = check_curve(c); !st) return st.error();
  std::vector<MoldLoop> loops;
  std::vector<bool> used(boundary.curves.size(), false);
  for (std::size_t k = 0; k < boundary.curves.size(); ++k) {
    const auto& c = boundary.curves[k];
    const bool ends_meet = (c.points.front() - c.points.back()).norm() <= gap;
    if (!c.closed && !(ends_meet && c.points.size() > 3)) continue;
    MoldLoop loop;
    append(loop, c, static_cast<int>(k), false, gap);
    drop_closing_point(loop, gap);
    used[k] = true;
    loops.push_back(std::move(loop));
  }
  for (std::size_t k = 0; k < boundary.curves.size(); ++k) {
    if (used[k]) continue;
    auto loop = chain_from(boundary, static_cast<int>(k), used, gap);
    if (!loop) return loop.error();
    loops.push_back(std::move(loop).value());
  }
  return loops;
}

void densify(MoldLoop& loop, double step) {
  MoldLoop out;
  const std::size_t n = loop.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = loop.points[i], b = loop.points[(i + 1) % n];
    const int parts = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int j = 0; j < parts; ++j) {
      out.points.push_back(a + (b - a) * (static_cast<double>(j) / parts));
      out.curve.push_back(loop.curve[i]);
    }
  }
  loop = std::move(out);
}

Status project_loops(const MoldSurface& mold, const PlyBoundary& boundary,
                     std::vector<MoldLoop>& loops, double reach) {
  const double close = kOnFaceRel * mold.size();
  for (auto& loop : loops) {
    Projection prev;
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      const Projection pr = project_near(mold, loop.points[i], prev, close);
      prev = pr;
      const auto& c = boundary.curves[static_cast<std::size_t>(loop.curve[i])];
      if (!pr.ok || !(pr.distance <= reach))
        return Error{ErrorCode::kBoundaryOffMold,
                     "boundary",
                     {c.name, pr.ok ? pr.distance : -1.0, reach, point_text(loop.points[i])}};
      loop.points[i] = pr.point;
    }
  }
  return ok_status();
}

namespace {

// The closest points of segments p0 p1 and q0 q1, at p0 + s (p1 - p0) and q0 + t (q1 - q0).
struct ClosestPair {
  double s = 0.0, t = 0.0, distance = INFINITY;
};
ClosestPair closest(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), den = a * e - b * b;
  ClosestPair out;
  if (!(a > 0.0) || !(e > 0.0)) return out;
  out.s = den > 0.0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  out.t = (b * out.s + f) / e;
  if (out.t < 0.0 || out.t > 1.0) {
    out.t = std::clamp(out.t, 0.0, 1.0);
    out.s = std::clamp((b * out.t - c) / a, 0.0, 1.0);
  }
  out.distance = ((p0 + out.s * d1) - (q0 + out.t * d2)).norm();
  return out;
}

// The first crossing of two segments of the loop that share no point (i < j: segments i and
// j), the segments found through a grid of cells `cell` wide.
std::optional<std::pair<std::size_t, std::size_t>> first_crossing(const MoldLoop& loop, double cell,
                                                                  double touch, Vec3& at) {
  const std::size_t n = loop.points.size();
  const auto key = [cell](const Vec3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / cell)),
                                    static_cast<long long>(std::floor(p.y() / cell)),
                                    static_cast<long long>(std::floor(p.z() / cell))};
  };
  std::map<std::array<long long, 3>, std::vector<std::size_t>> grid;
  for (std::size_t i = 0; i < n; ++i)
    grid[key(0.5 * (loop.points[i] + loop.points[(i + 1) % n]))].push_back(i);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 &p0 = loop.points[i], &p1 = loop.points[(i + 1) % n];
    const auto k = key(0.5 * (p0 + p1));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (std::size_t j : it->second) {
            if (j <= i + 1 || (i == 0 && j == n - 1)) continue;
            const ClosestPair c = closest(p0, p1, loop.points[j], loop.points[(j + 1) % n]);
            if (c.distance <= touch && c.s > 0.0 && c.s < 1.0 && c.t > 0.0 && c.t < 1.0) {
              at = p0 + c.s * (p1 - p0);
              return std::make_pair(i, j);
            }
          }
        }
  }
  return std::nullopt;
}

// Where a loop moved across itself crosses itself (the swallowtail an offset makes past a
// corner, inward past a convex one or outward past a concave one), the shorter of the two
// loops the crossing makes is cut out: what is left is the offset region's boundary.
void remove_self_crossings(MoldLoop& loop) {
  const std::size_t n0 = loop.points.size();
  if (n0 < 4) return;
  double longest = 0.0, length = 0.0;
  for (std::size_t i = 0; i < n0; ++i) {
    const double l = (loop.points[(i + 1) % n0] - loop.points[i]).norm();
    longest = std::max(longest, l);
    length += l;
  }
  const double touch = kCrossingTouch * length / static_cast<double>(n0);
  Vec3 at;
  for (std::size_t round = 0; round < n0 && loop.points.size() >= 4; ++round) {
    const auto hit = first_crossing(loop, 2.0 * longest + touch, touch, at);
    if (!hit) return;
    const auto [i, j] = *hit;
    const std::size_t n = loop.points.size();
    MoldLoop out;
    if (j - i <= n / 2) {  // cut out points i + 1 .. j
      for (std::size_t k = 0; k < n; ++k) {
        if (k > i && k <= j) continue;
        out.points.push_back(loop.points[k]);
        out.curve.push_back(loop.curve[k]);
        if (k == i) {
          out.points.push_back(at);
          out.curve.push_back(loop.curve[i]);
        }
      }
    } else {  // keep points i + 1 .. j only
      out.points.push_back(at);
      out.curve.push_back(loop.curve[i]);
      for (std::size_t k = i + 1; k <= j; ++k) {
        out.points.push_back(loop.points[k]);
        out.curve.push_back(loop.curve[k]);
      }
    }
    loop = std::move(out);
  }
}

}  // namespace

void offset_loops(const MoldSurface& mold, std::vector<MoldLoop>& loops, double offset,
                  const std::function<bool(const Vec3&, double)>& inside) {
  for (auto& loop : loops) {
    const std::size_t n = loop.points.size();
    // Across the loop, to its left seen from outside: normal x tangent.
    std::vector<Vec3> across(n);
    double length = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 t = loop.points[(i + 1) % n] - loop.points[(i + n - 1) % n];
      const Projection pr = mold.project(loop.points[i]);
      const Vec3 nrm = mold.normal(pr.at).n;
      across[i] = nrm.cross(t).normalized();
      if (!across[i].allFinite()) across[i] = Vec3::Zero();
      length += (loop.points[(i + 1) % n] - loop.points[i]).norm();
    }
    const double probe = kSideProbeSegments * length / static_cast<double>(n);
    // Each vote probes both sides: a side past the mold's edge (a loop along the edge) is in
    // the region on neither, so the side that is decides.
    int left_inside = 0;
    for (int k = 0; k < kSideVotes; ++k) {
      const std::size_t i = (static_cast<std::size_t>(k) * n) / kSideVotes;
      const double reach = kSideProbeReach * probe;
      const bool left = inside(loop.points[i] + probe * across[i], reach);
      const bool right = inside(loop.points[i] - probe * across[i], reach);
      left_inside += left == right ? 0 : (left ? 1 : -1);
    }
    // Growing moves away from the region.
    const double sign = left_inside > 0 ? -1.0 : 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      // A point moved past the mold's edge stays where it is: the faces' cuts clip the loop to
      // the mold (projected onto its edge, it would make the loop double back along it).
      const Vec3 moved = loop.points[i] + sign * offset * across[i];
      const Projection pr = mold.project(moved);
      loop.points[i] = pr.ok && pr.distance <= kOffsetOnMold * std::abs(offset) ? pr.point : moved;
    }
    remove_self_crossings(loop);
  }
}

}  // namespace plyfit::detail
