// Multi-face molds: a kernel ShellData written by the mold writer as one STEP or IGES file
// (faces sewn by OpenCASCADE) reads back through the importers face by face, each surface bit
// for bit, with its orientation and name; OpenCASCADE's own reading finds one valid shell whose
// shared edges are the shell's. Shells built here from exact analytic patches: two plates side
// by side, a plate cut along its diagonal into two trimmed triangles, two sphere octants
// sharing a meridian and the pole, and an octant cut from the equator to the pole (a trimmed
// face with a collapsed edge).

#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "geometry/analytic_surfaces.hpp"
#include "surface/shell/shell.hpp"

#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "samples/sample_list.hpp"
#include "test_util.hpp"

#include <filesystem>
#include <map>

using namespace plyfit;
using namespace plyfit::test;

namespace {

constexpr std::int32_t kFree = TrimLoop::kFreeEdge;

// The plate [x0, x1] x [0, h] in z = 0 with u = x, v = y.
NurbsSurfaceData plate(double x0, double x1, double h) {
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = {x0, x0, x1, x1};
  s.knots_v = {0, 0, h, h};
  s.poles = {Vec3(x0, 0, 0), Vec3(x0, h, 0), Vec3(x1, 0, 0), Vec3(x1, h, 0)};
  return s;
}

FaceData face(NurbsSurfaceData s, std::vector<Vec2> loop, std::vector<std::int32_t> tags,
              const std::string& name) {
  FaceData f;
  f.surface = std::move(s);
  f.loops.push_back({std::move(loop), std::move(tags)});
  f.name = name;
  return f;
}

// The border of the domain [u0, u1] x [v0, v1], counter-clockwise from (u0, v0).
std::vector<Vec2> border(const NurbsSurfaceData& s) {
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  return {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)};
}

struct Case {
  std::string name;
  ShellData shell;
};

std::vector<Case> cases() {
  std::vector<Case> v;
  {  // Two plates side by side: the segment x = 50 is shared (the left plate's right side).
    ShellData s;
    const auto a = plate(0, 50, 60), b = plate(50, 100, 60);
    s.faces.push_back(face(a, border(a), {kFree, 0, kFree, kFree}, "left"));
    s.faces.push_back(face(b, border(b), {kFree, kFree, kFree, 0}, "right"));
    s.edge_count = 1;
    v.push_back({"plates", s});
  }
  {  // One plate surface cut along its diagonal: two trimmed triangles, the diagonal shared.
    ShellData s;
    const auto p = plate(0, 100, 60);
    s.faces.push_back(
        face(p, {Vec2(0, 0), Vec2(100, 0), Vec2(100, 60)}, {kFree, kFree, 0}, "lower"));
    s.faces.push_back(
        face(p, {Vec2(0, 0), Vec2(100, 60), Vec2(0, 60)}, {0, kFree, kFree}, "upper"));
    s.edge_count = 1;
    v.push_back({"triangles", s});
  }
  {  // Two sphere octants (R 20, longitudes 0..90 and 90..180): the meridian at 90 degrees is
     // shared; u = 0 is the pole (a collapsed edge), u = 1 the equator.
    ShellData s;
    const auto a = sphere_patch(20, 0, kPi / 2, 0, kPi / 2);
    const auto b = sphere_patch(20, 0, kPi / 2, kPi / 2, kPi);
    s.faces.push_back(face(a, border(a), {kFree, kFree, 0, kFree}, "octant-1"));
    s.faces.push_back(face(b, border(b), {0, kFree, kFree, kFree}, "octant-2"));
    s.edge_count = 1;
    v.push_back({"octants", s});
  }
  {  // One sphere octant cut along a (u, v) diagonal from the equator at longitude 0 to the
     // pole: the first piece is trimmed with the collapsed pole edge in its loop.
    ShellData s;
    const auto o = sphere_patch(20, 0, kPi / 2, 0, kPi / 2);
    const auto c = border(o);  // c[0], c[3] at the pole (u = u0)
    s.faces.push_back(face(o, {c[0], c[1], c[3]}, {kFree, 0, kFree}, "cut-1"));
    s.faces.push_back(face(o, {c[1], c[2], c[3]}, {kFree, kFree, 0}, "cut-2"));
    s.edge_count = 1;
    v.push_back({"octant-cut", s});
  }
  return v;
}

bool is_iges(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".igs") == 0;
}

TopoDS_Shape read_occt(const std::string& path, bool iges) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  if (iges) {
    IGESControl_Reader r;
    REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
    r.TransferRoots();
    return r.OneShape();
  }
  STEPControl_Reader r;
  REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
  r.TransferRoots();
  return r.OneShape();
}

// Edges of `shape` bounding two of its faces (seams, bounding one face twice, and collapsed
// edges at poles, not counted).
int shared_edges(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape map;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, map);
  int n = 0;
  for (int i = 1; i <= map.Extent(); ++i)
    n += map(i).Extent() == 2 && !BRep_Tool::Degenerated(TopoDS::Edge(map.FindKey(i)));
  return n;
}

// Writes `shell` to `path` and checks the file: the importers read every face back by its name,
// its surface bit for bit, its orientation kept; OpenCASCADE's own reading finds one valid shell
// whose shared edges are the shell's.
void check_shell_file(const ShellData& shell, const std::string& name, const std::string& path) {
  INFO(path);
  exporters::MoldWriteOptions wo;
  wo.name = name;
  const Status st = exporters::write_shell(shell, path, wo);
  INFO((st.ok() ? std::string() : exporters::describe(st.error())));
  REQUIRE(st.ok());
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Mold& m = (*file)->mold();
  REQUIRE(m.faces.size() == shell.faces.size());
  std::map<std::string, int> by_name;
  for (const auto& f : m.faces) by_name[f.name] = f.index;
  for (size_t i = 0; i < shell.faces.size(); ++i) {
    const FaceData& f = shell.faces[i];
    const std::string face_name = f.name.empty() ? "face " + std::to_string(i) : f.name;
    INFO("face " << face_name);
    REQUIRE(by_name.count(face_name) == 1);
    auto back = (*file)->convert_face(by_name[face_name]);
    REQUIRE(back.ok());
    CHECK(back->reversed == f.reversed);
    const NurbsSurfaceData& a = back->surface;
    const NurbsSurfaceData& b = f.surface;
    CHECK(a.degree_u == b.degree_u);
    CHECK(a.degree_v == b.degree_v);
    CHECK(a.knots_u == b.knots_u);
    CHECK(a.knots_v == b.knots_v);
    CHECK(a.weights == b.weights);
    REQUIRE(a.poles.size() == b.poles.size());
    for (size_t k = 0; k < a.poles.size(); ++k) CHECK(a.poles[k] == b.poles[k]);
  }
  const TopoDS_Shape shape = read_occt(path, is_iges(path));
  int shells = 0;
  for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next()) ++shells;
  CHECK(shells == 1);
  CHECK(shared_edges(shape) == shell.edge_count);
  CHECK(BRepCheck_Analyzer(shape).IsValid());
}

}  // namespace

TEST_CASE("samples: a shell written as one file reads back face by face, bit for bit") {
  Scratch tmp("shells");
  for (const auto& c : cases())
    for (const char* ext : {".step", ".igs"})
      check_shell_file(c.shell, c.name, tmp.file(c.name + ext));
}

TEST_CASE("samples: every built-in sample shell reads back face by face (STEP and IGES)") {
  Scratch tmp("sample_shells");
  for (const auto& s : sample_shells()) {
    auto spec = parse_builtin_spec(s.spec).value();
    const ShellData shell = builtin_shell(spec.first, spec.second).value();
    for (const char* ext : {".step", ".igs"})
      check_shell_file(shell, s.file, tmp.file(s.file + ext));
  }
}

TEST_CASE("samples: the committed sample shells are what the mold writer writes today") {
  Scratch tmp("sample_shells_bytes");
  for (const auto& s : sample_shells()) {
    auto spec = parse_builtin_spec(s.spec).value();
    const ShellData shell = builtin_shell(spec.first, spec.second).value();
    for (const char* ext : {".step", ".igs"}) {
      const std::string name = s.file + ext;
      INFO(name << " (regenerate with scripts/make-sample-molds)");
      exporters::MoldWriteOptions wo;
      wo.name = s.file;
      REQUIRE(exporters::write_shell(shell, tmp.file(name), wo).ok());
      const std::string committed = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/" + name;
      REQUIRE(std::filesystem::exists(committed));
      CHECK(slurp(tmp.file(name)) == slurp(committed));
    }
  }
}

TEST_CASE("samples: the shell writer refuses bad shells, naming the file and the face") {
  Scratch tmp("shells_bad");
  ShellData empty;
  auto st = exporters::write_shell(empty, tmp.file("e.step"));
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == ErrorCode::kShellNoFaces);
  CHECK(st.error().input == tmp.file("e.step"));
  ShellData bad = cases().front().shell;
  bad.faces[1].loops[0].edges.pop_back();
  st = exporters::write_shell(bad, tmp.file("b.igs"));
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == ErrorCode::kWriterEdgeTags);
  CHECK(st.error().input == tmp.file("b.igs"));
  CHECK(st.error().face == 1);
  CHECK(st.error().values == std::vector<MessageValue>{std::int64_t{3}, std::int64_t{4}});
  bad = cases().front().shell;
  bad.faces[0].loops[0].points[2] = Vec2(70, 60);  // off the left plate's domain
  st = exporters::write_shell(bad, tmp.file("b.step"));
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().code == ErrorCode::kWriterLoopOffDomain);
  CHECK(st.error().input == tmp.file("b.step"));
  CHECK(st.error().face == 0);
  CHECK(st.error().values == std::vector<MessageValue>{std::int64_t{0}});
  CHECK_FALSE(std::filesystem::exists(tmp.file("b.step")));
  CHECK_FALSE(std::filesystem::exists(tmp.file("b.igs")));
}
