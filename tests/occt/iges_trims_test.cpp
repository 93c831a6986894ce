// IGES trimmed surfaces (144) whose trim loops are model-space curves only
// (occt/src/iges_reader.cpp): read trimmed where the curves close, across both seams of a doubly
// periodic surface; listed with a warning naming the face where the reader cannot use them.

#include <plyfit/importers/importers.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRep_Builder.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax3.hxx>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"

#include <algorithm>
#include <string>

using namespace plyfit;
using namespace plyfit::test;

namespace {

// Samples per edge of the model-space trim curves, and the fit's tolerance (mm): the curves lie
// on the surface to this, which moves the area read back by about this times the perimeter,
// well within the listing's own accuracy (1e-6 relative), the test's.
constexpr int kEdgeSamples = 41;
constexpr double kFitTol = 1e-6;
constexpr double kAreaRel = 1e-6;

// A torus (R 40, r 20) as a B-spline surface periodic in u and v.
Handle(Geom_BSplineSurface) periodic_torus() {
  const Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(
      new Geom_ToroidalSurface(gp_Ax3(gp::Origin(), gp::DZ(), gp::DX()), 40.0, 20.0));
  REQUIRE(s->IsUPeriodic());
  REQUIRE(s->IsVPeriodic());
  return s;
}

// The face of `surface` bounded by the square [a, b] x [a, b] of parameters, its edges
// carrying model-space curves fitted through points of the surface (complete: not cut at the
// seams) and straight pcurves.
TopoDS_Face square_face(const Handle(Geom_BSplineSurface) & surface, double a, double b) {
  const gp_Pnt2d corner[4] = {gp_Pnt2d(a, a), gp_Pnt2d(b, a), gp_Pnt2d(b, b), gp_Pnt2d(a, b)};
  TopoDS_Vertex v[4];
  for (int k = 0; k < 4; ++k)
    v[k] = BRepBuilderAPI_MakeVertex(surface->Value(corner[k].X(), corner[k].Y())).Vertex();
  TopoDS_Face face = TopoDS::Face(BRepBuilderAPI_MakeFace(surface, kFitTol).Face().EmptyCopied());
  BRep_Builder builder;
  TopoDS_Wire wire;
  builder.MakeWire(wire);
  for (int k = 0; k < 4; ++k) {
    const gp_Pnt2d p = corner[k], q = corner[(k + 1) % 4];
    TColgp_Array1OfPnt points(1, kEdgeSamples);
    for (int i = 0; i < kEdgeSamples; ++i) {
      const double t = static_cast<double>(i) / (kEdgeSamples - 1);
      points(i + 1) = surface->Value(p.X() + t * (q.X() - p.X()), p.Y() + t * (q.Y() - p.Y()));
    }
    const Handle(Geom_BSplineCurve) c3 =
        GeomAPI_PointsToBSpline(points, 3, 8, GeomAbs_C2, kFitTol).Curve();
    const TopoDS_Edge e = BRepBuilderAPI_MakeEdge(c3, v[k], v[(k + 1) % 4]).Edge();
    // A straight pcurve: the file keeps only the model-space curve (write_3d_trims()).
    const gp_Vec2d step(p, q);
    builder.UpdateEdge(
        e, new Geom2d_TrimmedCurve(new Geom2d_Line(p, gp_Dir2d(step)), 0.0, step.Magnitude()), face,
        kFitTol);
    builder.Add(wire, e);
  }
  builder.Add(face, wire);
  return face;
}

// The area of `surface` over the square [a, b] x [a, b] of parameters, composite Simpson over
// the two halves either side of the knot k in each direction (the surface is smooth within
// each): kSimpsonIntervals intervals per half, error O(h^4) of a smooth integrand.
constexpr int kSimpsonIntervals = 200;
double square_area(const Handle(Geom_BSplineSurface) & surface, double a, double b, double k) {
  auto simpson = [](double lo, double hi, const auto& f) {
    const double h = (hi - lo) / kSimpsonIntervals;
    double sum = f(lo) + f(hi);
    for (int i = 1; i < kSimpsonIntervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
    return sum * h / 3.0;
  };
  auto halves = [&](const auto& f) { return simpson(a, k, f) + simpson(k, b, f); };
  return halves([&](double u) {
    return halves([&](double v) {
      gp_Pnt p;
      gp_Vec du, dv;
      surface->D1(u, v, p, du, dv);
      return du.Crossed(dv).Magnitude();
    });
  });
}

// Writes `face` as IGES 144 with model-space trim curves only (write.surfacecurve.mode 0).
void write_3d_trims(const TopoDS_Face& face, const std::string& path) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  IGESControl_Controller::Init();
  Interface_Static::SetIVal("write.surfacecurve.mode", 0);
  IGESControl_Writer w("MM", 0);
  const bool added = w.AddShape(face);
  Interface_Static::SetIVal("write.surfacecurve.mode", 1);
  REQUIRE(added);
  w.ComputeModel();
  REQUIRE(w.Write(path.c_str()));
}

// Whether m warns trim_loops_dropped for `face` (its first value), with a gap measured.
bool warns_trims(const Mold& m, int face) {
  return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const Warning& w) {
    return w.code == WarningCode::kTrimLoopsDropped && w.values.size() == 5 &&
           std::get<std::int64_t>(w.values[0]) == face;
  });
}

}  // namespace

TEST_CASE(
    "importers: an IGES face trimmed by closed model-space curves across both seams of a "
    "doubly periodic surface is read trimmed") {
  // A square of parameters 1.5 wide about the seam (the first knot) in u and in v.
  const Handle(Geom_BSplineSurface) surface = periodic_torus();
  REQUIRE(surface->UKnot(1) == surface->VKnot(1));
  const double a = surface->UKnot(1) - 0.75, b = surface->UKnot(1) + 0.75;
  const TopoDS_Face face = square_face(surface, a, b);
  const double area = square_area(surface, a, b, surface->UKnot(1));
  TempDir dir("iges-trims");
  const std::string path = dir.file("periodic-3d-trims.igs");
  write_3d_trims(face, path);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Mold& m = (*file)->mold();
  REQUIRE(m.faces.size() == 1);
  CHECK(m.faces[0].trimmed);
  CHECK(std::abs(m.faces[0].area - area) < kAreaRel * area);
  CHECK_FALSE(warns_trims(m, 0));
}

TEST_CASE(
    "importers: an IGES face whose model-space trim curves do not close is listed untrimmed "
    "with a warning naming it") {
  // The hard mold written by OpenCASCADE's own IGES writer with model-space curves only: each
  // of its four trim edges crosses a seam of the surface and the writer kept one half of its
  // curve, so the loop has four gaps; the reader skips it and the face comes out as the whole
  // torus. The same face with its parameter-space trims is read trimmed, with no warning.
  const std::string hard = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/hard/";
  auto broken = importers::open_mold(hard + "periodic-12x12-seams-3d-trims.igs");
  REQUIRE(broken.ok());
  CHECK(warns_trims((*broken)->mold(), 0));
  CHECK_FALSE((*broken)->mold().faces.at(0).trimmed);
  auto sound = importers::open_mold(hard + "periodic-12x12-seams.igs");
  REQUIRE(sound.ok());
  CHECK_FALSE(warns_trims((*sound)->mold(), 0));
  CHECK((*sound)->mold().faces.at(0).trimmed);
}
