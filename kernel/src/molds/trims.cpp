// The trims of the built-in molds: exact curves in (u, v) sampled into the polylines a face's
// loops are.
#include "molds/builtin.hpp"

#include "geometry/analytic_surfaces.hpp"
#include "geometry/bspline_basis.hpp"
#include "surface/face.hpp"

#include <cstdint>
#include <functional>

namespace plyfit::detail {

namespace {

/// Trim polylines: a chord is halved at most this many times (2^20 pieces of a knot span is
/// far below any tolerance reachable in double precision).
constexpr int kMaxTrimRefineDepth = 20;
/// Interior fractions of a trim chord where its distance from the curve is measured.
constexpr double kTrimChordFractions[3] = {0.25, 0.5, 0.75};

// Samples the curves of loop l as a polyline whose chords' surface images lie within tol3d of
// the surface images of the curves (checked at interior fractions, chords halved until they
// do).
Result<TrimLoop> sample_loop(const NurbsSurface& surface,
                             const std::vector<NurbsCurveData2>& curves, double tol3d,
                             std::size_t l) {
  TrimLoop loop;
  for (const auto& data : curves) {
    auto curve = NurbsCurve2::create(data);
    if (!curve) return Error{ErrorCode::kBuiltinTrimCurve}.because(curve.error());
    const auto at = [&](double t) { return Vec2(curve->point(t)); };
    const auto on_surface = [&](const Vec2& uv) { return surface.point(uv.x(), uv.y()); };
    const std::vector<double> ts = breakpoints(data.knots, curve->t0(), curve->t1());
    const std::function<void(double, const Vec2&, double, const Vec2&, int)> refine =
        [&](double t0, const Vec2& p0, double t1, const Vec2& p1, int depth) {
          double err = 0.0;
          for (double f : kTrimChordFractions)
            err = std::max(
                err, (on_surface(at(t0 + f * (t1 - t0))) - on_surface(p0 + f * (p1 - p0))).norm());
          if (err > tol3d && depth < kMaxTrimRefineDepth) {
            const double tm = 0.5 * (t0 + t1);
            const Vec2 pm = at(tm);
            refine(t0, p0, tm, pm, depth + 1);
            refine(tm, pm, t1, p1, depth + 1);
          } else {
            loop.points.push_back(p1);
          }
        };
    Vec2 p = at(ts.front());
    if (loop.points.empty()) loop.points.push_back(p);
    for (size_t k = 0; k + 1 < ts.size(); ++k) {
      const Vec2 q = at(ts[k + 1]);
      refine(ts[k], p, ts[k + 1], q, 0);
      p = q;
    }
  }
  loop.points.pop_back();  // the loop's end is its start
  if (loop.points.size() < 3)
    return Error{ErrorCode::kTrimLoopTooFewPoints, {}, {static_cast<std::int64_t>(l)}};
  return loop;
}

}  // namespace

// Sampled once against the untrimmed face's size, then again against the trimmed face's
// (smaller) size.
Status sample_trims(BuiltinFace& b, const Tolerances& tol) {
  if (b.exact_loops.empty()) return ok_status();
  auto surface = NurbsSurface::create(b.face.surface, tol);
  if (!surface) return surface.error();
  FaceData probe = b.face;
  probe.area = 1.0;  // only the size is needed here: no area integration (a second or more on
                     // a trimmed face of many spans)
  for (int pass = 0; pass < 2; ++pass) {
    auto face = Face::create(probe, tol);
    if (!face) return face.error();
    const double tol3d = tol.trim_chord_rel * face->size();
    probe.loops.clear();
    for (std::size_t l = 0; l < b.exact_loops.size(); ++l) {
      auto loop = sample_loop(*surface, b.exact_loops[l], tol3d, l);
      if (!loop) return loop.error();
      probe.loops.push_back(std::move(loop).value());
    }
  }
  b.face.loops = std::move(probe.loops);
  return ok_status();
}

std::vector<NurbsCurveData2> polygon_curves(const std::vector<Vec2>& corners) {
  std::vector<NurbsCurveData2> loop;
  for (size_t k = 0; k < corners.size(); ++k)
    loop.push_back(line2(corners[k], corners[(k + 1) % corners.size()]));
  return loop;
}

}  // namespace plyfit::detail
