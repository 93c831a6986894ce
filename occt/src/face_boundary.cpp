#include "face_measure_parts.hpp"

#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <gp_Ax2d.hxx>

#include <algorithm>
#include <vector>

namespace plyfit::importers::occt {

std::vector<TopoDS_Edge> ordered_edges(const TopoDS_Wire& w, const TopoDS_Face& f) {
  std::vector<TopoDS_Edge> edges;
  int count = 0;
  for (TopoDS_Iterator it(w); it.More(); it.Next()) ++count;
  for (BRepTools_WireExplorer we(w, f); we.More(); we.Next()) edges.push_back(we.Current());
  if (static_cast<int>(edges.size()) == count) return edges;
  // The explorer could not chain every edge (a wire OpenCASCADE finds ill-connected): keep the
  // stored order, which readers write along the wire.
  edges.clear();
  for (TopoDS_Iterator it(w); it.More(); it.Next())
    if (it.Value().ShapeType() == TopAbs_EDGE) edges.push_back(TopoDS::Edge(it.Value()));
  return edges;
}

namespace measure {

namespace {

// Samples per smooth interval of a pcurve searched for crossings of knot lines, and the
// bisection steps that locate a crossing (to the last bits of the parameter).
constexpr int kCrossingSamples = 16;
constexpr int kBisectionSteps = 60;

// Appends the straight (u, v) segment from `a` to `b` as a boundary edge, unless they coincide.
void add_segment(const gp_Pnt2d& a, const gp_Pnt2d& b, std::vector<EdgeRef>& edges,
                 std::vector<std::pair<double, double>>& ranges) {
  const double length = a.Distance(b);
  if (!(length > 0.0)) return;
  edges.push_back(EdgeRef{new Geom2d_Line(a, gp_Dir2d(b.X() - a.X(), b.Y() - a.Y())), 1.0});
  ranges.emplace_back(0.0, length);
}

}  // namespace

void split_at_crossings(const Handle(Geom2d_Curve) & c, double a, double b, const Breaks& ub,
                        const Breaks& vb, int edge, std::vector<Segment>& out) {
  std::vector<double> cuts{a, b};
  Geom2dAdaptor_Curve ad(c, a, b);
  const int nint = ad.NbIntervals(GeomAbs_C2);
  if (nint > 1) {
    TColStd_Array1OfReal iv(1, nint + 1);
    ad.Intervals(iv, GeomAbs_C2);
    for (int k = 2; k <= nint; ++k) cuts.push_back(iv(k));
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> all, found;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double t0 = cuts[k], t1 = cuts[k + 1];
    if (!(t1 > t0)) continue;
    all.push_back(t0);
    gp_Pnt2d prev = c->Value(t0);
    double tp = t0;
    for (int i = 1; i <= kCrossingSamples; ++i) {
      const double t = i == kCrossingSamples ? t1 : t0 + (t1 - t0) * i / kCrossingSamples;
      const gp_Pnt2d q = c->Value(t);
      for (int dir = 0; dir < 2; ++dir) {
        const double x0 = dir == 0 ? prev.X() : prev.Y(), x1 = dir == 0 ? q.X() : q.Y();
        (dir == 0 ? ub : vb).inside(std::min(x0, x1), std::max(x0, x1), found);
        for (double knot : found) {
          // Bisection on the sign of (coordinate - knot).
          double lo = tp, hi = t;
          const bool rising = x1 > x0;
          for (int it = 0; it < kBisectionSteps; ++it) {
            const double mid = 0.5 * (lo + hi);
            if (!(mid > lo && mid < hi)) break;
            const gp_Pnt2d m = c->Value(mid);
            const double xm = dir == 0 ? m.X() : m.Y();
            if ((xm < knot) == rising)
              lo = mid;
            else
              hi = mid;
          }
          all.push_back(0.5 * (lo + hi));
        }
      }
      prev = q;
      tp = t;
    }
  }
  all.push_back(b);
  std::sort(all.begin(), all.end());
  for (size_t k = 0; k + 1 < all.size(); ++k)
    if (all[k + 1] > all[k]) out.push_back(Segment{all[k], all[k + 1], edge, 0, 0, 0});
}

// The box of points on the boundary (each edge sampled on every smooth interval of its pcurve)
// and of the grid points of the (u, v) box inside the boundary polygon (even-odd rule): it
// depends on the geometry alone, not on the accuracy asked of the area.
BBox3 face_box(const Evaluator& eval, const std::vector<EdgeRef>& edges,
               const std::vector<std::pair<double, double>>& ranges, double u0, double u1,
               double v0, double v1) {
  BBox3 box;
  std::vector<std::pair<Vec2, Vec2>> poly;
  std::vector<double> run;  // boundary samples at one v (an isoparametric edge), one row
  std::vector<Vec3> run_points;
  double run_v = 0.0;
  const auto flush = [&] {
    run_points.resize(run.size());
    eval.points(run_v, run.data(), static_cast<int>(run.size()), run_points.data());
    for (const Vec3& p : run_points) box.add(p);
    run.clear();
  };
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto [a, b] = ranges[k];
    Geom2dAdaptor_Curve ad(edges[k].curve, a, b);
    const int nint = ad.NbIntervals(GeomAbs_C2);
    TColStd_Array1OfReal iv(1, nint + 1);
    ad.Intervals(iv, GeomAbs_C2);
    const int per = std::max(1, kBoxEdgeSamples / nint);
    Vec2 prev = Vec2::Zero();
    bool first = true;
    for (int i = 1; i <= nint; ++i)
      for (int j = (i == 1 ? 0 : 1); j <= per; ++j) {
        const gp_Pnt2d q = edges[k].curve->Value(iv(i) + (iv(i + 1) - iv(i)) * j / per);
        const Vec2 uv(q.X(), q.Y());
        if (!run.empty() && uv.y() != run_v) flush();
        run_v = uv.y();
        run.push_back(uv.x());
        if (!first) poly.emplace_back(prev, uv);
        prev = uv;
        first = false;
      }
  }
  if (!run.empty()) flush();
  std::vector<double> xs;
  double us[kBoxGrid];
  Vec3 ps[kBoxGrid];
  for (int r = 0; r < kBoxGrid; ++r) {
    const double v = v0 + (r + 0.5) * (v1 - v0) / kBoxGrid;
    xs.clear();
    for (const auto& [a, b] : poly)
      if ((a.y() <= v) != (b.y() <= v))
        xs.push_back(a.x() + (v - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    std::sort(xs.begin(), xs.end());
    size_t left = 0;
    int inside = 0;
    for (int c = 0; c < kBoxGrid; ++c) {
      const double u = u0 + (c + 0.5) * (u1 - u0) / kBoxGrid;
      while (left < xs.size() && xs[left] < u) ++left;
      if (left % 2 == 1) us[inside++] = u;
    }
    eval.points(v, us, inside, ps);  // the row's points inside at once
    for (int k = 0; k < inside; ++k) box.add(ps[k]);
  }
  return box;
}

// The boundary, wire by wire with the edges in order along it; where an edge's pcurve does
// not start where the previous one ended (CAD files leave gaps of up to 6e-4 mm, e.g.
// PRO20359-L1.igs), a straight (u, v) segment closes the gap, so that every loop is closed
// and Green's theorem gives the area it bounds (an open loop's result would depend on the
// direction of integration).
// False when an edge has no pcurve. `transposed`: every pcurve mirrored in the line u = v.
bool boundary_of(const TopoDS_Face& face, bool transposed, std::vector<EdgeRef>& edges,
                 std::vector<std::pair<double, double>>& ranges) {
  const gp_Ax2d diagonal(gp_Pnt2d(0, 0), gp_Dir2d(1, 1));
  for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) {
    const size_t first = edges.size();
    gp_Pnt2d loop_start, last_end;
    for (const TopoDS_Edge& e : ordered_edges(TopoDS::Wire(wx.Current()), face)) {
      const TopAbs_Orientation o = e.Orientation();
      if (o != TopAbs_FORWARD && o != TopAbs_REVERSED) continue;
      double a = 0, b = 0;
      Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, a, b);
      if (c.IsNull() || !(b > a)) return false;
      if (transposed) {
        c = Handle(Geom2d_Curve)::DownCast(c->Copy());
        c->Mirror(diagonal);
      }
      const bool reversed = o == TopAbs_REVERSED;
      const gp_Pnt2d start = c->Value(reversed ? b : a), end = c->Value(reversed ? a : b);
      if (edges.size() == first)
        loop_start = start;
      else
        add_segment(last_end, start, edges, ranges);
      edges.push_back(EdgeRef{c, reversed ? -1.0 : 1.0});
      ranges.emplace_back(a, b);
      last_end = end;
    }
    if (edges.size() > first) add_segment(last_end, loop_start, edges, ranges);
  }
  return !edges.empty();
}

}  // namespace measure

}  // namespace plyfit::importers::occt
