// The writers, read back by independent readers: net.step by OpenCASCADE's XDE STEP reader
// (names, curve counts, every node on its curve), net.vtk by a small legacy-VTK parser written
// here (counts, arrays, ranges), and the atomic-write and determinism promises. The DXF and
// SVG files are checked by ezdxf and Python's XML parser (tests/exporters/*.py).

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <catch2/catch.hpp>

#include "support/problems.hpp"

#include "net_util.hpp"  // exporters/src: the writers' cell enumeration
#include "test_util.hpp"

#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
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

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

using namespace plyfit;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
// A node lies on its STEP curve within this fraction of the face size (bounding-box
// diagonal): OpenCASCADE writes reals with 12 significant digits, so a pole moves by about
// 1e-12 of the coordinates; the brief asks for 1e-9.
constexpr double kOnCurveRel = 1e-9;

// A drape with everything the writers need, kept alive together.
struct Case {
  std::string name;
  Face face;
  DrapeProblem problem;
  DrapeResult result;
  FlatPattern flat;
  exporters::RunInfo run;
  exporters::ExportOptions options;
  exporters::ExportContext ctx() const { return {problem, result, face, &flat, run, options}; }
};

std::unique_ptr<Case> make_case(const std::string& mold, Result<Face> face, DrapeProblem pb) {
  INFO(mold << ": " << (face.ok() ? std::string() : face.error().message));
  REQUIRE(face.ok());
  auto r = drape(*face, pb);
  INFO((r.ok() ? std::string() : r.error().message));
  REQUIRE(r.ok());
  FlatPattern flat = flat_pattern(*face, *r);
  auto c = std::unique_ptr<Case>(
      new Case{mold, std::move(face).value(), pb, std::move(r).value(), std::move(flat), {}, {}});
  c->run.mold = mold;
  c->run.ply_name = "test ply";
  c->run.material = "plain weave";
  return c;
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
  // A trimmed CATIA face from ../shared/cad (IGES), swept both ways.
  const std::string cad = std::string(PLYFIT_SHARED_DIR) + "/cad/PRO20359-L1.igs";
  v.push_back(make_case(cad, importers::load_face(cad, 0),
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {-687.6, 558.9, 454.4},
                                {0, 1, 0}, {{0, 1, 0}, {0, -1, 0}})));
  return v;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("plyfit_exporters_test_" + name);
  fs::remove_all(p);
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

void check_step(const Case& c, int degree) {
  const fs::path dir = fresh_dir("step");
  exporters::ExportOptions opt = c.options;
  opt.curve_degree = degree;
  const exporters::ExportContext ctx{c.problem, c.result, c.face, &c.flat, c.run, opt};
  const auto* e = exporters::find_exporter("step");
  REQUIRE(e);
  const auto st = e->write(ctx, dir.string());
  INFO((st.ok() ? std::string() : st.error().message));
  REQUIRE(st.ok());
  const auto groups = read_step(dir / "net.step");

  const std::map<std::string, std::vector<std::vector<std::uint32_t>>> expected = {
      {"weft", c.result.threads(true)},
      {"warp", c.result.threads(false)},
      {"base_path", {c.result.base_path}}};
  REQUIRE(groups.size() == 3);
  const double tol = kOnCurveRel * c.face.size();
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
}

// ---------------------------------------------------------------------------------------
// VTK, read by a small parser of the legacy ASCII format.

struct Vtk {
  std::vector<Vec3> points;
  std::vector<std::pair<long, long>> lines;
  std::map<std::string, std::vector<double>> point_data, cell_data;
};

Vtk read_vtk(const fs::path& file) {
  std::ifstream in(file);
  REQUIRE(in);
  std::string line;
  std::getline(in, line);
  REQUIRE(line.rfind("# vtk DataFile Version", 0) == 0);
  std::getline(in, line);  // title
  std::getline(in, line);
  REQUIRE(line == "ASCII");
  std::string word;
  in >> word;
  REQUIRE(word == "DATASET");
  in >> word;
  REQUIRE(word == "POLYDATA");
  Vtk v;
  std::map<std::string, std::vector<double>>* data = nullptr;
  long data_count = 0;
  while (in >> word) {
    if (word == "POINTS") {
      long n = 0;
      std::string type;
      in >> n >> type;
      REQUIRE(type == "double");
      for (long k = 0; k < n; ++k) {
        Vec3 p;
        REQUIRE(static_cast<bool>(in >> p.x() >> p.y() >> p.z()));
        v.points.push_back(p);
      }
    } else if (word == "LINES") {
      long n = 0, size = 0;
      in >> n >> size;
      REQUIRE(size == 3 * n);
      for (long k = 0; k < n; ++k) {
        long two = 0, a = 0, b = 0;
        REQUIRE(static_cast<bool>(in >> two >> a >> b));
        REQUIRE(two == 2);
        v.lines.emplace_back(a, b);
      }
    } else if (word == "POINT_DATA" || word == "CELL_DATA") {
      in >> data_count;
      data = word == "POINT_DATA" ? &v.point_data : &v.cell_data;
    } else if (word == "SCALARS") {
      REQUIRE(data);
      std::string name, type, lut, lut_name;
      int comps = 0;
      in >> name >> type >> comps >> lut >> lut_name;
      REQUIRE(comps == 1);
      REQUIRE(lut == "LOOKUP_TABLE");
      auto& arr = (*data)[name];
      for (long k = 0; k < data_count; ++k) {
        double x = 0;
        REQUIRE(static_cast<bool>(in >> x));
        arr.push_back(x);
      }
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

TEST_CASE("exporters: net.step reads back in OpenCASCADE with named groups and nodes on curves",
          "[slow]") {
  for (const auto& c : cases()) {
    check_step(*c, 1);
    check_step(*c, 3);
  }
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
    {
      std::ofstream tcl(dir / "read.tcl");
      tcl << "pload MODELING XDE OCAF\nReadStep D {" << (dir / "net.step").string() << "}\n"
          << "foreach lab {0:1:1:1 0:1:1:2 0:1:1:3} {\n  XGetShape s D $lab\n"
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
    const std::map<std::string, std::size_t> expected = {{"weft", c->result.threads(true).size()},
                                                         {"warp", c->result.threads(false).size()},
                                                         {"base_path", 1}};
    CHECK(edges == expected);
  }
}

TEST_CASE("exporters: net.vtk parses and matches the drape") {
  for (const auto& c : cases()) {
    INFO(c->name);
    const fs::path dir = fresh_dir("vtk");
    REQUIRE(exporters::find_exporter("vtk")->write(c->ctx(), dir.string()).ok());
    const Vtk v = read_vtk(dir / "net.vtk");
    const DrapeResult& r = c->result;
    std::vector<std::uint32_t> written;
    for (std::uint32_t k = 0; k < r.nodes.size(); ++k)
      if (r.nodes[k].mapped() || r.nodes[k].has(DrapeNode::kExtended)) written.push_back(k);
    REQUIRE(v.points.size() == written.size());
    const auto links = r.links();
    REQUIRE(v.lines.size() == links.size());
    for (const char* name : {"thread_angle", "shear", "status", "on_path"}) {
      INFO(name);
      REQUIRE(v.point_data.count(name) == 1);
      CHECK(v.point_data.at(name).size() == v.points.size());
    }
    REQUIRE(v.cell_data.count("link_kind") == 1);
    CHECK(v.cell_data.at("link_kind").size() == v.lines.size());
    // Points are the nodes' exact positions, in order; the arrays hold their values.
    std::uint64_t status0 = 0, angles = 0;
    for (std::size_t k = 0; k < written.size(); ++k) {
      const DrapeNode& n = r.nodes[written[k]];
      CHECK(v.points[k] == n.point);
      const double g = v.point_data.at("thread_angle")[k];
      const double s = v.point_data.at("shear")[k];
      const double st = v.point_data.at("status")[k];
      CHECK((st == 0.0 || st == 1.0));
      CHECK((st == 0.0) == n.mapped());
      if (st == 0.0) ++status0;
      if (g == -1.0) {
        CHECK(s == -1.0);
      } else {
        ++angles;
        CHECK(g >= 0.0);
        CHECK(g <= kPi);
        CHECK(g == n.thread_angle);
        CHECK(s >= 0.0);
        CHECK(s <= kPi / 2);
        CHECK(std::abs(s - std::abs(kPi / 2 - g)) <= test::kRoundoffRel);
      }
      const double on = v.point_data.at("on_path")[k];
      CHECK((on == 0.0 || on == 1.0));
    }
    CHECK(status0 == r.metrics.nodes.mapped + r.metrics.nodes.auxiliary);
    CHECK(angles == r.metrics.angles);
    for (std::size_t k = 0; k < links.size(); ++k) {
      const auto [a, b] = v.lines[k];
      REQUIRE(a >= 0);
      REQUIRE(b >= 0);
      REQUIRE(a < static_cast<long>(v.points.size()));
      REQUIRE(b < static_cast<long>(v.points.size()));
      CHECK(v.points[a] == r.nodes[links[k].a].point);
      CHECK(v.points[b] == r.nodes[links[k].b].point);
      const double kind = v.cell_data.at("link_kind")[k];
      CHECK(kind == static_cast<double>(static_cast<int>(links[k].kind)));
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
      CHECK(st.error().message.find(e.files[blocked]) != std::string::npos);
      CHECK(st.error().message.find('\n') == std::string::npos);
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

TEST_CASE("exporters: flat.dxf leaves out the thread grid when asked") {
  const auto all = cases();
  Case& c = *all.front();
  auto count_threads = [&](bool on) {
    c.options.dxf_threads = on;
    const fs::path dir = fresh_dir("dxf_threads");
    REQUIRE(exporters::find_exporter("dxf")->write(c.ctx(), dir.string()).ok());
    const std::string text = slurp(dir / "flat.dxf");
    std::size_t n = 0;
    for (std::size_t at = text.find("\n  8\nTHREADS\n"); at != std::string::npos;
         at = text.find("\n  8\nTHREADS\n", at + 1))
      ++n;
    return n;
  };
  CHECK(count_threads(true) > 0);
  CHECK(count_threads(false) == 0);
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
