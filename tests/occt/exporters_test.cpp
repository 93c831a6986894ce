// The writers, read back by independent readers: net.step by OpenCASCADE's XDE STEP reader
// (names, curve counts, every node on its curve), net.vtk by a small binary legacy-VTK parser
// written here (counts, cells, arrays, NaN), the labels, units and sizes the shop sees, the
// interior point the DXF labels sit on, and the atomic-write and determinism promises. The
// DXF, SVG and VTK files are also checked by ezdxf, Python's XML parser and VTK's own reader
// (tests/exporters/*.py), and LibreCAD renders the DXF.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/step_curves.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "pattern/cells.hpp"
#include "pattern/flat_pattern.hpp"
#include "support/face_of.hpp"
#include "surface/shell/shell.hpp"

#include <unistd.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "support/problems.hpp"

#include "net_util.hpp"          // exporters/src: the writers' cell enumeration
#include "nurbs_conversion.hpp"  // occt/src: kernel NURBS as OpenCASCADE geometry
#include "test_util.hpp"

#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <TCollection_AsciiString.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

using namespace plyfit;
namespace fs = std::filesystem;

namespace {

// A node lies on its STEP curve within this fraction of the face size (bounding-box
// diagonal): OpenCASCADE writes reals with 12 significant digits, so a pole moves by about
// 1e-12 of the coordinates; the brief asks for 1e-9.
constexpr double kOnCurveRel = 1e-9;
// A point of the 3D ply boundary is a node, a boundary crossing or a boundary vertex, each
// evaluated on the surface: on the mold within this fraction of its size (the same rounding
// as kOnCurveRel).
constexpr double kOnMoldRel = 1e-9;
// The middle of a boundary segment leaves a curved mold by the chord's sagitta, L^2 / (8 R)
// for a chord L on a radius R. A segment stays within one cell (L <= sqrt(2) d for the spacing
// d); on the cases here (d / R <= 0.2) that is at most 0.05 d: "small against the spacing".
constexpr double kMidSegmentOffSpacing = 0.05;

// A drape with everything the writers need, kept alive together.
struct Case {
  std::string name;
  MoldSurface surface;                  ///< a face or a shell
  std::vector<NurbsSurfaceData> molds;  ///< the surfaces of its faces
  DrapeProblem problem;
  DrapeResult result;
  FlatPattern flat;
  exporters::RunInfo run;
  exporters::ExportOptions options;
  exporters::ExportContext ctx() const { return {problem, result, surface, &flat, run, options}; }
};

std::unique_ptr<Case> make_case(const std::string& mold,
                                std::shared_ptr<const DrapeSurface> surface,
                                std::vector<NurbsSurfaceData> molds, DrapeProblem pb) {
  auto r = drape(*surface, pb);  // the kernel's own drape() of a Face or Shell
  INFO(mold << ": " << (r.ok() ? std::string() : exporters::describe(r.error())));
  REQUIRE(r.ok());
  FlatPattern flat = flat_pattern(*surface, *r);
  auto c = std::unique_ptr<Case>(new Case{mold,
                                          MoldSurface(std::move(surface)),
                                          std::move(molds),
                                          pb,
                                          std::move(r).value(),
                                          std::move(flat),
                                          {},
                                          {}});
  c->run.mold = mold;
  c->run.ply_name = "test ply";
  c->run.material = "plain weave";
  return c;
}

std::unique_ptr<Case> make_case(const std::string& mold, Result<Face> face, DrapeProblem pb) {
  INFO(mold << ": " << (face.ok() ? std::string() : exporters::describe(face.error())));
  REQUIRE(face.ok());
  std::vector<NurbsSurfaceData> molds = {face->surface().data()};
  return make_case(mold, std::make_shared<const Face>(std::move(face).value()), std::move(molds),
                   std::move(pb));
}

std::unique_ptr<Case> make_case(const std::string& mold, Result<MoldSurface> surface,
                                DrapeProblem pb) {
  INFO(mold << ": " << (surface.ok() ? std::string() : exporters::describe(surface.error())));
  REQUIRE(surface.ok());
  return make_case(mold, Face(test::face_of(*surface)), std::move(pb));
}

// A drape across the faces of built-in shell `name`.
std::unique_ptr<Case> make_shell_case(const std::string& name, DrapeProblem pb) {
  auto data = builtin_shell(name, {});
  REQUIRE(data.ok());
  std::vector<NurbsSurfaceData> molds;
  for (const FaceData& f : data->faces) molds.push_back(f.surface);
  auto shell = Shell::create(std::move(data).value());
  INFO(name << ": " << (shell.ok() ? std::string() : exporters::describe(shell.error())));
  REQUIRE(shell.ok());
  return make_case("builtin:" + name, std::make_shared<const Shell>(std::move(shell).value()),
                   std::move(molds), std::move(pb));
}

std::unique_ptr<Case> make_case(const std::string& mold, std::map<std::string, double> params,
                                DrapeProblem pb) {
  auto fd = builtin_mold(mold, params);
  REQUIRE(fd.ok());
  return make_case("builtin:" + mold, Face::create(std::move(fd).value()), std::move(pb));
}

using support::problem;

// The paper's sphere-octant cases (a) and (c), a base path off the grid (auxiliary points),
// a two-sided sweep on the surface of revolution and a torus.
std::vector<std::unique_ptr<Case>> cases() {
  std::vector<std::unique_ptr<Case>> v;
  v.push_back(make_case("sphere-octant", {},
                        problem(1, {0, 0}, {1, 0}, {{0, 1}}, {0, 0, 20}, {0, 1, 0}, {{0, 1, 0}})));
  v.push_back(
      make_case("sphere-octant", {},
                problem(1, {15, 0}, {1, 1}, {{-1, 1}}, {0, 0, 20}, {0, 1, 0}, {{0, 1, 0}})));
  v.push_back(
      make_case("sphere-octant", {},
                problem(1.3, {0.4, 0.3}, {2, 1}, {{-1, 2}}, {0, 0, 20}, {0, 1, 0}, {{0, 1, 0}})));
  v.push_back(make_case("revolution-third", {},
                        problem(1, {35, 0}, {0, 1}, {{-1, 0}, {1, 0}}, {10, 10 * std::sqrt(3.0), 0},
                                {1, -1, 0}, {{1, -1, 0}, {-1, 1, 0}})));
  v.push_back(make_case("torus", {},
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {40, 0, 0}, {0, 0, 1},
                                {{0, 0, 1}, {0, 0, -1}})));
  // A trimmed face with a hole read from IGES (plyfit's sample dish: the corpus's trimmed
  // CATIA face PRO20359-L1 runs in the exporter case of tests/CMakeLists.txt), swept both ways.
  const std::string dish = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/dish.igs";
  v.push_back(make_case(dish, importers::load_face(dish, 0),
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {18, 0, 4.05}, {0, 1, 0},
                                {{0, 1, 0}, {0, -1, 0}})));
  // A plate with a hole that the cloth flows round: the outline has a hole.
  v.push_back(make_case("plate",
                        {{"W", 100}, {"H", 60}, {"hole_r", 10}, {"hole_x", 50}, {"hole_y", 30}},
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {20, 10, 0}, {0, 1, 0},
                                {{0, 1, 0}, {0, -1, 0}})));
  // A shell: from the flange over the fillet onto the wall, swept both ways.
  v.push_back(make_shell_case("flange-fillet-wall",
                              problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {-20, 30, 0}, {0, 1, 0},
                                      {{0, 1, 0}, {0, -1, 0}})));
  return v;
}

// Scratch folders, one per name and process (test runs of several clones at once, or ctest
// -j, must not share one), removed when the test program ends.
struct ScratchDirs {
  std::vector<fs::path> made;
  ~ScratchDirs() {
    std::error_code ec;
    for (const auto& p : made) fs::remove_all(p, ec);
  }
};
ScratchDirs scratch_dirs;

fs::path fresh_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("plyfit_exporters_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  scratch_dirs.made.push_back(p);
  fs::create_directories(p);
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---------------------------------------------------------------------------------------
// STEP, read back by OpenCASCADE's XDE reader.

struct StepGroup {
  std::vector<Handle(Geom_Curve)> curves;
  std::vector<std::pair<double, double>> ranges;
};

std::map<std::string, StepGroup> read_step(const fs::path& file) {
  STEPCAFControl_Reader reader;
  reader.SetNameMode(Standard_True);
  REQUIRE(reader.ReadFile(file.c_str()) == IFSelect_RetDone);
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  REQUIRE(reader.Transfer(doc));
  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence labels;
  shapes->GetFreeShapes(labels);
  std::map<std::string, StepGroup> out;
  for (int k = 1; k <= labels.Length(); ++k) {
    Handle(TDataStd_Name) name;
    REQUIRE(labels.Value(k).FindAttribute(TDataStd_Name::GetID(), name));
    const std::string key = TCollection_AsciiString(name->Get()).ToCString();
    StepGroup& g = out[key];
    for (TopExp_Explorer ex(shapes->GetShape(labels.Value(k)), TopAbs_EDGE); ex.More(); ex.Next()) {
      double a = 0, b = 0;
      Handle(Geom_Curve) c = BRep_Tool::Curve(TopoDS::Edge(ex.Current()), a, b);
      REQUIRE(!c.IsNull());
      g.curves.push_back(c);
      g.ranges.emplace_back(a, b);
    }
  }
  XCAFApp_Application::GetApplication()->Close(doc);
  return out;
}

// The B-spline behind a (possibly trimmed) curve.
Handle(Geom_BSplineCurve) bspline_of(Handle(Geom_Curve) c) {
  if (auto t = Handle(Geom_TrimmedCurve)::DownCast(c); !t.IsNull()) c = t->BasisCurve();
  return Handle(Geom_BSplineCurve)::DownCast(c);
}

// The ply boundary's sets net.step should hold: `ply_boundary` with the outer loops of the
// outline, `ply_hole_N` with its N-th hole (README, "net.step").
std::map<std::string, std::vector<const OutlineLoop*>> boundary_sets(const FlatPattern& flat) {
  std::map<std::string, std::vector<const OutlineLoop*>> sets;
  int holes = 0;
  for (const OutlineLoop& loop : flat.outline)
    sets[loop.hole ? "ply_hole_" + std::to_string(++holes) : "ply_boundary"].push_back(&loop);
  return sets;
}

// Distance from p to the nearest of `molds` (OpenCASCADE's projection onto each surface).
double mold_distance(const std::vector<Handle(Geom_BSplineSurface)>& molds, const gp_Pnt& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : molds) {
    GeomAPI_ProjectPointOnSurf proj(p, s);
    if (proj.NbPoints() > 0) best = std::min(best, proj.LowerDistance());
  }
  return best;
}

// The ply boundary read back: one closed degree-1 curve per outline loop, through every 3D
// outline point, its corners on the mold and its segments close to it.
void check_boundary(const Case& c, const std::map<std::string, StepGroup>& groups) {
  std::vector<Handle(Geom_BSplineSurface)> molds;
  for (const auto& m : c.molds) molds.push_back(occt::to_occt(m));
  const double tol = kOnCurveRel * c.surface.size();
  const double on_mold = kOnMoldRel * c.surface.size();
  const double mid_tol =
      kMidSegmentOffSpacing * std::max(c.problem.ply.d_weft, c.problem.ply.d_warp);
  const auto expected = boundary_sets(c.flat);
  REQUIRE(expected.count("ply_boundary") == 1);  // every case has an outline
  for (const auto& [name, loops] : expected) {
    INFO(c.name << " group " << name);
    REQUIRE(groups.count(name) == 1);
    const StepGroup& g = groups.at(name);
    REQUIRE(g.curves.size() == loops.size());
    for (std::size_t k = 0; k < loops.size(); ++k) {
      const Handle(Geom_BSplineCurve) b = bspline_of(g.curves[k]);
      REQUIRE(!b.IsNull());
      CHECK(b->Degree() == 1);
      CHECK(b->NbPoles() >= 4);  // a closed loop of three corners or more
      const gp_Pnt a = g.curves[k]->Value(g.ranges[k].first);
      const gp_Pnt z = g.curves[k]->Value(g.ranges[k].second);
      CHECK(a.Distance(z) <= tol);
      double worst_point = 0.0, worst_corner = 0.0, worst_mid = 0.0;
      for (const Vec3& p : loops[k]->points3d) {
        GeomAPI_ProjectPointOnCurve proj(gp_Pnt(p.x(), p.y(), p.z()), g.curves[k],
                                         g.ranges[k].first, g.ranges[k].second);
        REQUIRE(proj.NbPoints() > 0);
        worst_point = std::max(worst_point, proj.LowerDistance());
      }
      for (int i = 1; i <= b->NbPoles(); ++i) {
        worst_corner = std::max(worst_corner, mold_distance(molds, b->Pole(i)));
        if (i > 1) {
          const gp_XYZ mid = 0.5 * (b->Pole(i - 1).XYZ() + b->Pole(i).XYZ());
          worst_mid = std::max(worst_mid, mold_distance(molds, gp_Pnt(mid)));
        }
      }
      CHECK(worst_point <= tol);
      CHECK(worst_corner <= on_mold);
      CHECK(worst_mid <= mid_tol);
    }
  }
}

void check_step(const Case& c, int degree) {
  const fs::path dir = fresh_dir("step");
  exporters::ExportOptions opt = c.options;
  opt.curve_degree = degree;
  const exporters::ExportContext ctx{c.problem, c.result, c.surface, &c.flat, c.run, opt};
  const auto* e = exporters::find_exporter("step");
  REQUIRE(e);
  const auto st = e->write(ctx, dir.string());
  INFO((st.ok() ? std::string() : exporters::describe(st.error())));
  REQUIRE(st.ok());
  const auto groups = read_step(dir / "net.step");

  const std::map<std::string, std::vector<std::vector<std::uint32_t>>> expected = {
      {"weft", c.result.threads(true)},
      {"warp", c.result.threads(false)},
      {"base_path", {c.result.base_path}}};
  REQUIRE(groups.size() == 3 + boundary_sets(c.flat).size());
  const double tol = kOnCurveRel * c.surface.size();
  for (const auto& [name, runs] : expected) {
    INFO(c.name << " degree " << degree << " group " << name);
    REQUIRE(groups.count(name) == 1);
    const StepGroup& g = groups.at(name);
    REQUIRE(g.curves.size() == runs.size());
    REQUIRE(!runs.empty());
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const Handle(Geom_BSplineCurve) b = bspline_of(g.curves[k]);
      REQUIRE(!b.IsNull());
      const int n = static_cast<int>(runs[k].size());
      // Degree 1 always; degree 3 through four nodes or more (the kernel's interpolation
      // gives a line through two points and a quadratic through three).
      CHECK(b->Degree() == (degree == 1 ? 1 : std::min(3, n - 1)));
      double worst = 0.0;
      for (const std::uint32_t id : runs[k]) {
        const Vec3& p = c.result.nodes[id].point;
        GeomAPI_ProjectPointOnCurve proj(gp_Pnt(p.x(), p.y(), p.z()), g.curves[k],
                                         g.ranges[k].first, g.ranges[k].second);
        REQUIRE(proj.NbPoints() > 0);
        worst = std::max(worst, proj.LowerDistance());
      }
      CHECK(worst <= tol);
      // The curve runs from the run's first node to its last.
      const Vec3& p0 = c.result.nodes[runs[k].front()].point;
      const Vec3& p1 = c.result.nodes[runs[k].back()].point;
      const gp_Pnt a = g.curves[k]->Value(g.ranges[k].first);
      const gp_Pnt z = g.curves[k]->Value(g.ranges[k].second);
      CHECK(a.Distance(gp_Pnt(p0.x(), p0.y(), p0.z())) <= tol);
      CHECK(z.Distance(gp_Pnt(p1.x(), p1.y(), p1.z())) <= tol);
    }
  }
  check_boundary(c, groups);
}

// ---------------------------------------------------------------------------------------
// VTK, read by a small parser of the legacy BINARY format (big-endian data blocks).

struct Vtk {
  std::vector<Vec3> points;
  std::vector<std::vector<long>> verts, lines, polys;
  std::map<std::string, std::vector<double>> point_data, cell_data;
};

Vtk read_vtk(const fs::path& file) {
  const std::string text = slurp(file);
  std::size_t at = 0;
  auto line = [&] {
    const std::size_t end = text.find('\n', at);
    REQUIRE(end != std::string::npos);
    std::string l = text.substr(at, end - at);
    at = end + 1;
    return l;
  };
  auto bytes = [&](int n) {
    REQUIRE(at + static_cast<std::size_t>(n) <= text.size());
    std::uint64_t v = 0;
    for (int k = 0; k < n; ++k) v = (v << 8) | static_cast<unsigned char>(text[at++]);
    return v;
  };
  auto int32 = [&] { return static_cast<long>(static_cast<std::int32_t>(bytes(4))); };
  auto float64 = [&] {
    const std::uint64_t u = bytes(8);
    double x = 0;
    std::memcpy(&x, &u, sizeof x);
    return x;
  };
  auto end_block = [&] {
    REQUIRE(at < text.size());
    REQUIRE(text[at] == '\n');
    ++at;
  };
  REQUIRE(line().rfind("# vtk DataFile Version 3.0", 0) == 0);
  line();  // title
  REQUIRE(line() == "BINARY");
  REQUIRE(line() == "DATASET POLYDATA");
  Vtk v;
  std::map<std::string, std::vector<double>>* data = nullptr;
  long data_count = 0;
  while (at < text.size()) {
    std::istringstream head(line());
    std::string word;
    head >> word;
    if (word == "POINTS") {
      long n = 0;
      std::string type;
      head >> n >> type;
      REQUIRE(type == "double");
      for (long k = 0; k < n; ++k) {
        Vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = float64();
        v.points.push_back(p);
      }
      end_block();
    } else if (word == "VERTICES" || word == "LINES" || word == "POLYGONS") {
      long n = 0, size = 0;
      head >> n >> size;
      auto& cells = word == "VERTICES" ? v.verts : word == "LINES" ? v.lines : v.polys;
      long read = 0;
      for (long k = 0; k < n; ++k) {
        const long count = int32();
        REQUIRE(count > 0);
        std::vector<long> ids;
        for (long m = 0; m < count; ++m) ids.push_back(int32());
        read += 1 + count;
        cells.push_back(ids);
      }
      REQUIRE(read == size);
      end_block();
    } else if (word == "POINT_DATA" || word == "CELL_DATA") {
      head >> data_count;
      data = word == "POINT_DATA" ? &v.point_data : &v.cell_data;
    } else if (word == "SCALARS") {
      REQUIRE(data);
      std::string name, type;
      int comps = 0;
      head >> name >> type >> comps;
      REQUIRE(comps == 1);
      REQUIRE((type == "double" || type == "int"));
      REQUIRE(line() == "LOOKUP_TABLE default");
      auto& arr = (*data)[name];
      for (long k = 0; k < data_count; ++k)
        arr.push_back(type == "double" ? float64() : static_cast<double>(int32()));
      end_block();
    } else {
      FAIL("unexpected keyword in net.vtk: " << word);
    }
  }
  return v;
}

}  // namespace

TEST_CASE("exporters: the registry holds dxf, step, json, svg, vtk") {
  std::vector<std::string> keys;
  for (const auto& e : exporters::registry()) keys.push_back(e.key);
  CHECK(keys == std::vector<std::string>{"dxf", "step", "json", "svg", "vtk"});
  CHECK(exporters::find_exporter("SVG") != nullptr);
  CHECK(exporters::find_exporter("svg")->files ==
        std::vector<std::string>{"flat.svg", "drape.svg", "shear.svg"});
  CHECK(exporters::find_exporter("pdf") == nullptr);
}

TEST_CASE(
    "exporters: net.step reads back in OpenCASCADE with named groups, nodes on curves and the "
    "ply boundary closed on the mold",
    "[slow]") {
  for (const auto& c : cases()) {
    check_step(*c, 1);
    check_step(*c, 3);
  }
}

TEST_CASE(
    "exporters: the STEP curve writer's closed polylines and names read back in "
    "OpenCASCADE") {
  // A set of closed 3D polylines (as the ply boundary in 3D will be) and a name that needs
  // escaping, next to an open set.
  const std::vector<std::vector<Vec3>> loops = {
      {Vec3(0, 0, 0), Vec3(10, 0, 1), Vec3(10, 5, 2), Vec3(0, 5, 1)},
      {Vec3(2, 2, 0.5), Vec3(4, 2, 0.5), Vec3(3, 3, 0.5)}};
  auto closed = exporters::polyline_set("ply_boundary", loops, true);
  REQUIRE(closed.ok());
  auto open = exporters::polyline_set("it's a \\ test", {{Vec3(0, 0, 0), Vec3(1, 2, 3)}}, false);
  REQUIRE(open.ok());
  const fs::path dir = fresh_dir("step_curves");
  exporters::StepFileInfo info;
  info.file_name = "curves.step";
  REQUIRE(
      exporters::write_step_curves((dir / "curves.step").string(), {*closed, *open}, info).ok());
  const auto groups = read_step(dir / "curves.step");
  REQUIRE(groups.size() == 2);
  REQUIRE(groups.count("ply_boundary") == 1);
  CHECK(groups.count("it's a \\ test") == 1);
  const StepGroup& g = groups.at("ply_boundary");
  REQUIRE(g.curves.size() == loops.size());
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const Handle(Geom_BSplineCurve) b = bspline_of(g.curves[k]);
    REQUIRE(!b.IsNull());
    CHECK(b->Degree() == 1);
    // Every corner, and back to the first: the poles are the loop's points, exactly.
    REQUIRE(b->NbPoles() == static_cast<int>(loops[k].size()) + 1);
    for (int i = 1; i <= b->NbPoles(); ++i) {
      const Vec3& p = loops[k][static_cast<std::size_t>(i - 1) % loops[k].size()];
      CHECK(b->Pole(i).Distance(gp_Pnt(p.x(), p.y(), p.z())) == 0.0);
    }
  }
  // A rational curve is refused, with the set named.
  exporters::StepCurveSet rational = *open;
  rational.curves[0].weights = {1.0, 2.0};
  const auto st = exporters::step_curves_text({rational}, info);
  REQUIRE_FALSE(st.ok());
  CHECK(exporters::describe(st.error()).find("rational") != std::string::npos);
}

TEST_CASE("exporters: net.step reads back in DRAW (occt-draw) with its names and curve counts") {
  // DRAW, OpenCASCADE's test harness (Debian occt-draw, scripts/install-deps --test), reads the
  // file with its own commands: ReadStep into an XDE document, the product names and the edges
  // of each.
  if (std::system("command -v occt-draw > /dev/null 2>&1") != 0) {
    WARN("skipped: occt-draw is not installed (scripts/install-deps --test)");
    return;
  }
  for (const auto& c : cases()) {
    INFO(c->name);
    const fs::path dir = fresh_dir("draw");
    REQUIRE(exporters::find_exporter("step")->write(c->ctx(), dir.string()).ok());
    std::map<std::string, std::size_t> expected = {{"weft", c->result.threads(true).size()},
                                                   {"warp", c->result.threads(false).size()},
                                                   {"base_path", 1}};
    for (const auto& [name, loops] : boundary_sets(c->flat)) expected[name] = loops.size();
    {
      std::ofstream tcl(dir / "read.tcl");
      tcl << "pload MODELING XDE OCAF\nReadStep D {" << (dir / "net.step").string() << "}\n"
          << "foreach lab {";
      for (std::size_t k = 1; k <= expected.size(); ++k) tcl << " 0:1:1:" << k;
      tcl << "} {\n  XGetShape s D $lab\n"
          << "  puts \"group [GetName D $lab] [llength [explode s e]]\"\n}\nexit\n";
    }
    const std::string out = (dir / "draw.txt").string();
    const std::string cmd =
        "timeout 120 occt-draw -b -f '" + (dir / "read.tcl").string() + "' > '" + out + "' 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    std::ifstream in(out);
    std::map<std::string, std::size_t> edges;
    for (std::string line; std::getline(in, line);) {
      std::istringstream ls(line);
      std::string word, name;
      std::size_t n = 0;
      if (ls >> word >> name >> n && word == "group") edges[name] = n;
    }
    CHECK(edges == expected);
  }
}

TEST_CASE(
    "exporters: net.vtk holds the nodes, links and mapped cells, in degrees, NaN where undefined") {
  for (const auto& c : cases()) {
    INFO(c->name);
    const fs::path dir = fresh_dir("vtk");
    REQUIRE(exporters::find_exporter("vtk")->write(c->ctx(), dir.string()).ok());
    const Vtk v = read_vtk(dir / "net.vtk");
    const DrapeResult& r = c->result;
    std::vector<std::uint32_t> written;
    std::uint64_t beyond = 0;
    for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
      if (r.nodes[k].mapped() || r.nodes[k].has(DrapeNode::kExtended)) written.push_back(k);
      if (!r.nodes[k].mapped() && r.nodes[k].has(DrapeNode::kExtended)) ++beyond;
    }
    REQUIRE(v.points.size() == written.size());
    const auto links = r.links();
    const auto cells = plyfit::mapped_cells(r);
    REQUIRE(v.verts.size() == beyond);
    REQUIRE(v.lines.size() == links.size());
    REQUIRE(v.polys.size() == cells.size());
    for (const char* name : {"thread_angle_deg", "shear_deg", "status", "on_path"}) {
      INFO(name);
      REQUIRE(v.point_data.count(name) == 1);
      CHECK(v.point_data.at(name).size() == v.points.size());
    }
    const std::size_t ncells = v.verts.size() + v.lines.size() + v.polys.size();
    for (const char* name : {"cell_kind", "shear_deg"}) {
      INFO(name);
      REQUIRE(v.cell_data.count(name) == 1);
      CHECK(v.cell_data.at(name).size() == ncells);
    }
    // Points are the nodes' exact positions, in order; the arrays hold their values.
    std::uint64_t status0 = 0, angles = 0;
    for (std::size_t k = 0; k < written.size(); ++k) {
      const DrapeNode& n = r.nodes[written[k]];
      CHECK(v.points[k] == n.point);
      const double g = v.point_data.at("thread_angle_deg")[k];
      const double s = v.point_data.at("shear_deg")[k];
      const double st = v.point_data.at("status")[k];
      CHECK((st == 0.0 || st == 1.0));
      CHECK((st == 0.0) == n.mapped());
      if (st == 0.0) ++status0;
      CHECK(std::isnan(g) == !(n.mapped() && n.has(DrapeNode::kHasAngle)));
      if (std::isnan(g)) {
        CHECK(std::isnan(s));
      } else {
        ++angles;
        CHECK(std::abs(g - n.thread_angle * kRadToDeg) <= test::kRoundoffRel * 180.0);
        CHECK(g >= 0.0);
        CHECK(g <= 180.0);
        CHECK(std::abs(s - std::abs(90.0 - g)) <= test::kRoundoffRel * 180.0);
      }
      const double on = v.point_data.at("on_path")[k];
      CHECK((on == 0.0 || on == 1.0));
      CHECK((on == 1.0) == n.has(DrapeNode::kOnPath));
    }
    CHECK(status0 == r.metrics.nodes.mapped + r.metrics.nodes.auxiliary);
    CHECK(angles == r.metrics.angles);
    // Vertices: the nodes beyond the face (status 1).
    for (std::size_t k = 0; k < v.verts.size(); ++k) {
      REQUIRE(v.verts[k].size() == 1);
      CHECK(v.point_data.at("status")[static_cast<std::size_t>(v.verts[k][0])] == 1.0);
      CHECK(v.cell_data.at("cell_kind")[k] == 4.0);
      CHECK(std::isnan(v.cell_data.at("shear_deg")[k]));
    }
    for (std::size_t k = 0; k < links.size(); ++k) {
      REQUIRE(v.lines[k].size() == 2);
      const long a = v.lines[k][0], b = v.lines[k][1];
      REQUIRE(a >= 0);
      REQUIRE(b >= 0);
      REQUIRE(a < static_cast<long>(v.points.size()));
      REQUIRE(b < static_cast<long>(v.points.size()));
      CHECK(v.points[static_cast<std::size_t>(a)] == r.nodes[links[k].a].point);
      CHECK(v.points[static_cast<std::size_t>(b)] == r.nodes[links[k].b].point);
      const std::size_t cell = v.verts.size() + k;
      CHECK(v.cell_data.at("cell_kind")[cell] ==
            static_cast<double>(static_cast<int>(links[k].kind)));
      CHECK(std::isnan(v.cell_data.at("shear_deg")[cell]));
    }
    // Polygons: the kernel's mapped cells, corner by corner, with their shear in degrees.
    for (std::size_t k = 0; k < cells.size(); ++k) {
      REQUIRE(v.polys[k].size() == cells[k].nodes.size());
      double shear = -1.0;
      for (std::size_t m = 0; m < cells[k].nodes.size(); ++m) {
        const DrapeNode& n = r.nodes[cells[k].nodes[m]];
        CHECK(v.points[static_cast<std::size_t>(v.polys[k][m])] == n.point);
        if (n.has(DrapeNode::kHasAngle))
          shear = std::max(shear, std::abs(kPi / 2 - n.thread_angle));
      }
      const std::size_t cell = v.verts.size() + links.size() + k;
      CHECK(v.cell_data.at("cell_kind")[cell] == 3.0);
      const double cs = v.cell_data.at("shear_deg")[cell];
      if (shear < 0) {
        CHECK(std::isnan(cs));
      } else {
        CHECK(std::abs(cs - shear * kRadToDeg) <= test::kRoundoffRel * 180.0);
      }
    }
  }
}

TEST_CASE("exporters: a failed write leaves neither the file nor a temporary file") {
  const auto all = cases();
  const Case& c = *all.front();
  for (const auto& e : exporters::registry()) {
    for (std::size_t blocked = 0; blocked < e.files.size(); ++blocked) {
      INFO(e.key << " blocked at " << e.files[blocked]);
      // A folder where the file should go: the rename into place fails.
      const fs::path dir = fresh_dir("atomic");
      fs::create_directory(dir / e.files[blocked]);
      const auto st = e.write(c.ctx(), dir.string());
      REQUIRE(!st.ok());
      CHECK(exporters::describe(st.error()).find(e.files[blocked]) != std::string::npos);
      CHECK(exporters::describe(st.error()).find('\n') == std::string::npos);
      // Files before the blocked one are whole; nothing else is there.
      std::set<std::string> present;
      for (const auto& entry : fs::directory_iterator(dir))
        present.insert(entry.path().filename().string());
      std::set<std::string> expected(e.files.begin(), e.files.begin() + blocked + 1);
      CHECK(present == expected);
      for (std::size_t k = 0; k < blocked; ++k) CHECK(fs::is_regular_file(dir / e.files[k]));
    }
    // A folder that does not exist: nothing is created.
    const fs::path missing = fresh_dir("atomic_missing") / "absent";
    const auto st = e.write(c.ctx(), missing.string());
    CHECK(!st.ok());
    CHECK(!fs::exists(missing));
  }
  // The output folder cannot be created (a file is in the way).
  const fs::path dir = fresh_dir("atomic_outdir");
  { std::ofstream(dir / "file") << "x"; }
  const auto st = exporters::write_outputs(c.ctx(), (dir / "file" / "out").string(), {"dxf"});
  CHECK(!st.ok());
}

TEST_CASE("exporters: equal inputs give equal bytes") {
  const auto all = cases();
  for (const auto& c : all) {
    INFO(c->name);
    std::vector<std::string> keys;
    for (const auto& e : exporters::registry()) keys.push_back(e.key);
    const fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
    REQUIRE(exporters::write_outputs(c->ctx(), a.string(), keys).ok());
    REQUIRE(exporters::write_outputs(c->ctx(), b.string(), keys).ok());
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(a)) {
      INFO(entry.path().filename());
      CHECK(slurp(entry.path()) == slurp(b / entry.path().filename()));
      ++files;
    }
    CHECK(files == 7);
  }
}

TEST_CASE("exporters: flat.dxf has no thread grid unless asked for one") {
  const auto all = cases();
  Case& c = *all.front();
  auto dxf = [&](bool on) {
    c.options.dxf_threads = on;
    const fs::path dir = fresh_dir("dxf_threads");
    REQUIRE(exporters::find_exporter("dxf")->write(c.ctx(), dir.string()).ok());
    return slurp(dir / "flat.dxf");
  };
  auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  };
  CHECK_FALSE(exporters::ExportOptions{}.dxf_threads);  // the default: a cutter cuts every line
  const std::string on = dxf(true), off = dxf(false);
  CHECK(count(on, "\n  8\nTHREADS\n") > 0);
  CHECK(count(off, "THREADS") == 0);  // neither entities nor the layer
  CHECK(count(off, "\n  8\nOUTLINE\n") == 1);
}

TEST_CASE("exporters: flat.dxf labels name the mold file, not its folder, with real degree signs") {
  const auto all = cases();
  Case& c = *all.front();
  c.run.mold = "/some/where/deep/molds/wing-skin.stp";
  c.options.ply_angle_deg = -45;
  const fs::path dir = fresh_dir("dxf_labels");
  REQUIRE(exporters::find_exporter("dxf")->write(c.ctx(), dir.string()).ok());
  const std::string text = slurp(dir / "flat.dxf");
  CHECK(text.find("\n  1\nMOLD: wing-skin.stp face 0\n") != std::string::npos);
  CHECK(text.find("/some/where") == std::string::npos);
  CHECK(text.find("\n  3\nANSI_1252\n") != std::string::npos);
  // The degree sign is the cp1252 byte 0xB0, never AutoCAD's %%d code.
  CHECK(text.find("\n  1\nPLY ANGLE: -45\xb0\n") != std::string::npos);
  CHECK(text.find("%%d") == std::string::npos);
  CHECK(text.find("%%D") == std::string::npos);
}

TEST_CASE("exporters: report.json spells the file's unit one way") {
  const auto all = cases();
  Case& c = *all.front();
  for (const auto& [given, expected] : std::vector<std::pair<std::string, std::string>>{
           {"mm", "millimetre"},
           {"millimetre", "millimetre"},
           {"millimetre (MM)", "millimetre"},
           {"MILLIMETRE", "millimetre"},
           {"inch (IN)", "inch"},
           {"INCH", "inch"},
           {"unspecified (millimetre assumed)", "unspecified (millimetre assumed)"}}) {
    INFO(given);
    c.run.mold_unit = given;
    const auto j = nlohmann::json::parse(exporters::report_json(c.ctx()));
    CHECK(j["mold"]["unit"] == expected);
  }
}

TEST_CASE("exporters: flat.svg is sized in millimetres, one user unit per millimetre") {
  const auto all = cases();
  const Case& c = *all.front();
  const fs::path dir = fresh_dir("svg_mm");
  REQUIRE(exporters::find_exporter("svg")->write(c.ctx(), dir.string()).ok());
  const std::string text = slurp(dir / "flat.svg");
  const auto svg = text.find("<svg ");
  REQUIRE(svg != std::string::npos);
  const std::string head = text.substr(svg, text.find('>', svg) - svg);
  auto attr = [&](const std::string& name) {
    const auto at = head.find(" " + name + "=\"");
    REQUIRE(at != std::string::npos);
    const auto from = at + name.size() + 3;
    return head.substr(from, head.find('"', from) - from);
  };
  const std::string w = attr("width"), h = attr("height");
  REQUIRE(w.size() > 2);
  CHECK(w.substr(w.size() - 2) == "mm");
  CHECK(h.substr(h.size() - 2) == "mm");
  CHECK(attr("viewBox") == "0 0 " + w.substr(0, w.size() - 2) + " " + h.substr(0, h.size() - 2));
}

// The interior point the DXF labels sit on, on outlines with known answers.
std::vector<OutlineLoop> loops_of(const std::vector<std::vector<Vec2>>& polys) {
  std::vector<OutlineLoop> out;
  for (const auto& p : polys) {
    OutlineLoop l;
    l.points = p;
    out.push_back(l);
  }
  return out;
}

TEST_CASE("exporters: the labels' interior point is the centre of a largest inscribed circle") {
  using exporters::detail::interior_point;
  constexpr double kPrecision = 1e-4;
  // A 4 x 2 rectangle: the inscribed circle has radius 1, its centre on the line y = 1.
  {
    const auto loops = loops_of({{{0, 0}, {4, 0}, {4, 2}, {0, 2}}});
    const auto p = interior_point(loops, kPrecision);
    REQUIRE(p.found);
    CHECK(std::abs(p.radius - 1.0) <= kPrecision);
    CHECK(std::abs(p.point.y() - 1.0) <= kPrecision);
    CHECK(p.point.x() >= 1.0 - kPrecision);
    CHECK(p.point.x() <= 3.0 + kPrecision);
  }
  // A square frame (10 x 10 with a 6 x 6 hole): the ring is 2 wide, but the largest circle
  // sits in a corner, touching two outer edges and the hole's corner: centre (x, x) with
  // x = sqrt(2) (2 - x), radius x = 4 - 2 sqrt(2). Not in the hole (where the centroid is).
  {
    const auto loops =
        loops_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{2, 2}, {2, 8}, {8, 8}, {8, 2}}});
    const auto p = interior_point(loops, kPrecision);
    REQUIRE(p.found);
    CHECK(std::abs(p.radius - (4 - 2 * std::sqrt(2.0))) <= kPrecision);
    CHECK(exporters::detail::inside_outline(loops, p.point));
    const Vec2 q = p.point;
    CHECK_FALSE((q.x() > 2 && q.x() < 8 && q.y() > 2 && q.y() < 8));
  }
  // An L (two 1-wide arms of length 10): the circle in its corner touches the two outer edges
  // and the inner corner (1, 1): radius x with x = sqrt(2) (1 - x), x = 2 - sqrt(2). The L's
  // centroid (about (2.6, 2.6)) is outside it.
  {
    const auto loops = loops_of({{{0, 0}, {10, 0}, {10, 1}, {1, 1}, {1, 10}, {0, 10}}});
    const auto p = interior_point(loops, kPrecision);
    REQUIRE(p.found);
    CHECK(std::abs(p.radius - (2 - std::sqrt(2.0))) <= kPrecision);
    CHECK(exporters::detail::inside_outline(loops, p.point));
  }
  // A regular 64-gon of circumradius 10: the centre, radius 10 cos(pi / 64).
  {
    std::vector<Vec2> ring;
    for (int k = 0; k < 64; ++k)
      ring.emplace_back(10 * std::cos(2 * kPi * k / 64), 10 * std::sin(2 * kPi * k / 64));
    const auto p = interior_point(loops_of({ring}), kPrecision);
    REQUIRE(p.found);
    CHECK(std::abs(p.radius - 10 * std::cos(kPi / 64)) <= kPrecision);
    CHECK(p.point.norm() <= std::sqrt(2 * 10 * kPrecision));  // radius falls off quadratically
  }
  CHECK_FALSE(interior_point({}, kPrecision).found);
}

TEST_CASE("exporters: a box lies inside an outline when no edge meets it") {
  using exporters::detail::box_inside_outline;
  const auto loops =
      loops_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{4, 4}, {4, 6}, {6, 6}, {6, 4}}});
  CHECK(box_inside_outline(loops, {1, 1}, {3, 9}));
  CHECK(box_inside_outline(loops, {1, 1}, {5, 3.5}));              // below the hole
  CHECK_FALSE(box_inside_outline(loops, {3, 3}, {7, 7}));          // around the hole
  CHECK_FALSE(box_inside_outline(loops, {4.5, 4.5}, {5.5, 5.5}));  // in the hole
  CHECK_FALSE(box_inside_outline(loops, {8, 8}, {11, 9}));         // across the border
  CHECK_FALSE(box_inside_outline(loops, {11, 1}, {12, 2}));        // outside
}

TEST_CASE("exporters: the writers' mapped cells are the kernel's (their area is flat_area)") {
  for (const auto& c : cases()) {
    INFO(c->name);
    const DrapeResult& r = c->result;
    double area = 0.0;
    for (const auto& cell : exporters::detail::mapped_cells(r)) {
      for (std::size_t k = 1; k + 1 < cell.nodes.size(); ++k) {
        const Vec2 p0 = r.nodes[cell.nodes[0]].ply, p1 = r.nodes[cell.nodes[k]].ply,
                   p2 = r.nodes[cell.nodes[k + 1]].ply;
        area += 0.5 * std::abs(cross2(p1 - p0, p2 - p0));
      }
    }
    REQUIRE(r.metrics.flat_area > 0.0);
    CHECK(std::abs(area - r.metrics.flat_area) <= test::kRoundoffRel * r.metrics.flat_area);
  }
}
