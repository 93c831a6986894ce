// Sewing faces of the shared CAD files (../shared/cad) into shells: the deflector's 18 faces
// (occ22470.igs, a closed shell), the 4 parametric-spline patches of surf114.igs and the 4
// panels of trj7_c2-td-203.stp (neither shares a border), and the cornetta's 110 faces; and
// drapes over them.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include "drape/drape.hpp"
#include "surface/shell/shell.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "occt/shell_checks.hpp"
#include "support/net_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

/// The importer's documented cap on the sewing tolerance, relative to the shell's size.
constexpr double kSewingCapRel = 1e-4;

// A shared file opened by plyfit and read by OpenCASCADE's own reader.
struct SharedFile {
  std::unique_ptr<importers::MoldFile> file;
  Reference ref;
  double cap = 0.0;  // the largest sewing tolerance the importer allows on all of it
};

SharedFile open_shared(const std::string& name, int faces) {
  const std::string path = shared_cad(name);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  SharedFile f{std::move(file).value(), read_reference(path, name.find(".igs") != name.npos)};
  REQUIRE(f.ref.count() == faces);
  Bnd_Box all;
  BRepBndLib::Add(f.ref.shape, all);
  f.cap = kSewingCapRel * std::sqrt(all.SquareExtent());
  return f;
}

// Edges of a shape that bound two different faces, by OpenCASCADE.
int occt_shared_edges(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int shared = 0;
  for (int e = 1; e <= edge_faces.Extent(); ++e)
    shared += edge_faces(e).Extent() == 2 && !edge_faces(e).First().IsSame(edge_faces(e).Last());
  return shared;
}

// Sews every face of a file whose faces share no edge: as many shells as faces, a warning;
// the kernel's Shell finds `euler` and `free_loops` (check_kernel_shell).
ShellCheck sew_apart(SharedFile& f, int euler, int free_loops) {
  const int n = f.ref.count();
  auto shell = f.file->convert_shell({});
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == 0);
  CHECK(shell->tolerance == 0.0);
  CHECK(the_warning(f.file->summary().warnings, WarningCode::kSeparateShells) ==
        std::vector<double>{double(n), double(n)});  // faces, shells
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 1000);
  check_kernel_shell(*shell, euler, free_loops);
  return c;
}

}  // namespace

TEST_CASE("importers: the deflector's 18 faces (occ22470.igs) sew into one closed shell") {
  SharedFile f = open_shared("occ22470.igs", 18);
  // OpenCASCADE's own analysis of the file's shell: every edge bounds two faces, no free
  // boundary, and its Euler characteristic.
  const int occt_shared = occt_shared_edges(f.ref.shape);
  TopTools_IndexedMapOfShape vertices, edges;
  TopExp::MapShapes(f.ref.shape, TopAbs_VERTEX, vertices);
  TopExp::MapShapes(f.ref.shape, TopAbs_EDGE, edges);
  const int occt_euler = vertices.Extent() - edges.Extent() + f.ref.count();
  ShapeAnalysis_FreeBounds free_bounds(f.ref.shape);
  TopTools_IndexedMapOfShape free_edges;
  TopExp::MapShapes(free_bounds.GetClosedWires(), TopAbs_EDGE, free_edges);
  TopExp::MapShapes(free_bounds.GetOpenWires(), TopAbs_EDGE, free_edges);
  CHECK(free_edges.Extent() == 0);
  CHECK(occt_shared == edges.Extent());
  CHECK(occt_euler == 2);  // a closed shell of genus 0

  auto shell = f.file->convert_shell(f.file->all_faces());
  REQUIRE(shell.ok());
  CHECK(shell->faces.size() == 18);
  CHECK(shell->edge_count == occt_shared);
  CHECK(sewing_warnings(f.file->summary().warnings).empty());
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  CHECK(c.shared == occt_shared);
  CHECK(c.free_runs == free_edges.Extent());
  CHECK(c.vertices - c.shared + 18 == occt_euler);
  check_kernel_shell(*shell, occt_euler, 0);
  // The gap closed is no larger than the tolerances OpenCASCADE's reader gave the edges.
  double edge_tol = 0.0;
  for (int e = 1; e <= edges.Extent(); ++e)
    edge_tol = std::max(edge_tol, BRep_Tool::Tolerance(TopoDS::Edge(edges(e))));
  CHECK(shell->tolerance <= 2 * edge_tol);
  WARN("occ22470: " << c.shared << " shared edges, gap " << shell->tolerance
                    << " mm, worst use-to-use distance " << c.worst_ratio << " of the allowed");
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 1000);
}

TEST_CASE("importers: surf114's four patches cross each other but share no border") {
  SharedFile f = open_shared("surf114.igs", 4);
  // Independently: no border of one patch runs along a border of another within the largest
  // sewing tolerance the importer allows (1e-4 of the size), so no edge can be shared.
  for (int i = 0; i < 4; ++i)
    for (TopExp_Explorer ex(f.ref.face(i), TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e)) continue;
      BRepAdaptor_Curve c(e);
      for (int j = 0; j < 4; ++j) {
        if (j == i) continue;
        double far = 0.0;
        for (int s = 0; s <= 10; ++s) {
          const gp_Pnt p =
              c.Value(c.FirstParameter() + s * (c.LastParameter() - c.FirstParameter()) / 10);
          BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(p).Vertex(),
                                       BRepTools::OuterWire(f.ref.face(j)));
          REQUIRE(d.IsDone());
          far = std::max(far, d.Value());
        }
        CHECK(far > f.cap);
      }
    }
  // ... though they cross: every patch touches the tube (face 1).
  for (int i : {0, 2, 3}) {
    BRepExtrema_DistShapeShape d(f.ref.face(1), f.ref.face(i));
    REQUIRE(d.IsDone());
    CHECK(d.Value() <= f.cap);
  }
  // The patches' own topology (tubes, a collapsed end) is not checked here.
  CHECK(sew_apart(f, kUnchecked, kUnchecked).shared == 0);
}

TEST_CASE("importers: trj7's four panels lie apart: four shells, no shared edge") {
  SharedFile f = open_shared("trj7_c2-td-203.stp", 4);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      BRepExtrema_DistShapeShape d(f.ref.face(i), f.ref.face(j));
      REQUIRE(d.IsDone());
      CHECK(d.Value() > f.cap);
    }
  // One loop of free edges per panel: four discs.
  CHECK(sew_apart(f, 4, 4).free_runs == 4);
}

TEST_CASE("importers: the cornetta's 110 faces sew into one shell like the file's own", "[slow]") {
  SharedFile f = open_shared("bug27693_cornetta-step.stp", 110);
  auto shell = f.file->convert_shell({});
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == occt_shared_edges(f.ref.shape));
  CHECK(sewing_warnings(f.file->summary().warnings).empty());
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  WARN("cornetta: " << c.shared << " shared edges, " << c.free_runs << " free runs, gap "
                    << shell->tolerance << " mm, worst use-to-use distance " << c.worst_ratio
                    << " of the allowed");
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 300);
  check_kernel_shell(*shell, kUnchecked, kUnchecked);
}

namespace {

Shell sewn_shell(const std::string& name) {
  auto data = importers::load_shell(shared_cad(name), {});
  REQUIRE(data.ok());
  auto sh = Shell::create(std::move(data).value());
  INFO(name << ": " << (sh.ok() ? "" : exporters::describe(sh.error())));
  REQUIRE(sh.ok());
  return std::move(sh).value();
}

// A bounded ply W x H started at its middle, base path along ply y, swept both ways.
DrapeProblem centred_problem(double d, double W, double H, const Vec3& start, const Vec3& normal) {
  DrapeProblem pb;
  pb.ply.d_weft = pb.ply.d_warp = d;
  pb.ply.rect = Vec2(W, H);
  pb.ply.start = Vec2(W / 2, H / 2);
  pb.ply.base_dir = Vec2(0, 1);
  pb.ply.sweeps = {Vec2(1, 0), Vec2(-1, 0)};
  pb.start = start;
  pb.base_normal = normal;
  pb.sweeps = {normal, -normal};
  return pb;
}

}  // namespace

TEST_CASE("importers: a ply drapes over the deflector's 18 sewn faces, across its creases") {
  // A ply 100 along its base path (up the outer wall, face 10, from the point and normal
  // `plyfit info --face 10` gives) and 200 across it, swept both ways along the wall: the
  // cloth wraps the ends of the deflector, over creases of up to 151 degrees (the rim lip).
  const Shell sh = sewn_shell("occ22470.igs");
  REQUIRE(sh.face_count() == 18);
  const Vec3 start(100.09345, 79.1264305, 55.1308847);
  const Vec3 normal(0.977279697, -0.211953753, 0.0);
  DrapeProblem pb = centred_problem(2.0, 100, 200, start, normal);
  pb.ply.base_dir = Vec2(1, 0);
  pb.ply.sweeps = {Vec2(0, 1), Vec2(0, -1)};
  auto r = drape(sh, pb);
  REQUIRE(r.ok());
  support::check_clean_crossing(*r);
  CHECK(r->metrics.crease_angle_max > 150.0 * kDegToRad);
  CHECK(r->metrics.edge_length_max_rel < 1e-9);
  CHECK(r->metrics.surface_distance_max < 1e-9 * sh.size());
  int faces = 0;
  for (const auto& f : r->metrics.faces) faces += f.mapped > 0;
  CHECK(faces >= 5);
  CHECK(r->metrics.nodes.mapped > 5000);
}

TEST_CASE("importers: faces that share no edge drape as the one face the start is on") {
  // surf114's four patches and trj7's four panels sew into separate shells: a drape over all
  // of them stays on the face it starts on and is that face's drape, node for node (the
  // sample scenes surf114-blob and trj7-panel).
  struct Case {
    const char* file;
    int face;
    double d, W, H, lock_deg;
    Vec3 start;
  };
  for (const Case& c : {Case{"surf114.igs", 3, 2.0, 80, 80, 50, Vec3(-32, 19, 100)},
                        Case{"trj7_c2-td-203.stp", 2, 5.0, 300, 300, 90, Vec3(150, 600, 230)}}) {
    INFO(c.file);
    const Shell sh = sewn_shell(c.file);
    auto one = importers::load_face(shared_cad(c.file), c.face);
    REQUIRE(one.ok());
    const DrapeProblem pb = centred_problem(c.d, c.W, c.H, c.start, Vec3(1, 0, 0));
    DrapeOptions opt;
    opt.lock_angle = c.lock_deg * kDegToRad;
    auto a = drape(sh, pb, opt);
    auto b = drape(*one, pb, opt);
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    CHECK(support::seam_gaps(*a) == 0);
    CHECK(support::same_net(*a, *b, 1e-9 * c.d) > 100);
    REQUIRE(a->metrics.faces.size() == 4);  // the shell's faces are the file's, in order
    for (int k = 0; k < 4; ++k) CHECK((a->metrics.faces[k].mapped > 0) == (k == c.face));
  }
}
