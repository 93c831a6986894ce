// The curves of a STEP or IGES file (Importer::curves): the edges of its shape that bound no
// face (free curves, wires), else every face's edges, each as a polyline.

#include "mold_file.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cmath>

namespace plyfit::importers::occt {

namespace {

std::string kind_name(GeomAbs_CurveType type) {
  switch (type) {
    case GeomAbs_Line:
      return "line";
    case GeomAbs_Circle:
      return "circle";
    case GeomAbs_Ellipse:
      return "ellipse";
    case GeomAbs_Hyperbola:
      return "hyperbola";
    case GeomAbs_Parabola:
      return "parabola";
    case GeomAbs_BezierCurve:
      return "bezier";
    case GeomAbs_BSplineCurve:
      return "bspline";
    case GeomAbs_OffsetCurve:
      return "offset";
    default:
      return "other";
  }
}

// The edges the curves are made of: those of no face, else all (both in the walk's order).
TopTools_IndexedMapOfShape curve_edges(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape faces_of;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of);
  TopTools_IndexedMapOfShape free_edges, all;
  for (int i = 1; i <= faces_of.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(faces_of.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    all.Add(e);
    if (faces_of(i).IsEmpty()) free_edges.Add(e);
  }
  return free_edges.IsEmpty() ? all : free_edges;
}

// The name of an edge: its entity's, else its wire's.
std::string edge_name(const TopoDS_Shape& edge,
                      const std::vector<std::pair<TopoDS_Shape, std::string>>& names) {
  for (const auto& [s, n] : names)
    if (s.IsSame(edge)) return n;
  for (const auto& [s, n] : names) {
    if (s.ShapeType() != TopAbs_WIRE) continue;
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(s, TopAbs_EDGE, edges);
    if (edges.Contains(edge)) return n;
  }
  return {};
}

// Edge `index` as a polyline within `chord` mm of it, in the edge's direction.
Result<FileCurve> discretise(const TopoDS_Edge& edge, int index, double chord) {
  const BRepAdaptor_Curve curve(edge);
  GCPnts_QuasiUniformDeflection sampler(curve, chord);
  if (!sampler.IsDone() || sampler.NbPoints() < 2)
    return Error{ErrorCode::kCurveNotDiscretised, {}, {std::int64_t{index}}};
  FileCurve out;
  out.kind = kind_name(curve.GetType());
  out.length = GCPnts_AbscissaPoint::Length(curve);
  for (int i = 1; i <= sampler.NbPoints(); ++i) {
    const gp_Pnt p = sampler.Value(i);
    out.points.emplace_back(p.X(), p.Y(), p.Z());
  }
  if (edge.Orientation() == TopAbs_REVERSED) std::reverse(out.points.begin(), out.points.end());
  TopoDS_Vertex v1, v2;
  TopExp::Vertices(edge, v1, v2);
  out.closed = (!v1.IsNull() && v1.IsSame(v2)) || curve.IsClosed();
  if (out.closed && out.points.size() > 2) out.points.pop_back();
  return out;
}

}  // namespace

Result<std::vector<FileCurve>> curves_with(const std::string& path, const std::string& format_key,
                                           const ImportOptions& options, const ReadFunction& read) {
  auto ro = read_guarded(path, format_key, options, read);
  if (!ro) return ro.error();
  return guarded({path, -1, {}}, [&]() -> Result<std::vector<FileCurve>> {
    const TopTools_IndexedMapOfShape edges = curve_edges(ro->shape);
    std::vector<FileCurve> out;
    if (edges.IsEmpty()) return out;
    Bnd_Box box;
    for (int i = 1; i <= edges.Extent(); ++i) BRepBndLib::Add(edges(i), box);
    const double size = box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
    const double chord = options.tolerances.curve_chord_rel * size;
    if (!(chord > 0.0)) return Error{ErrorCode::kCurvesNoExtent};
    for (int i = 1; i <= edges.Extent(); ++i) {
      auto c = discretise(TopoDS::Edge(edges(i)), i - 1, chord);
      if (!c) return c.error();
      c->index = i - 1;
      c->name = edge_name(edges(i), ro->shape_names);
      out.push_back(std::move(c).value());
    }
    return out;
  });
}

}  // namespace plyfit::importers::occt
