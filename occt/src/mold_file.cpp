#include "mold_file.hpp"

#include "face_measure.hpp"
#include "file_checks.hpp"
#include "geometry_checks.hpp"

#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <optional>
#include <set>
#include <utility>

namespace plyfit::importers::occt {

namespace {
// Face areas are plyfit's own integration (face_measure.hpp), to an estimated relative error
// of at most kAreaRelListing in the listing (plyfit info: enough to tell faces apart) and of
// kAreaRelPrecise for a face that is draped, whose area report.json gives and divides the
// covered area by (coverage). OpenCASCADE's adaptive integration (BRepGProp), used before, was
// asked for 1e-12 and took seconds per face on large B-spline faces; on the shared files it is
// off by up to 2e-4 (faces of bug27693_cornetta-step.stp, trj7_c2-td-203.stp face 1), where
// plyfit's integration in u and in v agree to 1e-11 and, on untrimmed faces, the kernel's
// tensor Gauss quadrature agrees to 2e-12 (BENCHMARKS.md, "Face areas").
constexpr double kAreaRelListing = 1e-6;
constexpr double kAreaRelPrecise = 1e-9;

// Points sampled on each edge's pcurve to decide whether a wire is the natural boundary.
constexpr int kBoundarySamples = 64;
// A face is untrimmed when its boundary lies on its surface's natural boundary to within this
// fraction of the face size: the round-off of CAD exporters (1e-7 mm, OCCT's Precision::
// Confusion, on parts of a few mm to a few m) passes; any real trim, however slight, does not.
// (On the shared test files, natural boundaries deviate by <= 2e-8 of the face size and the
// slightest real trims by >= 1.2e-7.)
constexpr double kNaturalBoundaryRel = 5e-8;
// Trim polylines: every edge starts as at least this many segments (plus its C2 breaks), and a
// segment is halved at most this many times (2^20 per initial segment is far below any
// tolerance reachable in double precision for a continuous pcurve).
constexpr int kMinEdgeSegments = 8;
constexpr int kMaxRefineDepth = 20;
// Budget of trim polyline points for one face (all its edges); past it the conversion fails
// with an error.
constexpr size_t kMaxLoopPoints = 2'000'000;
// Sample count along a seam to check that the two seam edges of the surface coincide.
constexpr int kSeamSamples = 9;
// Interior fractions of a polyline segment where the chord error is measured.
constexpr double kChordFractions[3] = {0.25, 0.5, 0.75};

Error point_budget_exceeded() {
  return Error{ErrorCode::kTrimPointBudget, {}, {static_cast<std::int64_t>(kMaxLoopPoints)}};
}

Vec3 vec(const gp_Pnt& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}

// ---------------------------------------------------------------------------------------------
// Listing: surface kind, degrees, range, natural boundary.

// Strips rectangular trims to find the kind of surface a face lies on.
Handle(Geom_Surface) basis_of(Handle(Geom_Surface) s) {
  while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  return s;
}

// A polynomial patch's kind, degrees, pole counts and rationality (B-spline or Bezier).
template <typename Patch>
void describe_patch(const Patch& p, const char* kind, FaceInfo& info) {
  info.kind = kind;
  info.degree_u = p.UDegree();
  info.degree_v = p.VDegree();
  info.poles_u = p.NbUPoles();
  info.poles_v = p.NbVPoles();
  info.rational = p.IsURational() || p.IsVRational();
}

// The name of a surface kind plyfit lists by name, "other" for the rest.
const char* kind_name(const Handle(Geom_Surface) & s) {
  static const std::pair<Handle(Standard_Type), const char*> kKinds[] = {
      {STANDARD_TYPE(Geom_Plane), "plane"},
      {STANDARD_TYPE(Geom_CylindricalSurface), "cylinder"},
      {STANDARD_TYPE(Geom_ConicalSurface), "cone"},
      {STANDARD_TYPE(Geom_SphericalSurface), "sphere"},
      {STANDARD_TYPE(Geom_ToroidalSurface), "torus"},
      {STANDARD_TYPE(Geom_SurfaceOfRevolution), "revolution"},
      {STANDARD_TYPE(Geom_SurfaceOfLinearExtrusion), "extrusion"},
      {STANDARD_TYPE(Geom_OffsetSurface), "offset"}};
  for (const auto& [type, name] : kKinds)
    if (s->IsKind(type)) return name;
  return "other";
}

void describe_surface(const Handle(Geom_Surface) & surface, FaceInfo& info) {
  const Handle(Geom_Surface) s = basis_of(surface);
  if (auto b = Handle(Geom_BSplineSurface)::DownCast(s))
    describe_patch(*b, "bspline", info);
  else if (auto z = Handle(Geom_BezierSurface)::DownCast(s))
    describe_patch(*z, "bezier", info);
  else
    info.kind = kind_name(s);
}

bool is_nurbs_type(const Handle(Geom_Surface) & s) {
  return s->DynamicType() == STANDARD_TYPE(Geom_BSplineSurface) ||
         s->DynamicType() == STANDARD_TYPE(Geom_BezierSurface);
}

struct Rect {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

Rect uv_bounds(const TopoDS_Face& f) {
  Rect r;
  BRepTools::UVBounds(f, r.u0, r.u1, r.v0, r.v1);
  return r;
}

// The parameter range of the NURBS a face converts to, in the face's own (u, v): the
// surface's bounds for B-splines and Béziers (a periodic B-spline is cut at the face's start
// when the face lies outside its first period); for every other kind the face's (u, v) bounds
// clipped to the surface's and to one period, as BRepTools_NurbsConvertModification does.
Rect nurbs_range(const TopoDS_Face& f, const Handle(Geom_Surface) & s) {
  Rect sr;
  s->Bounds(sr.u0, sr.u1, sr.v0, sr.v1);
  const Rect c = uv_bounds(f);
  if (is_nurbs_type(s)) {
    const double tol = BRep_Tool::Tolerance(f);
    GeomAdaptor_Surface ad(s);
    const double tu = ad.UResolution(tol), tv = ad.VResolution(tol);
    if (s->IsUPeriodic() && (c.u0 < sr.u0 - tu || c.u1 > sr.u1 + tu)) {
      sr.u0 = c.u0;
      sr.u1 = c.u0 + s->UPeriod();
    }
    if (s->IsVPeriodic() && (c.v0 < sr.v0 - tv || c.v1 > sr.v1 + tv)) {
      sr.v0 = c.v0;
      sr.v1 = c.v0 + s->VPeriod();
    }
    return sr;
  }
  const double tol_par = 0.1 * BRep_Tool::Tolerance(f);
  auto clip = [&](double cs, double ce, double ss, double se, bool periodic, double period,
                  double& a, double& b) {
    a = std::abs(cs - ss) <= tol_par ? ss : cs;
    b = std::abs(ce - se) <= tol_par ? se : ce;
    if (!periodic) {
      a = std::max(ss, cs);
      b = std::min(se, ce);
    } else if (b - a > period) {
      b = a + period;
    }
  };
  Rect r;
  clip(c.u0, c.u1, sr.u0, sr.u1, s->IsUPeriodic(), s->IsUPeriodic() ? s->UPeriod() : 0.0, r.u0,
       r.u1);
  clip(c.v0, c.v1, sr.v0, sr.v1, s->IsVPeriodic(), s->IsVPeriodic() ? s->VPeriod() : 0.0, r.v0,
       r.v1);
  return r;
}

int count_wires(const TopoDS_Face& f) {
  int n = 0;
  for (TopExp_Explorer ex(f, TopAbs_WIRE); ex.More(); ex.Next()) ++n;
  return n;
}

// True when the face has one wire and every edge of it runs along the border of `r`: each
// sampled boundary point lies within kNaturalBoundaryRel * `size` (3D) of the surface's image
// of the nearest border line. The face is then bounded by its surface's natural boundary; a
// boundary that departs from it by more, however little, makes the face trimmed. `kernel`: the
// kernel's copy of `s` (FaceMeasure::surface) or null, far faster, three points at one v a row.
bool natural_boundary(const TopoDS_Face& f, const Handle(Geom_Surface) & s, const Rect& r,
                      double size, const NurbsSurface* kernel) {
  if (count_wires(f) != 1) return false;
  const double tol = kNaturalBoundaryRel * size;
  const auto at = [&](double u, double v) {
    return kernel ? kernel->point(u, v) : vec(s->Value(u, v));
  };
  SurfaceEval1 row[3];
  for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    double a = 0, b = 0;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, f, a, b);
    if (c.IsNull()) return false;
    for (int k = 0; k <= kBoundarySamples; ++k) {
      const gp_Pnt2d q = c->Value(a + (b - a) * k / kBoundarySamples);
      const double us[3] = {q.X(), r.u0, r.u1};
      if (kernel)
        kernel->eval1_along_u(q.Y(), us, 3, row);
      else
        for (int j = 0; j < 3; ++j) row[j].p = at(us[j], q.Y());
      const Vec3& p = row[0].p;
      const double d = std::min({(p - row[1].p).norm(), (p - row[2].p).norm(),
                                 (p - at(q.X(), r.v0)).norm(), (p - at(q.X(), r.v1)).norm()});
      if (!(d <= tol)) return false;
    }
  }
  return true;
}

// The listing entry of a face: kind, degrees, orientation, area (to `area_rel`, estimated),
// bounding box and trim status. `area_note` is set when the area misses `area_rel`.
// Each face's neighbours and free edges in the file's own topology: the faces that share one
// of its edges (as OpenCASCADE read them, without sewing), and its edges no other face has,
// seams (an edge closed on the face) excepted.
void file_neighbours(const TopTools_IndexedMapOfShape& faces, std::vector<FaceInfo>& infos) {
  TopTools_IndexedMapOfShape edges;
  std::vector<std::vector<int>> edge_faces;
  std::vector<std::vector<int>> face_edges(static_cast<std::size_t>(faces.Extent()));
  for (int i = 1; i <= faces.Extent(); ++i) {
    TopTools_IndexedMapOfShape own;
    TopExp::MapShapes(faces(i), TopAbs_EDGE, own);
    for (int e = 1; e <= own.Extent(); ++e) {
      if (BRep_Tool::IsClosed(TopoDS::Edge(own(e)), TopoDS::Face(faces(i)))) continue;
      const int k = edges.Add(own(e));
      if (k > static_cast<int>(edge_faces.size())) edge_faces.resize(static_cast<std::size_t>(k));
      edge_faces[static_cast<std::size_t>(k - 1)].push_back(i - 1);
      face_edges[static_cast<std::size_t>(i - 1)].push_back(k - 1);
    }
  }
  for (std::size_t f = 0; f < face_edges.size() && f < infos.size(); ++f) {
    std::set<int> nb;
    int free = 0;
    for (int e : face_edges[f]) {
      const auto& users = edge_faces[static_cast<std::size_t>(e)];
      free += users.size() == 1 ? 1 : 0;
      for (int g : users)
        if (g != static_cast<int>(f)) nb.insert(g);
    }
    infos[f].neighbours.assign(nb.begin(), nb.end());
    infos[f].free_edges = free;
  }
}

// Face `index` of the file (made by its entity `entity`) listed, with its area to `area_rel`;
// `area_note` is the area's warning when it falls short (area_warning()); `surface`: FaceMeasure's.
FaceInfo describe_face(const TopoDS_Face& f, int index, const std::string& entity, double area_rel,
                       std::optional<Warning>& area_note,
                       std::shared_ptr<const NurbsSurface>& surface) {
  FaceInfo info;
  info.index = index;
  info.reversed = f.Orientation() == TopAbs_REVERSED;
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  if (s.IsNull()) {
    info.kind = "none";
    return info;
  }
  describe_surface(s, info);
  FaceMeasure m = measure_face(f, area_rel, true);
  info.area = m.area;
  info.area_measured = m.measured;
  info.bbox = m.bbox;
  area_note = area_warning(m, area_rel, index, entity);
  const int wires = count_wires(f);
  info.holes = std::max(0, wires - 1);
  info.trimmed = !natural_boundary(f, s, nurbs_range(f, s), info.bbox.diagonal(), m.surface.get());
  surface = std::move(m.surface);
  return info;
}

// ---------------------------------------------------------------------------------------------
// Conversion of one face.

// Samples one edge's pcurve as a polyline in the edge's direction on the face. Segments are
// halved until, at three interior fractions, both the 3D distance between the surface images
// of the pcurve point and of the chord point, and the chord's (u, v) deviation weighted by the
// surface's parametric speeds, are at most `tol3d`. With `chords3d` (faces of a shell, whose
// shared edges are matched in 3D), the straight 3D chord between the images of a segment's
// ends must also be within `tol3d` of the pcurve's image: an edge straight in (u, v) but curved
// in space (a circle along a cylinder's v = 0) is then refined too.
class EdgeSampler {
 public:
  EdgeSampler(const Handle(Geom_BSplineSurface) & s, double tol3d, Vec2 speeds, bool chords3d)
      : s_(s), tol_(tol3d), speeds_(std::move(speeds)), chords3d_(chords3d) {}

  Status sample(const TopoDS_Edge& e, const TopoDS_Face& f, std::vector<Vec2>& out) {
    double a = 0, b = 0;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, f, a, b);
    if (c.IsNull()) return Error{ErrorCode::kEdgeNoPcurve};
    c_ = c;
    Geom2dAdaptor_Curve ad(c, a, b);
    std::vector<double> ts;
    const int nint = ad.NbIntervals(GeomAbs_C2);
    TColStd_Array1OfReal iv(1, nint + 1);
    ad.Intervals(iv, GeomAbs_C2);
    for (int k = 1; k <= nint; ++k) {
      const double t0 = iv(k), t1 = iv(k + 1);
      const int n = std::max(1, kMinEdgeSegments / nint);
      for (int j = 0; j < n; ++j) ts.push_back(t0 + (t1 - t0) * j / n);
    }
    ts.push_back(b);
    std::vector<Vec2> pts;
    pts.push_back(uv(ts.front()));
    for (size_t k = 0; k + 1 < ts.size(); ++k) {
      if (!(ts[k + 1] > ts[k])) continue;
      refine(ts[k], pts.back(), ts[k + 1], uv(ts[k + 1]), 0, pts);
      if (points_ + pts.size() > kMaxLoopPoints) return point_budget_exceeded();
    }
    points_ += pts.size();
    if (e.Orientation() == TopAbs_REVERSED) std::reverse(pts.begin(), pts.end());
    out.insert(out.end(), pts.begin(), pts.end());
    return ok_status();
  }

 private:
  Vec2 uv(double t) const {
    const gp_Pnt2d p = c_->Value(t);
    return Vec2(p.X(), p.Y());
  }
  Vec3 point(const Vec2& uv) const { return vec(s_->Value(uv.x(), uv.y())); }

  void refine(double t0, const Vec2& p0, double t1, const Vec2& p1, int depth,
              std::vector<Vec2>& out) const {
    double err = 0.0;
    for (double fr : kChordFractions) {
      const Vec2 q = uv(t0 + fr * (t1 - t0));
      const Vec2 lin = p0 + fr * (p1 - p0);
      const Vec2 d = q - lin;
      err = std::max(err, std::hypot(d.x() * speeds_.x(), d.y() * speeds_.y()));
      if (err > tol_) break;
      const Vec3 on = point(q);
      err = std::max(err, (on - point(lin)).norm());
      if (err > tol_) break;
      if (chords3d_) err = std::max(err, (on - (point(p0) + fr * (point(p1) - point(p0)))).norm());
      if (err > tol_) break;
    }
    if (err <= tol_ || depth >= kMaxRefineDepth || points_ + out.size() > kMaxLoopPoints) {
      out.push_back(p1);
      return;
    }
    const double tm = 0.5 * (t0 + t1);
    const Vec2 pm = uv(tm);
    refine(t0, p0, tm, pm, depth + 1, out);
    refine(tm, pm, t1, p1, depth + 1, out);
  }

  Handle(Geom_BSplineSurface) s_;
  Handle(Geom2d_Curve) c_;
  double tol_;
  Vec2 speeds_;
  bool chords3d_;
  size_t points_ = 0;  // of the face's edges sampled so far: the budget is the face's
};

// With `tag`, loop.edges[k] is the tag of the edge segment k was sampled from (a segment that
// joins two edges' ends belongs to the edge it leads into).
Result<std::vector<TrimLoop>> trim_loops(const TopoDS_Face& f,
                                         const Handle(Geom_BSplineSurface) & s, double tol3d,
                                         const Vec2& speeds, double merge_u, double merge_v,
                                         const EdgeTag* tag) {
  std::vector<TopoDS_Wire> wires;
  const TopoDS_Wire outer = BRepTools::OuterWire(f);
  if (!outer.IsNull()) wires.push_back(outer);
  for (TopExp_Explorer ex(f, TopAbs_WIRE); ex.More(); ex.Next())
    if (!ex.Current().IsSame(outer)) wires.push_back(TopoDS::Wire(ex.Current()));
  EdgeSampler sampler(s, tol3d, speeds, tag != nullptr);
  std::vector<TrimLoop> loops;
  size_t total = 0;
  for (const auto& w : wires) {
    TrimLoop loop;
    // ends[k]: tag of the segment that ends at points[k] (ends[0]: of the closing segment).
    std::vector<std::int32_t> ends;
    std::int32_t first_tag = TrimLoop::kFreeEdge;
    for (const auto& e : ordered_edges(w, f)) {
      std::vector<Vec2> pts;
      auto st = sampler.sample(e, f, pts);
      if (!st) return st.error();
      size_t first = 0;
      // An edge starts where the previous one ended: drop the repeated point.
      if (!loop.points.empty() && !pts.empty() &&
          std::abs(pts.front().x() - loop.points.back().x()) <= merge_u &&
          std::abs(pts.front().y() - loop.points.back().y()) <= merge_v)
        first = 1;
      loop.points.insert(loop.points.end(), pts.begin() + static_cast<long>(first), pts.end());
      if (tag) {
        const std::int32_t t = (*tag)(e);
        if (ends.empty()) first_tag = t;
        ends.resize(loop.points.size(), t);
      }
    }
    if (loop.points.size() > 1 &&
        std::abs(loop.points.front().x() - loop.points.back().x()) <= merge_u &&
        std::abs(loop.points.front().y() - loop.points.back().y()) <= merge_v) {
      loop.points.pop_back();
      if (tag) {
        first_tag = ends.back();
        ends.pop_back();
      }
    }
    if (tag && !ends.empty()) {
      ends[0] = first_tag;
      loop.edges.resize(ends.size());
      for (size_t k = 0; k < ends.size(); ++k) loop.edges[k] = ends[(k + 1) % ends.size()];
    }
    total += loop.points.size();
    if (total > kMaxLoopPoints) return point_budget_exceeded();
    if (loop.points.size() >= 3) loops.push_back(std::move(loop));
  }
  if (loops.empty()) return Error{ErrorCode::kFaceNoTrimLoop};
  return loops;
}

// Makes a periodic direction of `s` non-periodic over a range that holds the face: the first
// period when the face lies in it, else the period starting at the face's start.
void unperiodise(Handle(Geom_BSplineSurface) & s, const Rect& face, double tu, double tv) {
  double u0, u1, v0, v1;
  s->Bounds(u0, u1, v0, v1);
  const bool cut_u = s->IsUPeriodic() && (face.u0 < u0 - tu || face.u1 > u1 + tu);
  const bool cut_v = s->IsVPeriodic() && (face.v0 < v0 - tv || face.v1 > v1 + tv);
  if (cut_u || cut_v) {
    const double a0 = cut_u ? face.u0 : u0, a1 = cut_u ? face.u0 + s->UPeriod() : u1;
    const double b0 = cut_v ? face.v0 : v0, b1 = cut_v ? face.v0 + s->VPeriod() : v1;
    s->Segment(a0, a1, b0, b1);
  }
  if (s->IsUPeriodic()) s->SetUNotPeriodic();
  if (s->IsVPeriodic()) s->SetVNotPeriodic();
}

// True when the surface's two borders u = u0 and u = u1 (or v) coincide within tol3d.
bool seam_closes(const Handle(Geom_BSplineSurface) & s, bool along_u, double tol3d) {
  double u0, u1, v0, v1;
  s->Bounds(u0, u1, v0, v1);
  for (int k = 0; k < kSeamSamples; ++k) {
    const double f = static_cast<double>(k) / (kSeamSamples - 1);
    const gp_Pnt a = along_u ? s->Value(u0, v0 + f * (v1 - v0)) : s->Value(u0 + f * (u1 - u0), v0);
    const gp_Pnt b = along_u ? s->Value(u1, v0 + f * (v1 - v0)) : s->Value(u0 + f * (u1 - u0), v1);
    if (a.Distance(b) > tol3d) return false;
  }
  return true;
}

// `measured` (may be null): the surface the face was measured on, taken if made from its data.
Result<FaceData> convert(const TopoDS_Face& face, const FaceInfo& info, const Tolerances& tol,
                         const EdgeTag* tag, std::shared_ptr<const NurbsSurface> measured) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  if (s.IsNull()) return Error{ErrorCode::kFaceNoSurface};
  TopoDS_Face work = face;
  // Tags of the converted face's edges: those of the edges of `face` they were made from.
  TopTools_DataMapOfShapeShape original_edge;
  EdgeTag work_tag;
  if (!is_nurbs_type(s)) {
    BRepBuilderAPI_NurbsConvert nc(face, Standard_True);
    if (!nc.IsDone()) return Error{ErrorCode::kNurbsConversionFailed, {}, {info.kind}};
    const TopoDS_Shape converted = nc.ModifiedShape(face);
    if (converted.IsNull() || converted.ShapeType() != TopAbs_FACE)
      return Error{ErrorCode::kNurbsConversionNoFace, {}, {info.kind}};
    work = TopoDS::Face(converted);
    s = BRep_Tool::Surface(work);
    if (tag) {
      for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
        original_edge.Bind(nc.ModifiedShape(ex.Current()), ex.Current());
      work_tag = [&original_edge, tag](const TopoDS_Edge& e) {
        const TopoDS_Shape* o = original_edge.Seek(e);
        return o ? (*tag)(TopoDS::Edge(*o)) : TrimLoop::kFreeEdge;
      };
      tag = &work_tag;
    }
  }
  Handle(Geom_BSplineSurface) bs;
  if (s->DynamicType() == STANDARD_TYPE(Geom_BSplineSurface))
    bs = Handle(Geom_BSplineSurface)::DownCast(s->Copy());
  else if (s->DynamicType() == STANDARD_TYPE(Geom_BezierSurface))
    bs = GeomConvert::SurfaceToBSplineSurface(s);
  if (bs.IsNull())
    return Error{
        ErrorCode::kNurbsConversionType, {}, {info.kind, std::string(s->DynamicType()->Name())}};

  const double size = info.bbox.diagonal();
  if (!(size > 0.0)) return Error{ErrorCode::kFaceZeroSize};
  const double tol3d = tol.trim_chord_rel * size;
  const Rect fr = uv_bounds(work);
  {
    GeomAdaptor_Surface ad(bs);
    unperiodise(bs, fr, ad.UResolution(tol3d), ad.VResolution(tol3d));
  }
  Rect dom;
  bs->Bounds(dom.u0, dom.u1, dom.v0, dom.v1);
  GeomAdaptor_Surface ad(bs);
  const double tu = ad.UResolution(tol3d), tv = ad.VResolution(tol3d);

  FaceData fd;
  fd.surface = nurbs_data(bs);
  const NurbsSurfaceData& d = fd.surface;
  fd.reversed = face.Orientation() == TopAbs_REVERSED;
  fd.closed_u = std::abs(fr.u0 - dom.u0) <= tu && std::abs(fr.u1 - dom.u1) <= tu &&
                seam_closes(bs, true, tol3d);
  fd.closed_v = std::abs(fr.v0 - dom.v0) <= tv && std::abs(fr.v1 - dom.v1) <= tv &&
                seam_closes(bs, false, tol3d);
  fd.area = info.area;
  fd.name = info.name;
  if (measured && measured->made_from(d, tol)) fd.built = std::move(measured);

  // Whether the face is trimmed was decided on the original face (exact geometry); the
  // conversion maps the face's parameter range onto the NURBS domain, and an approximating
  // conversion (offset surfaces) may move the recomputed pcurves off the border by its error.
  // A face of a shell always has its loops: their segments carry the edges' tags.
  if (info.trimmed || tag) {
    if (!fd.built) {
      auto surf = NurbsSurface::create(d, tol);
      if (!surf) return Error{ErrorCode::kFaceSurfaceInvalid}.because(surf.error());
      fd.built = std::make_shared<const NurbsSurface>(std::move(surf).value());
    }
    const Vec2 speeds(fd.built->speed_u(), fd.built->speed_v());
    auto loops = trim_loops(work, bs, tol3d, speeds, tol.param_rel * (dom.u1 - dom.u0),
                            tol.param_rel * (dom.v1 - dom.v0), tag);
    if (!loops) return loops.error();
    fd.loops = std::move(loops).value();
  }
  return fd;
}

// The data of WarningCode::kListingFailedFaces for face i (its entity) and why it failed: the
// face, the entity, then for `why` and each of its causes its code's name, its value count and
// its values (the exporters render the chain: message_text.hpp's error_chain_text()).
std::vector<MessageValue> failure_data(int i, const std::string& entity, const Error& why) {
  std::vector<MessageValue> out{std::int64_t{i}, entity};
  for (const Error* e = &why; e; e = e->cause.get()) {
    out.emplace_back(std::string(to_string(e->code)));
    out.emplace_back(static_cast<std::int64_t>(e->values.size()));
    out.insert(out.end(), e->values.begin(), e->values.end());
  }
  return out;
}

// An opened file. Reading and transferring happen at open; each face's entry (kind, degrees,
// area, box, trim status) is computed when first needed: all of them, with areas to
// kAreaRelListing, on the first call to mold(); face i alone, with its area to kAreaRelPrecise,
// by describe(i) or convert_face(i), so that importing one face pays neither for the listing
// of the others nor for a listing-accuracy area it does not use. Not thread-safe.
class OcctMoldFile final : public MoldFile {
 public:
  OcctMoldFile(Mold mold, TopTools_IndexedMapOfShape faces, std::vector<std::string> entities,
               ImportOptions options, double precision)
      : mold_(std::move(mold)),
        faces_(std::move(faces)),
        entities_(std::move(entities)),
        options_(std::move(options)),
        precision_(precision),
        state_(static_cast<size_t>(faces_.Extent()), State::kPending),
        failure_(static_cast<size_t>(faces_.Extent())),
        note_(static_cast<size_t>(faces_.Extent())) {}

  const Mold& mold() const override {
    if (!listed_) {
      list_faces();
      file_neighbours(faces_, mold_.faces);
      listed_ = true;
    }
    return mold_;
  }

  int face_count() const override { return faces_.Extent(); }

  Result<FaceInfo> describe(int index) const override {
    if (auto st = check_index(index); !st) return st.error();
    if (!describe_once(index, true)) return blamed(failure_[static_cast<size_t>(index)], at(index));
    return mold_.faces[static_cast<size_t>(index)];
  }

  const Mold& summary() const override { return mold_; }

  Result<FaceData> convert_face(int index) override {
    if (auto st = check_index(index); !st) return st.error();
    if (!describe_once(index, true)) return blamed(failure_[static_cast<size_t>(index)], at(index));
    if (!mold_.faces[static_cast<size_t>(index)].area_measured)
      return blamed(Error{ErrorCode::kFaceAreaNotMeasured, {}, {why_not_measured(index)}},
                    at(index));
    return guarded(at(index), [&]() -> Result<FaceData> {
      return convert(TopoDS::Face(faces_(index + 1)), mold_.faces[static_cast<size_t>(index)],
                     options_.tolerances, nullptr, take_measured(index));
    });
  }

  Result<ShellData> convert_shell(const std::vector<int>& indices) override {
    const ShellInput in{mold_.source, faces_, precision_, options_,
                        [this](int i) { return describe(i); }};
    return sew_faces(in, indices, mold_.warnings);
  }

 private:
  // kListed: area to kAreaRelListing; kPrecise: to kAreaRelPrecise.
  enum class State { kPending, kListed, kPrecise, kFailed };

  // Face `index` of the file and the entity that made it.
  Blame at(int index) const { return {mold_.source, index, entities_[static_cast<size_t>(index)]}; }

  Status check_index(int index) const {
    const int n = faces_.Extent();
    if (index >= 0 && index < n) return ok_status();
    return Error{ErrorCode::kFaceIndexRange, mold_.source, {std::int64_t{index}, std::int64_t{n}}};
  }

  // Face `index`'s surface measured to kAreaRelPrecise (the last face's only), once, else null.
  std::shared_ptr<const NurbsSurface> take_measured(int index) {
    return index == measured_.first ? std::exchange(measured_, {}).second : nullptr;
  }

  // Fills mold_.faces[i], with its area to kAreaRelPrecise when `precise` (a listed face gets
  // its area computed again); false when OpenCASCADE failed on the face. A precise area short
  // of its accuracy is a warning of the file.
  bool describe_once(int i, bool precise) const {
    const size_t k = static_cast<size_t>(i);
    const TopoDS_Face& f = TopoDS::Face(faces_(i + 1));
    if (state_[k] == State::kPending) {
      std::shared_ptr<const NurbsSurface> surface;
      auto info = guarded({}, [&]() -> Result<FaceInfo> {
        return describe_face(f, i, entities_[k], precise ? kAreaRelPrecise : kAreaRelListing,
                             note_[k], surface);
      });
      if (precise) measured_ = {i, std::move(surface)};
      if (info) {
        info->name = mold_.faces[k].name;
        mold_.faces[k] = std::move(info).value();
        state_[k] = precise ? State::kPrecise : State::kListed;
      } else {
        failure_[k] = Error{ErrorCode::kFaceNotDescribed}.because(info.error());
        state_[k] = State::kFailed;
      }
    } else if (state_[k] == State::kListed && precise) {
      auto m = guarded(
          {}, [&]() -> Result<FaceMeasure> { return measure_face(f, kAreaRelPrecise, false); });
      if (!m) {
        failure_[k] = Error{ErrorCode::kFaceNotMeasured}.because(m.error());
        state_[k] = State::kFailed;
        return false;
      }
      mold_.faces[k].area = m->area;
      mold_.faces[k].area_measured = m->measured;
      measured_ = {i, std::move(m->surface)};
      note_[k] = area_warning(*m, kAreaRelPrecise, i, entities_[k]);
      state_[k] = State::kPrecise;
    } else {
      return state_[k] != State::kFailed;
    }
    if (state_[k] == State::kPrecise && note_[k]) mold_.warnings.push_back(*note_[k]);
    return state_[k] != State::kFailed;
  }

  // The listing of every face (describe_once()) and its warnings: the faces that could not be
  // described, whose area could not be measured, and whose area falls short of the listing's
  // accuracy (counts, then the first such face's data).
  void list_faces() const {
    Warning failed{WarningCode::kListingFailedFaces, {}};
    Warning unmeasured{WarningCode::kUnmeasuredFaces, {}};
    Warning short_areas{WarningCode::kShortAreaFaces, {}};
    std::int64_t n_failed = 0, n_unmeasured = 0, n_short = 0;
    const auto first = [](Warning& w, std::int64_t& n, std::vector<MessageValue> data) {
      if (n++ == 0) w.values = std::move(data);
    };
    for (int i = 0; i < faces_.Extent(); ++i) {
      const size_t k = static_cast<size_t>(i);
      if (!describe_once(i, false))
        first(failed, n_failed, failure_data(i, entities_[k], failure_[k]));
      else if (!mold_.faces[k].area_measured)
        first(unmeasured, n_unmeasured, note_[k] ? note_[k]->values : std::vector<MessageValue>{});
      else if (note_[k] && state_[k] == State::kListed)
        first(short_areas, n_short, note_[k]->values);
    }
    for (auto [w, n] : {std::pair{&unmeasured, n_unmeasured}, std::pair{&failed, n_failed},
                        std::pair{&short_areas, n_short}})
      if (n > 0) {
        w->values.insert(w->values.begin(), MessageValue{n});
        mold_.warnings.push_back(std::move(*w));
      }
  }

  // Why face `index`, listed, could not be measured (its note's last value).
  std::string why_not_measured(int index) const {
    const auto& note = note_[static_cast<size_t>(index)];
    if (note && !note->values.empty())
      if (const auto* why = std::get_if<std::string>(&note->values.back())) return *why;
    return {};
  }

  mutable Mold mold_;
  TopTools_IndexedMapOfShape faces_;
  std::vector<std::string> entities_;  // the file's entity of each face ("#12", "DE 5", "")
  ImportOptions options_;
  double precision_;
  mutable std::vector<State> state_;
  mutable std::vector<Error> failure_;  // why a face in State::kFailed failed
  // The face's area warning: its accuracy when short of the asked, why it was not measured.
  mutable std::vector<std::optional<Warning>> note_;
  mutable bool listed_ = false;
  mutable std::pair<int, std::shared_ptr<const NurbsSurface>> measured_{-1, nullptr};
};

// Every face's geometry as read (geometry_checks.hpp); the first problem names the file,
// the face and its entity.
Status check_geometry(const std::string& path, const TopTools_IndexedMapOfShape& faces,
                      const std::vector<std::string>& entities) {
  for (int i = 0; i < faces.Extent(); ++i) {
    const Blame at{path, i, entities[static_cast<size_t>(i)]};
    auto st = guarded(at, [&] { return check_face_geometry(TopoDS::Face(faces(i + 1))); });
    if (!st) return st.error();
  }
  return ok_status();
}

}  // namespace

Result<FaceData> convert_face(const TopoDS_Face& face, const FaceInfo& info, const Tolerances& tol,
                              const EdgeTag* tag) {
  return convert(face, info, tol, tag, nullptr);
}

Result<ReadOutput> read_guarded(const std::string& path, const std::string& format_key,
                                const ImportOptions& options, const ReadFunction& read) {
  const auto sniffed = check_file_head(path, format_key);
  if (!sniffed) return sniffed.error();
  const Sniffed want = *sniffed;
  if (auto checked = check_file_text(path, want == Sniffed::kStep); !checked)
    return Error(checked.error()).in(path);

  prepare_occt();
  Handle(Deadline) deadline = new Deadline(options.time_limit_s);
  auto out = guarded({path, -1, {}}, [&]() -> Result<ReadOutput> {
    debug_reader_fault();
    return read(path, *deadline);
  });
  if (!out) return out.error();
  if (deadline->expired())
    return Error{
        ErrorCode::kReadTimeLimit, path, {std::int64_t{static_cast<int>(options.time_limit_s)}}};
  return out;
}

Result<std::unique_ptr<MoldFile>> open_with(const std::string& path, const std::string& format_key,
                                            const ImportOptions& options,
                                            const ReadFunction& read) {
  auto out = read_guarded(path, format_key, options, read);
  if (!out) return out.error();
  ReadOutput& ro = out.value();

  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(ro.shape, TopAbs_FACE, faces);
  if (faces.IsEmpty())
    return Error{ErrorCode::kFileNoFaces, path,
                 ro.warnings.empty() ? std::vector<MessageValue>{} : ro.warnings.front().values};

  Mold mold;
  mold.source = path;
  mold.format = format_key;
  mold.schema = ro.schema;
  mold.unit = ro.unit;
  mold.warnings = ro.warnings;
  // Placeholders until each face is described (OcctMoldFile::describe_once).
  for (int i = 0; i < faces.Extent(); ++i) {
    FaceInfo pending;
    pending.index = i;
    pending.kind = "unknown";
    mold.faces.push_back(pending);
  }
  for (const auto& [shape, name] : ro.shape_names) {
    const int k = faces.FindIndex(shape);
    if (k > 0 && mold.faces[k - 1].name.empty()) mold.faces[k - 1].name = name;
  }
  std::vector<std::string> entities(static_cast<size_t>(faces.Extent()));
  for (const auto& [shape, label] : ro.face_entities)
    if (const int k = faces.FindIndex(shape); k > 0) entities[static_cast<size_t>(k - 1)] = label;
  if (auto checked = check_geometry(path, faces, entities); !checked) return checked.error();
  return std::unique_ptr<MoldFile>(std::make_unique<OcctMoldFile>(
      std::move(mold), std::move(faces), std::move(entities), options, ro.precision));
}

}  // namespace plyfit::importers::occt
