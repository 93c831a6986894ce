// The writers, read back: net.vtk by a small binary legacy-VTK parser written here (counts,
// cells, arrays, NaN), the labels, units and sizes the shop sees, the interior point the DXF
// labels sit on, the atomic-write and determinism promises and the writers' error codes.
// net.step is read back by OpenCASCADE in net_step_test.cpp. The DXF, SVG and VTK files are
// also checked by ezdxf, Python's XML parser and VTK's own reader (tests/exporters/*.py), and
// LibreCAD renders the DXF.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/step_curves.hpp>
#include "pattern/cells.hpp"

#include "export_cases.hpp"

#include <nlohmann/json.hpp>

#include "net_util.hpp"                // exporters/src: the writers' cell enumeration
#include "render/label_placement.hpp"  // exporters/src: where the DXF labels go
#include "test_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

using namespace plyfit;
using namespace plyfit::test;  // export_cases.hpp: Case, cases(), fresh_dir(); slurp()
namespace fs = std::filesystem;

namespace {

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

TEST_CASE("exporters: the registry holds dxf, step, json, svg, vtk, glb") {
  std::vector<std::string> keys;
  for (const auto& e : exporters::registry()) keys.push_back(e.key);
  CHECK(keys == std::vector<std::string>{"dxf", "step", "json", "svg", "vtk", "glb"});
  CHECK(exporters::find_exporter("SVG") != nullptr);
  CHECK(exporters::find_exporter("svg")->files ==
        std::vector<std::string>{"flat.svg", "drape.svg", "shear.svg", "view.svg"});
  CHECK(exporters::find_exporter("pdf") == nullptr);
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
      CHECK(st.error().code == ErrorCode::kFileNotRenamed);
      CHECK(st.error().input == (dir / e.files[blocked]).string());
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
    REQUIRE(!st.ok());
    CHECK(st.error().code == ErrorCode::kFileNotCreated);
    CHECK(st.error().input == (missing / e.files.front()).string());
    CHECK(!fs::exists(missing));
  }
  // The output folder cannot be created (a file is in the way).
  const fs::path dir = fresh_dir("atomic_outdir");
  { std::ofstream(dir / "file") << "x"; }
  const auto st = exporters::write_outputs(c.ctx(), (dir / "file" / "out").string(), {"dxf"});
  REQUIRE(!st.ok());
  CHECK(st.error().code == ErrorCode::kOutputFolderNotCreated);
  CHECK(st.error().input == (dir / "file" / "out").string());
  // An output no writer makes: named, with the known ones.
  const auto unknown = exporters::write_outputs(c.ctx(), fresh_dir("unknown").string(), {"pdf"});
  REQUIRE(!unknown.ok());
  CHECK(unknown.error().code == ErrorCode::kUnknownOutput);
  CHECK(unknown.error().values ==
        std::vector<MessageValue>{std::string("pdf"), exporters::supported_keys()});
}

TEST_CASE("exporters: writer errors are codes naming the file, the curve set or the thread") {
  const auto all = cases();
  const Case& c = *all.front();
  const auto* step = exporters::find_exporter("step");
  REQUIRE(step);
  const fs::path dir = fresh_dir("errors");
  const std::string net_step = (dir / "net.step").string();
  SECTION("a weft run through two coincident nodes") {
    DrapeResult r = c.result;
    const auto runs = r.threads(true);
    const auto run =
        std::find_if(runs.begin(), runs.end(),
                     [](const std::vector<std::uint32_t>& v) { return v.size() >= 2; });
    REQUIRE(run != runs.end());
    r.nodes[(*run)[1]].point = r.nodes[(*run)[0]].point;
    const exporters::ExportContext ctx{c.problem, r, c.surface, &c.flat, c.run, c.options};
    const auto st = step->write(ctx, dir.string());
    REQUIRE(!st.ok());
    CHECK(st.error().code == ErrorCode::kThreadCurveNotBuilt);
    CHECK(st.error().input == net_step);
    CHECK(st.error().values == std::vector<MessageValue>{std::string("weft")});
    CHECK(st.error().cause != nullptr);
    CHECK(!fs::exists(net_step));
  }
  SECTION("a ply boundary loop of fewer than three points on the mold") {
    FlatPattern flat = c.flat;
    REQUIRE(!flat.outline.empty());
    REQUIRE(!flat.outline.front().hole);
    flat.outline.front().points3d.resize(2);
    const exporters::ExportContext ctx{c.problem, c.result, c.surface, &flat, c.run, c.options};
    const auto st = step->write(ctx, dir.string());
    REQUIRE(!st.ok());
    CHECK(st.error().code == ErrorCode::kBoundaryLoopTooSmall);
    CHECK(st.error().input == net_step);
    CHECK(st.error().values == std::vector<MessageValue>{std::string("ply_boundary")});
  }
  SECTION("a curve the kernel refuses (knots out of order), in its set") {
    NurbsCurveData3 bad;
    bad.degree = 1;
    bad.poles = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
    bad.knots = {0.0, 1.0, 0.5, 1.0};
    const auto st = exporters::write_step_curves(net_step, {{"bad set", {bad}}}, {});
    REQUIRE(!st.ok());
    CHECK(st.error().code == ErrorCode::kCurveInvalid);
    CHECK(st.error().input == net_step);
    CHECK(st.error().where == "bad set");
    CHECK(st.error().cause != nullptr);
    CHECK(!fs::exists(net_step));
  }
  SECTION("a file committed twice") {
    exporters::AtomicFile file(net_step);
    file.stream() << "x";
    REQUIRE(file.commit().ok());
    const auto again = file.commit();
    REQUIRE(!again.ok());
    CHECK(again.error().code == ErrorCode::kFileAlreadyClosed);
    CHECK(again.error().input == net_step);
  }
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
    CHECK(files == 9);
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

TEST_CASE(
    "exporters: view.svg draws every cell of a small net, at most 1500 blocks of a large one") {
  auto cell_count = [](const Case& c) {
    const fs::path dir = fresh_dir("view");
    REQUIRE(exporters::find_exporter("svg")->write(c.ctx(), dir.string()).ok());
    const std::string text = slurp(dir / "view.svg");
    std::size_t n = 0;
    for (auto at = text.find("class=\"cell\""); at != std::string::npos;
         at = text.find("class=\"cell\"", at + 1))
      ++n;
    return n;
  };
  const auto all = cases();
  const Case& small = *all.front();
  REQUIRE(plyfit::mapped_cells(small.result).size() <= 1500);
  CHECK(cell_count(small) == plyfit::mapped_cells(small.result).size());
  // A hemisphere of more than 1500 cells: blocks of s x s cells, s the smallest that leaves at
  // most 1500, so more than a quarter of that ((s - 1)^2 < cells / 1500).
  const auto big = make_case("hemisphere", {{"R", 20}},
                             problem(1, {0, 0}, {0, 1}, {{-1, 0}, {1, 0}}, {0, 0, 20}, {1, 0, 0},
                                     {{1, 0, 0}, {-1, 0, 0}}));
  REQUIRE(plyfit::mapped_cells(big->result).size() > 1500);
  const std::size_t blocks = cell_count(*big);
  CHECK(blocks <= 1500);
  CHECK(blocks > 1500 / 4);
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
  using exporters::render::interior_point;
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
    CHECK(exporters::render::inside_outline(loops, p.point));
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
    CHECK(exporters::render::inside_outline(loops, p.point));
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
  using exporters::render::box_inside_outline;
  const auto loops =
      loops_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{4, 4}, {4, 6}, {6, 6}, {6, 4}}});
  CHECK(box_inside_outline(loops, {1, 1}, {3, 9}));
  CHECK(box_inside_outline(loops, {1, 1}, {5, 3.5}));              // below the hole
  CHECK_FALSE(box_inside_outline(loops, {3, 3}, {7, 7}));          // around the hole
  CHECK_FALSE(box_inside_outline(loops, {4.5, 4.5}, {5.5, 5.5}));  // in the hole
  CHECK_FALSE(box_inside_outline(loops, {8, 8}, {11, 9}));         // across the border
  CHECK_FALSE(box_inside_outline(loops, {11, 1}, {12, 2}));        // outside
}

TEST_CASE("exporters: a label's obstacles: distances to a line, a disc and a box") {
  exporters::render::Obstacles o;
  CHECK(std::isinf(o.distance({0, 0})));
  CHECK_FALSE(o.meet({0, 0}, {1, 1}));
  o.segments.push_back({{0, 0}, {10, 0}});
  o.discs.push_back({{20, 0}, 2});
  o.boxes.push_back({{0, 10}, {4, 12}});
  CHECK(std::abs(o.distance({5, 3}) - 3.0) <= 1e-12);   // above the line
  CHECK(std::abs(o.distance({20, 5}) - 3.0) <= 1e-12);  // 5 from the disc's centre
  CHECK(std::abs(o.distance({2, 9}) - 1.0) <= 1e-12);   // below the box
  CHECK(o.distance({2, 11}) < 0);                       // in the box
  CHECK(o.meet({4, -1}, {6, 1}));                       // across the line
  CHECK(o.meet({2, 1}, {3, 10.5}));                     // into the box
  CHECK(o.meet({21, 1}, {30, 30}));                     // the disc's edge (1.41 from (20, 0))
  CHECK_FALSE(o.meet({21.5, 1.5}, {30, 30}));           // 2.12 from its centre
  CHECK_FALSE(o.meet({5, 1}, {6, 9}));                  // between the line and the box
}

TEST_CASE("exporters: the label block keeps clear of a line across the outline") {
  using exporters::render::place_block;
  // A 10 x 10 square cut by a line y = 5 (the base path): a block 4 h wide and h high with
  // half a text height of gap fits in either half, at most h = 2.5 (its width), less by a grid
  // cell's offset from the middle (a grid of 32 cells along the side: 10 / 32).
  const auto loops = loops_of({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}});
  exporters::render::Obstacles path;
  path.segments.push_back({{0, 5}, {10, 5}});
  const exporters::render::BlockShape shape{4.0, 1.0};
  const auto place = place_block(loops, shape, 10.0, 100.0, {0, 0}, path);
  const double cell = 10.0 / exporters::render::kGridCells;
  CHECK(place.h <= 2.5);
  CHECK(place.h >= 2.5 * (1 - cell / 5.0) - 1e-9);
  const Vec2 lo(place.top_left.x(), place.top_left.y() - shape.height_at(place.h));
  const Vec2 hi(place.top_left.x() + shape.width_at(place.h), place.top_left.y());
  CHECK(exporters::render::box_inside_outline(loops, lo, hi));
  const Vec2 gap = Vec2::Constant(exporters::render::kObstacleGap * place.h);
  CHECK_FALSE(path.meet(lo - gap, hi + gap));
  // Without the line, the block is centred in the square (its pole, to kPolePrecisionRel of the
  // square's side), 4 h <= 10.
  const auto free = place_block(loops, shape, 10.0, 100.0, {0, 0});
  CHECK(free.h <= 2.5);
  CHECK(free.h >= 2.5 - 10.0 * exporters::render::kPolePrecisionRel);
}

TEST_CASE(
    "exporters: a label goes to its preferred place, else beside its anchor where it is free") {
  using exporters::render::place_label;
  exporters::render::Obstacles none;
  const Vec2 anchor(0, 0), size(4, 1), preferred(1, 1), right(1, 0);
  CHECK(place_label(anchor, size, preferred, right, 0.5, none) == preferred);
  // Something at the preferred place: the label moves to the right of the anchor first (the
  // direction given), half a unit away, centred on it vertically.
  exporters::render::Obstacles taken;
  taken.boxes.push_back({{0.5, 0.6}, {6, 3}});
  const Vec2 at = place_label(anchor, size, preferred, right, 0.5, taken);
  CHECK_FALSE(taken.meet(at, at + size));
  CHECK(at == Vec2(0.5, -0.5));
  // A line through the anchor along x: no place across it; the first free side above or below.
  exporters::render::Obstacles line;
  line.segments.push_back({{-100, 0}, {100, 0}});
  const Vec2 off = place_label(anchor, size, {-2, -0.5}, right, 0.5, line);
  CHECK_FALSE(line.meet(off, off + size));
  // With something to avoid as well (the drawing), a free place clear of both if there is one
  // within reach; else clear of the obstacles alone.
  exporters::render::Obstacles drawing;
  drawing.boxes.push_back({{-1, -1}, {1, 1}});
  const Vec2 both = place_label(anchor, size, preferred, right, 0.5, none, &drawing);
  CHECK_FALSE(drawing.meet(both, both + size));
  exporters::render::Obstacles everywhere;
  everywhere.boxes.push_back({{-1000, -1000}, {1000, 1000}});
  CHECK(place_label(anchor, size, preferred, right, 0.5, none, &everywhere) == preferred);
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
