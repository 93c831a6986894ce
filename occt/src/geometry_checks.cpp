#include "geometry_checks.hpp"

#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Conic.hxx>
#include <Geom2d_Ellipse.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_OffsetCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_OffsetCurve.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <StepData_StepModel.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

namespace plyfit::importers::occt {

namespace {

// Surfaces and curves wrap others (trimmed, offset, swept); a file cannot nest them deeper.
constexpr int kMaxWrapping = 16;

std::string numbered(const char* format, int n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, format, n);
  return buf;
}

std::string index_text(int i, int j = 0) {
  char buf[32];
  if (j)
    std::snprintf(buf, sizeof buf, "(%d, %d)", i, j);
  else
    std::snprintf(buf, sizeof buf, "(%d)", i);
  return buf;
}

// The first problem of a face's geometry, found by walking it; later checks are skipped once
// one is found. Points are placed by the current placement before they are measured.
class Checker {
 public:
  std::optional<Error> problem;
  bool ok() const { return !problem; }
  void context(std::string c) { context_ = std::move(c); }
  void place(const gp_Trsf& t) { trsf_ = t; }

  // A point's distance from the origin, placed.
  void point(const gp_Pnt& p, const std::string& what) {
    if (!finite(p.XYZ(), what)) return;
    bound(p.Transformed(trsf_).XYZ().Modulus(), what, " mm from the origin");
  }
  void length(double x, const std::string& what) {
    if (finite(gp_XYZ(x, 0, 0), what)) bound(std::abs(x), what, " mm");
  }
  void parameter(double t, const std::string& what) {
    if (finite(gp_XYZ(t, 0, 0), what)) bound(std::abs(t), what, "");
  }
  void direction(const gp_XYZ& d, const std::string& what) { finite(d, what); }
  // A trim bound of a surface or curve: OpenCASCADE writes an unbounded side as 2e100.
  void bound_value(double t, const std::string& what) { finite(gp_XYZ(t, 0, 0), what); }
  void weight(double w, const std::string& what) {
    if (ok() && !(w > 0.0 && std::isfinite(w))) fail(ErrorCode::kFaceWeightNotPositive, what);
  }
  void tolerance(double t, const std::string& what) {
    if (ok() && !(t >= 0.0 && std::isfinite(t))) fail(ErrorCode::kFaceToleranceInvalid, what);
  }
  void placement(const gp_Trsf& t, const std::string& what) {
    const gp_Mat m = t.HVectorialPart();
    for (int i = 1; i <= 3; ++i) direction(gp_XYZ(m(i, 1), m(i, 2), m(i, 3)), what);
    if (ok() && !(std::isfinite(t.ScaleFactor()) && t.ScaleFactor() != 0.0))
      fail(ErrorCode::kFaceScaleInvalid, what);
    if (ok()) bound(t.TranslationPart().Modulus(), what, " mm from the origin");
  }

  void surface(const Handle(Geom_Surface) & s, int depth = 0);
  void curve(const Handle(Geom_Curve) & c, int depth = 0);
  void curve2d(const Handle(Geom2d_Curve) & c, int depth = 0);
  // A curve of either space (Curves3d, Curves2d below): its kind's values, then what it wraps.
  template <typename Space>
  void any_curve(const Handle(typename Space::Curve) & c, int depth);

 private:
  // The first problem: `code`, with the part of the face (context_) and `what` its values.
  void fail(ErrorCode code, const std::string& what, std::vector<MessageValue> more = {}) {
    if (!ok()) return;
    std::vector<MessageValue> values{context_, what};
    values.insert(values.end(), more.begin(), more.end());
    problem = Error{code, {}, std::move(values)};
  }
  bool finite(const gp_XYZ& v, const std::string& what) {
    if (!ok()) return false;
    if (std::isfinite(v.X()) && std::isfinite(v.Y()) && std::isfinite(v.Z())) return true;
    fail(ErrorCode::kFaceGeometryNotFinite, what);
    return false;
  }
  void bound(double magnitude, const std::string& what, const char* unit) {
    if (ok() && !(magnitude <= kMaxModelCoordinate))
      fail(ErrorCode::kFaceGeometryTooLarge, what,
           {magnitude, std::string(unit), kMaxModelCoordinate});
  }
  void bspline(const Handle(Geom_BSplineSurface) & b);
  // The poles (checked by `at`), weights and knots of a B-spline or Bezier curve, 3D or 2D.
  template <typename Curve, typename At>
  void poles_and_knots(const Curve& c, const At& at) {
    for (int i = 1; i <= c->NbPoles() && ok(); ++i) {
      at(c->Pole(i), "pole " + index_text(i));
      if (c->IsRational()) weight(c->Weight(i), "weight " + index_text(i));
    }
    if constexpr (requires { c->NbKnots(); })
      for (int i = 1; i <= c->NbKnots(); ++i) parameter(c->Knot(i), "knot " + index_text(i));
  }
  void elementary(const Handle(Geom_Surface) & s);

  std::string context_;
  gp_Trsf trsf_;
};

void Checker::bspline(const Handle(Geom_BSplineSurface) & b) {
  const bool rational = b->IsURational() || b->IsVRational();
  for (int i = 1; i <= b->NbUPoles() && ok(); ++i)
    for (int j = 1; j <= b->NbVPoles() && ok(); ++j) {
      point(b->Pole(i, j), "pole " + index_text(i, j));
      if (rational) weight(b->Weight(i, j), "weight " + index_text(i, j));
    }
  for (int i = 1; i <= b->NbUKnots(); ++i) parameter(b->UKnot(i), "u knot " + index_text(i));
  for (int i = 1; i <= b->NbVKnots(); ++i) parameter(b->VKnot(i), "v knot " + index_text(i));
}

// Planes, cylinders, cones, spheres and tori: their frame and radii.
void Checker::elementary(const Handle(Geom_Surface) & s) {
  const auto e = Handle(Geom_ElementarySurface)::DownCast(s);
  const gp_Ax3 a = e->Position();
  point(a.Location(), "origin");
  direction(a.Direction().XYZ(), "axis");
  direction(a.XDirection().XYZ(), "x direction");
  if (const auto c = Handle(Geom_CylindricalSurface)::DownCast(s); !c.IsNull())
    length(c->Radius(), "radius");
  if (const auto c = Handle(Geom_ConicalSurface)::DownCast(s); !c.IsNull()) {
    length(c->RefRadius(), "radius");
    parameter(c->SemiAngle(), "half angle");
  }
  if (const auto c = Handle(Geom_SphericalSurface)::DownCast(s); !c.IsNull())
    length(c->Radius(), "radius");
  if (const auto c = Handle(Geom_ToroidalSurface)::DownCast(s); !c.IsNull()) {
    length(c->MajorRadius(), "major radius");
    length(c->MinorRadius(), "minor radius");
  }
}

void Checker::surface(const Handle(Geom_Surface) & s, int depth) {
  if (s.IsNull() || !ok() || depth > kMaxWrapping) return;
  if (const auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s); !t.IsNull()) {
    double u0, u1, v0, v1;
    t->Bounds(u0, u1, v0, v1);
    for (double p : {u0, u1, v0, v1}) bound_value(p, "trim bound");
    surface(t->BasisSurface(), depth + 1);
  } else if (const auto b = Handle(Geom_BSplineSurface)::DownCast(s); !b.IsNull()) {
    bspline(b);
  } else if (const auto z = Handle(Geom_BezierSurface)::DownCast(s); !z.IsNull()) {
    for (int i = 1; i <= z->NbUPoles(); ++i)
      for (int j = 1; j <= z->NbVPoles(); ++j) {
        point(z->Pole(i, j), "pole " + index_text(i, j));
        weight(z->Weight(i, j), "weight " + index_text(i, j));
      }
  } else if (s->IsKind(STANDARD_TYPE(Geom_ElementarySurface))) {
    elementary(s);
  } else if (const auto r = Handle(Geom_SurfaceOfRevolution)::DownCast(s); !r.IsNull()) {
    point(r->Location(), "axis point");
    direction(r->Direction().XYZ(), "axis");
    curve(r->BasisCurve(), depth + 1);
  } else if (const auto x = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(s); !x.IsNull()) {
    direction(x->Direction().XYZ(), "direction");
    curve(x->BasisCurve(), depth + 1);
  } else if (const auto o = Handle(Geom_OffsetSurface)::DownCast(s); !o.IsNull()) {
    length(o->Offset(), "offset");
    surface(o->BasisSurface(), depth + 1);
  }
}

// OpenCASCADE's 3D and 2D curves: the same kinds with the same accessors, but no common base.
// A 3D curve's points are placed and measured from the origin, its sizes are lengths; a trim
// curve lies in the surface's (u, v), so its coordinates and sizes are parameters.
template <typename C, typename Tr, typename BS, typename Bz, typename L, typename Co, typename Ci,
          typename E, typename O>
struct CurveKinds {
  using Curve = C;
  using Trimmed = Tr;
  using BSpline = BS;
  using Bezier = Bz;
  using Line = L;
  using Conic = Co;
  using Circle = Ci;
  using Ellipse = E;
  using Offset = O;
};

struct Curves3d : CurveKinds<Geom_Curve, Geom_TrimmedCurve, Geom_BSplineCurve, Geom_BezierCurve,
                             Geom_Line, Geom_Conic, Geom_Circle, Geom_Ellipse, Geom_OffsetCurve> {
  static void point(Checker& c, const gp_Pnt& p, const std::string& what) { c.point(p, what); }
  static void size(Checker& c, double x, const std::string& what) { c.length(x, what); }
  static void direction(Checker& c, const gp_Dir& d, const std::string& what) {
    c.direction(d.XYZ(), what);
  }
  static void axis(Checker& c, const Conic& k) { direction(c, k.Position().Direction(), "axis"); }
  static void offset_direction(Checker& c, const Offset& o) {
    direction(c, o.Direction(), "direction");
  }
};

struct Curves2d
    : CurveKinds<Geom2d_Curve, Geom2d_TrimmedCurve, Geom2d_BSplineCurve, Geom2d_BezierCurve,
                 Geom2d_Line, Geom2d_Conic, Geom2d_Circle, Geom2d_Ellipse, Geom2d_OffsetCurve> {
  static void point(Checker& c, const gp_Pnt2d& p, const std::string& what) {
    c.parameter(p.X(), what);
    c.parameter(p.Y(), what);
  }
  static void size(Checker& c, double x, const std::string& what) { c.parameter(x, what); }
  static void direction(Checker& c, const gp_Dir2d& d, const std::string& what) {
    c.parameter(d.X(), what);
    c.parameter(d.Y(), what);
  }
  static void axis(Checker&, const Conic&) {}
  static void offset_direction(Checker&, const Offset&) {}
};

template <typename Space>
void Checker::any_curve(const Handle(typename Space::Curve) & c, int depth) {
  if (c.IsNull() || !ok() || depth > kMaxWrapping) return;
  auto at = [this](const auto& p, const std::string& what) { Space::point(*this, p, what); };
  if (const auto t = Handle(typename Space::Trimmed)::DownCast(c); !t.IsNull()) {
    bound_value(t->FirstParameter(), "trim bound");
    bound_value(t->LastParameter(), "trim bound");
    any_curve<Space>(t->BasisCurve(), depth + 1);
  } else if (const auto b = Handle(typename Space::BSpline)::DownCast(c); !b.IsNull()) {
    poles_and_knots(b, at);
  } else if (const auto z = Handle(typename Space::Bezier)::DownCast(c); !z.IsNull()) {
    poles_and_knots(z, at);
  } else if (const auto l = Handle(typename Space::Line)::DownCast(c); !l.IsNull()) {
    at(l->Position().Location(), "origin");
    Space::direction(*this, l->Position().Direction(), "direction");
  } else if (const auto k = Handle(typename Space::Conic)::DownCast(c); !k.IsNull()) {
    at(k->Location(), "centre");
    Space::axis(*this, *k);
    if (const auto r = Handle(typename Space::Circle)::DownCast(c); !r.IsNull())
      Space::size(*this, r->Radius(), "radius");
    if (const auto e = Handle(typename Space::Ellipse)::DownCast(c); !e.IsNull()) {
      Space::size(*this, e->MajorRadius(), "major radius");
      Space::size(*this, e->MinorRadius(), "minor radius");
    }
  } else if (const auto o = Handle(typename Space::Offset)::DownCast(c); !o.IsNull()) {
    Space::size(*this, o->Offset(), "offset");
    Space::offset_direction(*this, *o);
    any_curve<Space>(o->BasisCurve(), depth + 1);
  }
}

void Checker::curve(const Handle(Geom_Curve) & c, int depth) {
  any_curve<Curves3d>(c, depth);
}

void Checker::curve2d(const Handle(Geom2d_Curve) & c, int depth) {
  any_curve<Curves2d>(c, depth);
}

// Edge k of `face`: its 3D curve and range, its trim curve on the face and range, its vertices.
void check_edge(Checker& c, const TopoDS_Face& face, const TopoDS_Edge& e, int k) {
  const std::string name = "edge " + std::to_string(k);
  c.context(name);
  c.tolerance(BRep_Tool::Tolerance(e), "tolerance");
  TopLoc_Location loc;
  double a = 0, b = 0;
  if (const Handle(Geom_Curve) curve = BRep_Tool::Curve(e, loc, a, b); !curve.IsNull()) {
    c.context(name + "'s curve");
    c.place(loc.Transformation());
    c.parameter(a, "start");
    c.parameter(b, "end");
    c.curve(curve);
  }
  if (const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(e, face, a, b);
      !pcurve.IsNull()) {
    c.context(name + "'s trim curve");
    c.parameter(a, "start");
    c.parameter(b, "end");
    c.curve2d(pcurve);
  }
  TopoDS_Vertex v[2];
  TopExp::Vertices(e, v[0], v[1]);
  c.context(name);
  c.place(gp_Trsf());
  for (const auto& vertex : v) {
    if (vertex.IsNull()) continue;
    c.point(BRep_Tool::Pnt(vertex), "vertex");
    c.tolerance(BRep_Tool::Tolerance(vertex), "vertex tolerance");
  }
}

}  // namespace

std::string entity_label(XSControl_Reader& reader, const TopoDS_Shape& face) {
  const Handle(Standard_Transient) e =
      reader.WS()->TransferReader()->EntityFromShapeResult(face, -1);
  if (e.IsNull()) return {};
  const Handle(Interface_InterfaceModel) model = reader.Model();
  if (const auto step = Handle(StepData_StepModel)::DownCast(model); !step.IsNull()) {
    const int id = step->IdentLabel(e);
    return id > 0 ? numbered("#%d", id) : std::string();
  }
  const auto iges = Handle(IGESData_IGESModel)::DownCast(model);
  const auto entity = Handle(IGESData_IGESEntity)::DownCast(e);
  if (iges.IsNull() || entity.IsNull()) return {};
  const int de = iges->DNum(entity);
  return de > 0 ? numbered("DE %d", de) : std::string();
}

Status check_face_geometry(const TopoDS_Face& face) {
  Checker c;
  TopLoc_Location loc;
  const Handle(Geom_Surface) s = BRep_Tool::Surface(face, loc);
  c.context("its placement");
  c.placement(loc.Transformation(), "transformation");
  c.context("its surface");
  c.place(loc.Transformation());
  c.surface(s);
  c.tolerance(BRep_Tool::Tolerance(face), "tolerance");
  int k = 0;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More() && c.ok(); ex.Next())
    check_edge(c, face, TopoDS::Edge(ex.Current()), k++);
  if (!c.ok()) return *c.problem;
  return ok_status();
}

}  // namespace plyfit::importers::occt
