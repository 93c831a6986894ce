// Surfaces of every kind (plane, cylinder, cone, sphere, torus, revolution, extrusion, offset,
// Bézier) and trims with holes, seams and reversed faces: shapes built with OCCT, written to
// STEP and IGES in a temporary folder, imported, and compared with OCCT's reading of the same
// files. Also the unit conversion (files written in inches).

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRep_Builder.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"
#include "occt/write_shapes.hpp"

#include <set>
#include "surface/face.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

/// OpenCASCADE approximates offset surfaces (GeomConvert::SurfaceToBSplineSurface uses
/// GeomConvert_ApproxSurface with a 3D tolerance of 1e-4 model units): a converted offset face
/// is only as close as that, relative to this test's 40 mm face.
constexpr double kOffsetApproxRel = 1e-4 / 40.0;

/// The writers print inch values with about 10 significant digits (IGES) and more (STEP):
/// coordinates read back in mm are exact to this fraction of the part size; a missing or
/// wrong unit conversion is off by a factor 25.4.
constexpr double kWrittenRealsRel = 1e-8;

Handle(Geom_BSplineCurve) spline(const std::vector<gp_Pnt>& pts) {
  Handle(TColgp_HArray1OfPnt) a = new TColgp_HArray1OfPnt(1, static_cast<int>(pts.size()));
  for (size_t i = 0; i < pts.size(); ++i) a->SetValue(static_cast<int>(i) + 1, pts[i]);
  GeomAPI_Interpolate in(a, Standard_False, 1e-9);
  in.Perform();
  REQUIRE(in.IsDone());
  return in.Curve();
}

Handle(Geom_BezierSurface) bezier_patch(const gp_Pnt& o, double size) {
  TColgp_Array2OfPnt p(1, 3, 1, 3);
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j)
      p(i, j) = gp_Pnt(o.X() + size * (i - 1) / 2, o.Y() + size * (j - 1) / 2,
                       o.Z() + ((i == 2 && j == 2) ? size / 3 : 0.0));
  return new Geom_BezierSurface(p);
}

TopoDS_Shape analytic_shapes() {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  b.Add(c, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 10, 20, 30).Shape());
  b.Add(c, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(40, 0, 0), gp::DZ()), 5, 12).Shape());
  b.Add(c, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(60, 0, 0), gp::DZ()), 5, 12, kPi / 2).Shape());
  b.Add(c, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(80, 0, 0), gp::DZ()), 6, 2, 10).Shape());
  b.Add(c, BRepPrimAPI_MakeSphere(gp_Pnt(100, 0, 0), 7).Shape());
  b.Add(c, BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(130, 0, 0), gp::DZ()), 10, 3).Shape());
  const auto profile =
      spline({gp_Pnt(165, 0, 0), gp_Pnt(168, 0, 4), gp_Pnt(166, 0, 8), gp_Pnt(170, 0, 12)});
  const TopoDS_Edge pe = BRepBuilderAPI_MakeEdge(profile).Edge();
  b.Add(c, BRepPrimAPI_MakeRevol(pe, gp_Ax1(gp_Pnt(160, 0, 0), gp::DZ()), 1.5 * kPi).Shape());
  b.Add(c,
        BRepPrimAPI_MakeRevol(BRepBuilderAPI_MakeEdge(
                                  spline({gp_Pnt(195, 0, 0), gp_Pnt(197, 0, 5), gp_Pnt(194, 0, 9)}))
                                  .Edge(),
                              gp_Ax1(gp_Pnt(190, 0, 0), gp::DZ()))
            .Shape());
  const auto arc =
      spline({gp_Pnt(0, 50, 0), gp_Pnt(5, 55, 0), gp_Pnt(10, 52, 0), gp_Pnt(15, 58, 0)});
  b.Add(c, BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeEdge(arc).Edge(), gp_Vec(1, 2, 15)).Shape());
  // An offset of a doubly curved B-spline patch, over part of its range.
  Handle(Geom_Surface) base =
      GeomConvert::SurfaceToBSplineSurface(bezier_patch(gp_Pnt(30, 50, 0), 40));
  Handle(Geom_OffsetSurface) off = new Geom_OffsetSurface(base, 2.0);
  b.Add(c, BRepBuilderAPI_MakeFace(off, 0.1, 0.9, 0.05, 0.8, Precision::Confusion()).Face());
  b.Add(
      c,
      BRepBuilderAPI_MakeFace(bezier_patch(gp_Pnt(80, 50, 0), 20), Precision::Confusion()).Face());
  // A block with a cylindrical hole: planes with a hole, and a reversed inner cylinder.
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(0, 100, 0), 30, 20, 10).Shape();
  const TopoDS_Shape drill =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(15, 110, -5), gp::DZ()), 4, 20).Shape();
  BRepAlgoAPI_Cut cut(block, drill);
  REQUIRE(cut.IsDone());
  b.Add(c, cut.Shape());
  // A located (moved, rotated) cone: geometry must come out with its location applied.
  gp_Trsf t;
  t.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 1, 0)), 0.7);
  t.SetTranslationPart(gp_Vec(50, 100, 20));
  b.Add(c, BRepBuilderAPI_Transform(
               BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 3, 1, 6).Shape(), t, false)
               .Shape());
  return c;
}

// The kind of a surface, named independently of the importer.
std::string kind_of(Handle(Geom_Surface) s) {
  while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  if (s->IsKind(STANDARD_TYPE(Geom_BSplineSurface))) return "bspline";
  if (s->IsKind(STANDARD_TYPE(Geom_BezierSurface))) return "bezier";
  if (s->IsKind(STANDARD_TYPE(Geom_Plane))) return "plane";
  if (s->IsKind(STANDARD_TYPE(Geom_CylindricalSurface))) return "cylinder";
  if (s->IsKind(STANDARD_TYPE(Geom_ConicalSurface))) return "cone";
  if (s->IsKind(STANDARD_TYPE(Geom_SphericalSurface))) return "sphere";
  if (s->IsKind(STANDARD_TYPE(Geom_ToroidalSurface))) return "torus";
  if (s->IsKind(STANDARD_TYPE(Geom_SurfaceOfRevolution))) return "revolution";
  if (s->IsKind(STANDARD_TYPE(Geom_SurfaceOfLinearExtrusion))) return "extrusion";
  if (s->IsKind(STANDARD_TYPE(Geom_OffsetSurface))) return "offset";
  return "other";
}

// Closed in a direction: the surface closes on itself there and the face spans its whole
// range (one period).
bool spans_closed(const TopoDS_Face& f, bool along_u) {
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  double su0, su1, sv0, sv1, fu0, fu1, fv0, fv1;
  s->Bounds(su0, su1, sv0, sv1);
  BRepTools::UVBounds(f, fu0, fu1, fv0, fv1);
  if (along_u) return s->IsUClosed() && std::abs((fu1 - fu0) - (su1 - su0)) <= 1e-9 * (su1 - su0);
  return s->IsVClosed() && std::abs((fv1 - fv0) - (sv1 - sv0)) <= 1e-9 * (sv1 - sv0);
}

std::set<std::string> check_written_file(const std::string& path, bool iges) {
  INFO(path);
  auto file = importers::open_mold(path);
  INFO((file.ok() ? std::string() : exporters::describe(file.error())));
  REQUIRE(file.ok());
  const Mold& m = (*file)->mold();
  const Reference ref = read_reference(path, iges);
  REQUIRE(ref.count() == static_cast<int>(m.faces.size()));
  std::set<std::string> kinds;
  int reversed = 0, closed = 0, with_holes = 0;
  Rng rng(3);
  for (int i = 0; i < ref.count(); ++i) {
    const TopoDS_Face of = ref.face(i);
    const FaceInfo& info = m.faces[i];
    INFO("face " << i << " " << info.kind);
    CHECK(info.kind == kind_of(BRep_Tool::Surface(of)));
    kinds.insert(info.kind);
    auto data = (*file)->convert_face(i);
    INFO((data.ok() ? std::string() : exporters::describe(data.error())));
    REQUIRE(data.ok());
    CHECK(data->reversed == (of.Orientation() == TopAbs_REVERSED));
    CHECK(data->loops.empty() == !info.trimmed);
    CHECK(data->closed_u == spans_closed(of, true));
    CHECK(data->closed_v == spans_closed(of, false));
    reversed += data->reversed;
    closed += data->closed_u || data->closed_v;
    with_holes += info.holes > 0;
    auto face = Face::create(std::move(data).value());
    REQUIRE(face.ok());
    const double worst = check_surface(
        *face, of, 25, rng, info.kind == "offset" ? kOffsetApproxRel : kSurfaceAgreementRel);
    if (info.kind == "offset") WARN("offset face: deviation " << worst << " of the face size");
    if (face->trimmed())
      CHECK(check_contains(*face, face_in_converted_parameters(of), 1200, rng) >= 1000);
  }
  std::string all;
  for (const auto& k : kinds) all += k + " ";
  WARN(path << ": kinds " << all);
  CHECK(reversed > 0);
  CHECK(closed > 0);
  CHECK(with_holes > 0);
  return kinds;
}

}  // namespace

TEST_CASE("importers: surfaces of every kind convert exactly (STEP)") {
  TempDir dir("analytic_step");
  write_step(analytic_shapes(), dir.file("analytic.step"), "MM");
  const auto kinds = check_written_file(dir.file("analytic.step"), false);
  for (const char* k : {"plane", "cylinder", "cone", "sphere", "torus", "revolution", "extrusion",
                        "offset", "bspline"})
    CHECK(kinds.count(k) == 1);
}

TEST_CASE("importers: surfaces of every kind convert exactly (IGES)") {
  TempDir dir("analytic_iges");
  write_iges(analytic_shapes(), dir.file("analytic.igs"), "MM");
  const auto kinds = check_written_file(dir.file("analytic.igs"), true);
  for (const char* k : {"plane", "cylinder", "cone", "sphere", "torus"}) CHECK(kinds.count(k) == 1);
}

TEST_CASE("importers: lengths are converted to millimetres from the file's unit") {
  TempDir dir("units");
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 10, 20, 30).Shape();
  write_step(box, dir.file("inch.step"), "INCH");
  write_iges(box, dir.file("inch.igs"), "IN");
  // The files really hold inches.
  CHECK(read_bytes(dir.file("inch.step")).find("INCH") != std::string::npos);
  for (const std::string name : {"inch.step", "inch.igs"}) {
    INFO(name);
    auto file = importers::open_mold(dir.file(name));
    REQUIRE(file.ok());
    const Mold& m = (*file)->mold();
    INFO("unit " << m.unit);
    CHECK(m.unit.rfind("inch", 0) == 0);
    BBox3 all;
    for (const auto& f : m.faces) {
      all.add(f.bbox.min);
      all.add(f.bbox.max);
    }
    CHECK((all.min - Vec3(1, 2, 3)).norm() <= kWrittenRealsRel * 33);
    CHECK((all.max - Vec3(11, 22, 33)).norm() <= kWrittenRealsRel * 33);
    auto face = importers::load_face(dir.file(name), 0);
    REQUIRE(face.ok());
    const Reference ref = read_reference(dir.file(name), name.find("igs") != std::string::npos);
    CHECK(face->size() == Approx(occt_size(ref.face(0))).epsilon(kWrittenRealsRel));
  }
}
