// Face areas (importers/src/face_measure.cpp): the listing's (plyfit info, asked for 1e-6) and
// a described face's (the area report.json gives, asked for 1e-9) against closed forms of
// analytic faces, of a trimmed B-spline face with a hole and of a rational B-spline hemisphere;
// on the shared CAD files: area_corpus_test.cpp.

#include <plyfit/importers/importers.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <Geom2d_Circle.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <catch2/catch.hpp>

#include "face_measure.hpp"  // occt/src
#include "occt/occt_reference.hpp"
#include "occt/write_shapes.hpp"
#include "support/warnings.hpp"

#include <algorithm>
#include <memory>
#include "surface/face.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

// The accuracies the importer asks for (occt_mold.cpp): the listing, and a described face.
constexpr double kListingRel = 1e-6;
constexpr double kDescribedRel = 1e-9;
// OpenCASCADE's STEP writer prints reals with about 15 significant digits: the written faces
// are exact to this, relative.
constexpr double kWrittenRel = 1e-13;

// A bicubic B-spline with interior knots whose poles lie on an affine map of (u, v) at the
// Greville abscissae: by linear precision it is that map exactly, so |S_u x S_v| is constant.
Handle(Geom_BSplineSurface) affine_patch(const gp_Vec& a, const gp_Vec& b) {
  const int deg = 3;
  const std::vector<double> distinct = {0.0, 0.3, 0.55, 1.0};
  std::vector<double> flat;
  TColStd_Array1OfReal knots(1, static_cast<int>(distinct.size()));
  TColStd_Array1OfInteger mults(1, static_cast<int>(distinct.size()));
  for (size_t k = 0; k < distinct.size(); ++k) {
    const int m = (k == 0 || k + 1 == distinct.size()) ? deg + 1 : 1;
    knots(static_cast<int>(k) + 1) = distinct[k];
    mults(static_cast<int>(k) + 1) = m;
    for (int r = 0; r < m; ++r) flat.push_back(distinct[k]);
  }
  const int n = static_cast<int>(flat.size()) - deg - 1;
  std::vector<double> greville(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    greville[static_cast<size_t>(i)] =
        (flat[static_cast<size_t>(i) + 1] + flat[static_cast<size_t>(i) + 2] +
         flat[static_cast<size_t>(i) + 3]) /
        3.0;
  TColgp_Array2OfPnt poles(1, n, 1, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      poles(i + 1, j + 1) = gp_Pnt(5, -3, 2).Translated(a * greville[static_cast<size_t>(i)] +
                                                        b * greville[static_cast<size_t>(j)]);
  return new Geom_BSplineSurface(poles, knots, knots, mults, mults, deg, deg);
}

TopoDS_Wire circle_wire(const Handle(Geom_Surface) & s, const gp_Pnt2d& c, double r, bool ccw) {
  BRepBuilderAPI_MakeEdge edge(new Geom2d_Circle(gp_Ax2d(c, gp_Dir2d(1, 0)), r, ccw), s);
  REQUIRE(edge.IsDone());
  return BRepBuilderAPI_MakeWire(edge.Edge()).Wire();
}

struct Case {
  std::string name;
  TopoDS_Shape shape;
  std::vector<double> areas;  // every face's exact area, any order
};

// A B-spline face trimmed by a circle of radius 0.35 in (u, v) with a hole of radius 0.1 (the
// pcurves are exact circles; written to a file, the trims would become approximations of the
// 3D edges): the affine map scales every (u, v) area by |a x b|.
Case trimmed_affine_patch() {
  const gp_Vec a(40, 5, 2), b(10, 30, -3);
  const Handle(Geom_BSplineSurface) patch = affine_patch(a, b);
  BRepBuilderAPI_MakeFace make(patch, circle_wire(patch, gp_Pnt2d(0.5, 0.45), 0.35, true));
  make.Add(circle_wire(patch, gp_Pnt2d(0.45, 0.5), 0.1, false));
  REQUIRE(make.IsDone());
  return {"trimmed B-spline with a hole",
          make.Face(),
          {kPi * (0.35 * 0.35 - 0.1 * 0.1) * a.Crossed(b).Magnitude()}};
}

std::vector<Case> cases() {
  std::vector<Case> out;
  out.push_back({"cylinder",
                 BRepPrimAPI_MakeCylinder(5, 12).Shape(),
                 {2 * kPi * 5 * 12, 25 * kPi, 25 * kPi}});
  out.push_back({"quarter cylinder",
                 BRepPrimAPI_MakeCylinder(5, 12, kPi / 2).Shape(),
                 {30 * kPi, 60, 60, 25 * kPi / 4, 25 * kPi / 4}});
  const double slant = std::hypot(6.0 - 2.0, 10.0);
  out.push_back({"cone frustum",
                 BRepPrimAPI_MakeCone(6, 2, 10).Shape(),
                 {kPi * (6 + 2) * slant, 36 * kPi, 4 * kPi}});
  out.push_back({"sphere", BRepPrimAPI_MakeSphere(7).Shape(), {4 * kPi * 49}});
  out.push_back({"torus", BRepPrimAPI_MakeTorus(10, 3).Shape(), {4 * kPi * kPi * 10 * 3}});
  // A block with a round hole through it: two planes with a hole, four rectangles and the
  // (reversed) cylinder of the hole.
  BRepAlgoAPI_Cut cut(
      BRepPrimAPI_MakeBox(30, 20, 10).Shape(),
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(15, 10, -5), gp::DZ()), 4, 20).Shape());
  REQUIRE(cut.IsDone());
  out.push_back({"drilled block",
                 cut.Shape(),
                 {600 - 16 * kPi, 600 - 16 * kPi, 300, 300, 200, 200, 2 * kPi * 4 * 10}});
  // A rational B-spline hemisphere (OpenCASCADE's exact conversion of a sphere), R = 9.
  const Handle(Geom_Surface) cap =
      GeomConvert::SurfaceToBSplineSurface(new Geom_RectangularTrimmedSurface(
          new Geom_SphericalSurface(gp_Ax3(), 9), 0, 2 * kPi, 0, kPi / 2));
  out.push_back({"rational B-spline hemisphere",
                 BRepBuilderAPI_MakeFace(cap, Precision::Confusion()).Face(),
                 {2 * kPi * 81}});
  return out;
}

// Sorted areas against sorted expectations, each within `rel`.
void check_areas(std::vector<double> got, std::vector<double> want, double rel) {
  REQUIRE(got.size() == want.size());
  std::sort(got.begin(), got.end());
  std::sort(want.begin(), want.end());
  for (size_t k = 0; k < got.size(); ++k) {
    INFO("exact " << want[k] << ", got " << got[k]);
    CHECK(std::abs(got[k] - want[k]) <= (rel + kWrittenRel) * want[k]);
  }
}

}  // namespace

TEST_CASE("importers: the area of a trimmed B-spline face with a hole against its closed form") {
  const Case c = trimmed_affine_patch();
  const TopoDS_Face f = TopoDS::Face(c.shape);
  for (const double rel : {kListingRel, kDescribedRel}) {
    for (const bool transposed : {false, true}) {
      const auto m = importers::occt::measure_face(f, rel, false, transposed);
      INFO("asked " << rel << (transposed ? " along v" : " along u"));
      CHECK(m.converged);
      check_areas({m.area}, c.areas, rel);
    }
  }
}

TEST_CASE("importers: face areas against closed forms: listed to 1e-6, described to 1e-9") {
  TempDir dir("areas");
  for (const Case& c : cases()) {
    INFO(c.name);
    const std::string path = dir.file("case.step");
    write_step(c.shape, path);
    auto file = importers::open_mold(path);
    REQUIRE(file.ok());
    const Mold& m = (*file)->mold();
    std::vector<double> listed, described;
    for (const auto& f : m.faces) listed.push_back(f.area);
    check_areas(listed, c.areas, kListingRel);
    // A face described after the listing gets its area again, to the described accuracy...
    for (int i = 0; i < (*file)->face_count(); ++i) {
      auto info = (*file)->describe(i);
      REQUIRE(info.ok());
      described.push_back(info->area);
    }
    check_areas(described, c.areas, kDescribedRel);
    // ... and so does one described first.
    auto fresh = importers::open_mold(path);
    REQUIRE(fresh.ok());
    auto first = (*fresh)->describe(0);
    REQUIRE(first.ok());
    CHECK(first->area == described[0]);
    // No warning: every area reached its accuracy.
    CHECK(support::with_codes((*file)->summary().warnings,
                              {WarningCode::kFaceAreaShort, WarningCode::kFaceAreaUnmeasured,
                               WarningCode::kShortAreaFaces, WarningCode::kUnmeasuredFaces})
              .empty());
  }
}

TEST_CASE("importers: a face's area short of its accuracy is a warning with the accuracy reached") {
  using importers::occt::area_warning;
  importers::occt::FaceMeasure m;
  m.area = 200.0;
  m.error = 2e-5;
  m.converged = true;
  CHECK_FALSE(area_warning(m, 1e-9, 3, "#12"));
  m.converged = false;
  auto w = area_warning(m, 1e-9, 3, "#12");
  REQUIRE(w);
  CHECK(w->code == WarningCode::kFaceAreaShort);
  CHECK(support::value(*w, 0) == 3);
  CHECK(support::text(*w, 1) == "#12");
  CHECK(support::value(*w, 2) == 1e-9);
  CHECK(support::value(*w, 3) == 2e-5 / 200.0);
  // No error estimate (OpenCASCADE's integration): the accuracy reached is not given.
  m.error = 0.0;
  w = area_warning(m, 1e-6, 0, "");
  REQUIRE(w);
  CHECK(w->code == WarningCode::kFaceAreaShort);
  CHECK(w->values.size() == 3);
  // Not measured: why, instead.
  m.measured = false;
  m.failure = "the integration gave no finite value";
  w = area_warning(m, 1e-9, 5, "DE 7");
  REQUIRE(w);
  CHECK(w->code == WarningCode::kFaceAreaUnmeasured);
  CHECK(support::value(*w, 0) == 5);
  CHECK(support::text(*w, 1) == "DE 7");
  CHECK(support::text(*w, 2) == m.failure);
}

TEST_CASE("importers: a described face converts on the surface its area was measured on") {
  TempDir dir("measured_surface");
  const std::string path = dir.file("patch.step");
  write_step(trimmed_affine_patch().shape, path);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  REQUIRE((*file)->describe(0).ok());
  auto data = (*file)->convert_face(0);
  REQUIRE(data.ok());
  REQUIRE(data->built != nullptr);
  CHECK(data->built->made_from(data->surface, Tolerances{}));
  // The measured surface is handed over once: a second conversion builds its own (the face is
  // trimmed: its loops need the surface's speeds), from the same data.
  auto again = (*file)->convert_face(0);
  REQUIRE(again.ok());
  REQUIRE(again->built != nullptr);
  CHECK(again->built != data->built);
  CHECK(again->built->made_from(data->surface, Tolerances{}));
  // Face::create takes it.
  const std::shared_ptr<const NurbsSurface> built = data->built;
  auto face = Face::create(std::move(data).value());
  REQUIRE(face.ok());
  CHECK(&face->surface() == built.get());
}
