// Boundary curves as closed loops on the mold: chained end to end, divided, projected, offset.
#include "surface/bounded/bounded.hpp"
#include "surface/shell/shell.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace plyfit::detail {

namespace {

// Probes that decide which side of a loop its region lies on (offset_loops): how many points
// of the loop vote, and how far across it (relative to the loop's mean segment) they look.
constexpr int kSideVotes = 9;
constexpr double kSideProbeSegments = 0.5;
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

void offset_loops(const MoldSurface& mold, std::vector<MoldLoop>& loops, double offset,
                  const std::function<bool(const Vec3&)>& inside) {
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
    int left_inside = 0;
    for (int k = 0; k < kSideVotes; ++k) {
      const std::size_t i = (static_cast<std::size_t>(k) * n) / kSideVotes;
      left_inside += inside(loop.points[i] + probe * across[i]) ? 1 : -1;
    }
    // Growing moves away from the region.
    const double sign = left_inside > 0 ? -1.0 : 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Projection pr = mold.project(loop.points[i] + sign * offset * across[i]);
      if (pr.ok) loop.points[i] = pr.point;
    }
  }
}

}  // namespace plyfit::detail
