// Sewing faces of a mold file into a shell (MoldFile::convert_shell), on shells written with
// OpenCASCADE: a box of six loose faces (its orientations as written, or with a face turned
// inwards), a cylinder and its seam, two plates with a known gap, three faces on one edge, and
// bad face lists. The shared CAD files are in shell_corpus_test.cpp.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include <catch2/catch.hpp>

#include "occt/shell_checks.hpp"
#include "occt/write_shapes.hpp"
#include "surface/face.hpp"
#include "surface/shell/shell.hpp"

#include <tuple>

using namespace plyfit;
using namespace plyfit::test;

namespace {

// Writes `shape` as STEP or IGES with the file's precision (uncertainty, resolution) `precision`
// in millimetres.
void write_with_precision(const TopoDS_Shape& shape, const std::string& path, double precision) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Interface_Static::SetIVal("write.precision.mode", 2);  // write.precision.val
  Interface_Static::SetRVal("write.precision.val", precision);
  if (path.find(".igs") != std::string::npos)
    write_iges(shape, path);
  else
    write_step(shape, path);
  Interface_Static::SetIVal("write.precision.mode", 0);
}

// The faces of `shape`, each copied on its own (no edge shared), as one compound.
TopoDS_Shape loose_faces(const TopoDS_Shape& shape, int reverse_face = -1) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  int k = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next(), ++k) {
    TopoDS_Shape f = BRepBuilderAPI_Copy(ex.Current()).Shape();
    if (k == reverse_face) f.Reverse();
    b.Add(c, f);
  }
  return c;
}

// A closed cylinder (R 10, height 25: a lateral face with its seam, two discs) as STEP.
void write_cylinder(const std::string& path) {
  write_with_precision(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 10, 25).Shape(),
                       path, 1e-6);
}

// Two 100 x 100 plates side by side along x = 100, the second raised by `gap` (z).
TopoDS_Shape two_plates(double gap) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0, 100, 0, 100).Face());
  b.Add(c, BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, gap), gp::DZ()), 100, 200, 0, 100).Face());
  return c;
}

}  // namespace

TEST_CASE("importers: a box of six loose faces sews into a closed shell, oriented consistently") {
  TempDir dir("shell_box");
  // The file's own orientations: as the box has them (STEP), as IGES 510 faces without a shell
  // keep them (their surfaces' normals, three of them inwards), and with face 2 or face 0 (the
  // one the sewing orients the others by) turned inwards.
  for (const auto& [name, flipped] : std::vector<std::pair<std::string, int>>{
           {"box.step", -1}, {"box.igs", -1}, {"flipped2.step", 2}, {"flipped0.step", 0}}) {
    INFO(name);
    const std::string path = dir.file(name);
    const gp_Pnt corner(-10, 0, 5), centre(10, 15, 15);
    write_with_precision(loose_faces(BRepPrimAPI_MakeBox(corner, 40, 30, 20).Shape(), flipped),
                         path, 1e-6);
    auto file = importers::open_mold(path);
    REQUIRE(file.ok());
    const Reference ref = read_reference(path, name.find(".igs") != std::string::npos);
    REQUIRE(ref.count() == 6);
    // Independently, by OpenCASCADE: which faces' normals point out of the box; a consistent
    // shell reverses the others (ties: those that disagree with face 0).
    std::vector<bool> out(6);
    int outwards = 0;
    for (int i = 0; i < 6; ++i) {
      const TopoDS_Face f = ref.face(i);
      double u0, u1, v0, v1;
      BRepTools::UVBounds(f, u0, u1, v0, v1);
      GeomLProp_SLProps props(BRep_Tool::Surface(f), 0.5 * (u0 + u1), 0.5 * (v0 + v1), 1,
                              Precision::Confusion());
      REQUIRE(props.IsNormalDefined());
      const gp_Vec n = props.Normal().XYZ() * (f.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0);
      out[i] = n.Dot(gp_Vec(centre, props.Value())) > 0;
      outwards += out[i];
    }
    if (flipped >= 0) CHECK(outwards == 5);
    const bool kept = outwards > 3 || (outwards == 3 && out[0]);
    std::set<int> reversed;
    for (int i = 0; i < 6; ++i)
      if (out[i] != kept) reversed.insert(i);

    auto shell = (*file)->convert_shell({});  // all faces
    INFO((shell.ok() ? std::string() : exporters::describe(shell.error())));
    REQUIRE(shell.ok());
    CHECK(shell->faces.size() == 6);
    CHECK(shell->source_faces == std::vector<int>({0, 1, 2, 3, 4, 5}));
    CHECK(shell->edge_count == 12);
    // The faces meet exactly: the gap is round-off of the part size.
    CHECK(shell->tolerance <= kRoundoffRel * 50.0);
    const auto& warnings = (*file)->summary().warnings;
    if (reversed.empty())
      CHECK(sewing_warnings(warnings).empty());
    else
      CHECK(the_warning(warnings, WarningCode::kFacesReoriented) ==
            std::vector<double>(reversed.begin(), reversed.end()));
    auto [faces, sizes] = kernel_faces(**file, *shell);
    const ShellCheck c = check_shell(*shell, faces, sizes);  // uses opposite everywhere
    CHECK(c.shared == 12);
    CHECK(c.free_runs == 0);
    CHECK(c.vertices - c.shared + 6 == 2);
    check_kernel_shell(*shell, 2, 0);  // a closed shell of genus 0
    check_faces_like_convert_face(**file, *shell, faces, ref, reversed, 300);
    for (const Face& f : faces) {
      const auto& d = f.domain();
      const Vec2 mid(0.5 * (d.u0 + d.u1), 0.5 * (d.v0 + d.v1));
      const Vec3 from_centre = f.eval1(mid).p - Vec3(centre.X(), centre.Y(), centre.Z());
      CHECK((f.normal(mid).n.dot(from_centre) > 0.0) == kept);
    }
  }
}

TEST_CASE("importers: a cylinder's seam is not a shared edge; its two circles are") {
  TempDir dir("shell_cylinder");
  const std::string path = dir.file("cylinder.step");
  write_cylinder(path);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Reference ref = read_reference(path, false);
  REQUIRE(ref.count() == 3);
  auto shell = (*file)->convert_shell({2, 0, 1});
  REQUIRE(shell.ok());
  CHECK(shell->source_faces == std::vector<int>({2, 0, 1}));
  CHECK(shell->edge_count == 2);
  auto [faces, sizes] = kernel_faces(**file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  CHECK(c.shared == 2);
  int closed = 0;
  for (const auto& f : shell->faces) closed += f.closed_u || f.closed_v;
  CHECK(closed == 1);
  // The seam: one free run on each side of the lateral face's domain, nothing else free.
  CHECK(c.free_runs == 2);
  // Closed: no free loop. Its Euler characteristic: the next test.
  check_kernel_shell(*shell, kUnchecked, 0);
  check_faces_like_convert_face(**file, *shell, faces, ref, {}, 300);
}

// The kernel's Shell counts the two sides of a face's seam as one edge (both are in the
// face's loop): 2 for a closed cylinder with its caps, as OpenCASCADE counts.
TEST_CASE("importers: a sewn cylinder's Euler characteristic in the kernel is OpenCASCADE's") {
  TempDir dir("shell_cylinder_euler");
  const std::string path = dir.file("cylinder.step");
  write_cylinder(path);
  const Reference ref = read_reference(path, false);
  TopTools_IndexedMapOfShape vertices, edges;
  TopExp::MapShapes(ref.shape, TopAbs_VERTEX, vertices);
  TopExp::MapShapes(ref.shape, TopAbs_EDGE, edges);
  const int occt_euler = vertices.Extent() - edges.Extent() + ref.count();
  CHECK(occt_euler == 2);  // 2 vertices, 3 edges (2 circles, the seam), 3 faces
  auto shell = importers::load_shell(path, {});
  REQUIRE(shell.ok());
  check_kernel_shell(*shell, occt_euler, 0);
}

TEST_CASE("importers: the sewing closes a gap below the file's precision and reports it") {
  TempDir dir("shell_gap");
  constexpr double kGap = 2e-3;  // mm, between the plates' edges at x = 100
  // Within round-off of the measured gap: the plates' images along the edge differ by kGap in z.
  const double gap_tol = kRoundoffRel * 200.0;
  for (const std::string ext : {"step", "igs"}) {
    INFO(ext);
    const std::string fine = dir.file("fine." + ext), coarse = dir.file("coarse." + ext),
                      capped = dir.file("capped." + ext);
    write_with_precision(two_plates(kGap), fine, kGap / 10);   // the gap is not closed
    write_with_precision(two_plates(kGap), coarse, kGap * 5);  // the gap is closed
    write_with_precision(two_plates(0.05), capped, 1.0);       // precision above the cap
    auto f = importers::open_mold(fine);
    REQUIRE(f.ok());
    auto s = (*f)->convert_shell({0, 1});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 0);
    CHECK(s->tolerance == 0.0);
    CHECK(the_warning((*f)->summary().warnings, WarningCode::kSeparateShells) ==
          std::vector<double>{2, 2});
    auto c = importers::open_mold(coarse);
    REQUIRE(c.ok());
    s = (*c)->convert_shell({0, 1});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 1);
    CHECK(std::abs(s->tolerance - kGap) <= gap_tol);
    CHECK(sewing_warnings((*c)->summary().warnings).empty());
    auto [faces, sizes] = kernel_faces(**c, *s);
    const ShellCheck sc = check_shell(*s, faces, sizes);
    CHECK(sc.shared == 1);
    check_kernel_shell(*s, 1, 1);  // a disc
    CHECK(sc.free_runs == 2);
    // A stated precision of 1 mm is capped at 1e-4 of the shell's size (0.022 mm here): a
    // 0.05 mm gap stays open; an explicit sewing tolerance closes it.
    auto k = importers::open_mold(capped);
    REQUIRE(k.ok());
    s = (*k)->convert_shell({});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 0);
    importers::ImportOptions wide;
    wide.sewing_tolerance = 0.1;
    auto shell = importers::load_shell(capped, {}, wide);
    REQUIRE(shell.ok());
    CHECK(shell->edge_count == 1);
    CHECK(std::abs(shell->tolerance - 0.05) <= gap_tol);
  }
}

TEST_CASE("importers: an edge of three faces is non-manifold: free, with a warning") {
  TempDir dir("shell_fan");
  // Three plates on one line (100, y, 0): two flat ones and one standing up, joined there by
  // OpenCASCADE's non-manifold sewing, so that the file holds one edge of three faces.
  auto quad = [](const gp_Pnt& a, const gp_Pnt& b, const gp_Pnt& c, const gp_Pnt& d) {
    return BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire(), true)
        .Face();
  };
  BRepBuilderAPI_Sewing fan(1e-6);
  fan.SetNonManifoldMode(Standard_True);
  fan.Add(quad(gp_Pnt(0, 0, 0), gp_Pnt(100, 0, 0), gp_Pnt(100, 100, 0), gp_Pnt(0, 100, 0)));
  fan.Add(quad(gp_Pnt(100, 0, 0), gp_Pnt(200, 0, 0), gp_Pnt(200, 100, 0), gp_Pnt(100, 100, 0)));
  fan.Add(quad(gp_Pnt(100, 0, 0), gp_Pnt(100, 100, 0), gp_Pnt(100, 100, 100), gp_Pnt(100, 0, 100)));
  fan.Perform();
  const std::string path = dir.file("fan.step");
  write_with_precision(fan.SewedShape(), path, 1e-6);
  const Reference ref = read_reference(path, false);
  REQUIRE(ref.count() == 3);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(ref.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int of_three = 0;
  for (int e = 1; e <= edge_faces.Extent(); ++e) of_three += edge_faces(e).Extent() == 3;
  REQUIRE(of_three == 1);  // the file really holds it
  std::vector<Warning> warnings;
  auto shell = importers::load_shell(path, {}, {}, &warnings);
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == 0);
  CHECK(the_warning(warnings, WarningCode::kNonManifoldEdges) == std::vector<double>{1});
  CHECK(the_warning(warnings, WarningCode::kSeparateShells) == std::vector<double>{3, 3});
  for (const auto& f : shell->faces)
    for (const auto& loop : f.loops)
      for (auto t : loop.edges) CHECK(t == TrimLoop::kFreeEdge);
}

TEST_CASE("importers: bad face lists for a shell are one-line errors naming the file and face") {
  TempDir dir("shell_errors");
  const std::string path = dir.file("plates.step");
  write_with_precision(two_plates(0.0), path, 1e-6);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  for (const auto& [faces, code, face] : std::vector<std::tuple<std::vector<int>, ErrorCode, int>>{
           {{0, 2}, ErrorCode::kFaceIndexRange, 2},
           {{-1}, ErrorCode::kFaceIndexRange, -1},
           {{1, 0, 1}, ErrorCode::kFaceListedTwice, 1}}) {
    auto s = (*file)->convert_shell(faces);
    REQUIRE_FALSE(s.ok());
    INFO(exporters::describe(s.error()));
    CHECK(exporters::describe(s.error()).rfind(path + ": ", 0) == 0);
    CHECK(s.error().code == code);
    CHECK(s.error().values.at(0) == MessageValue{std::int64_t{face}});
    CHECK(exporters::describe(s.error()).find('\n') == std::string::npos);
  }
  importers::ImportOptions negative;
  negative.sewing_tolerance = -0.01;
  auto bad = importers::load_shell(path, {}, negative);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::kSewingToleranceInvalid);
  CHECK(bad.error().input == path);
  std::vector<Warning> warnings;
  auto missing = importers::load_shell(dir.file("none.step"), {}, {}, &warnings);
  REQUIRE_FALSE(missing.ok());
  CHECK(exporters::describe(missing.error()).find(dir.file("none.step")) != std::string::npos);
  auto ok = importers::load_shell(path, {1, 0}, {}, &warnings);
  REQUIRE(ok.ok());
  CHECK(ok->edge_count == 1);
  CHECK(ok->source_faces == std::vector<int>({1, 0}));
}
