// net.step read back by OpenCASCADE's XDE STEP reader (names, curve counts, every node on its
// curve, the 3D ply boundary closed on the mold) and by DRAW; plyfit's STEP curve writer on its
// own.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/step_curves.hpp>

#include "export_cases.hpp"

#include "nurbs_conversion.hpp"  // occt/src: kernel NURBS as OpenCASCADE geometry

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
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

using namespace plyfit;
using namespace plyfit::test;  // export_cases.hpp: Case, cases(), fresh_dir(), slurp()
namespace fs = std::filesystem;

namespace {

// A node lies on its STEP curve within this fraction of the face size (bounding-box
// diagonal): the file's reals read back bit for bit, so what is measured is the curve's
// construction (the cubic interpolation) and OpenCASCADE's projection onto it; the bound is far
// above round-off and far below the spacing.
constexpr double kOnCurveRel = 1e-9;
// A point of the 3D ply boundary is a node, a boundary crossing or a boundary vertex, each
// evaluated on the surface: on the mold within this fraction of its size (the same rounding
// as kOnCurveRel).
constexpr double kOnMoldRel = 1e-9;
// The middle of a boundary segment leaves a curved mold by the chord's sagitta, L^2 / (8 R)
// for a chord L on a radius R. A segment stays within one cell (L <= sqrt(2) d for the spacing
// d); on the cases here (d / R <= 0.2) that is at most 0.05 d: "small against the spacing".
constexpr double kMidSegmentOffSpacing = 0.05;

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

}  // namespace

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
  CHECK(st.error().code == ErrorCode::kCurveRational);
  CHECK(st.error().where == rational.name);
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
