// The curves of STEP and IGES files (importers::read_curves, occt/src/curve_reader.cpp), on
// files written here with OpenCASCADE: a circle, two arcs, a gap; and through the binary as a
// ply boundary (--boundary FILE.step[:PICK]).

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRep_Builder.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Circ.hxx>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "occt/write_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

using namespace plyfit;
using namespace plyfit::test;
using nlohmann::json;

namespace {

constexpr double kPiC = 3.14159265358979323846;
const gp_Pnt kCentre(50, 30, 0);
constexpr double kRadius = 20.0;

gp_Circ circle() {
  return gp_Circ(gp_Ax2(kCentre, gp::DZ()), kRadius);
}

// The arc of the circle from angle a to b (radians), as an edge.
TopoDS_Edge arc(double a, double b, double shift = 0.0) {
  gp_Circ c = circle();
  c.Translate(gp_Vec(shift, 0, 0));
  return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(c, a, b, true).Value()).Edge();
}

TopoDS_Shape compound(const TopoDS_Edge& a, const TopoDS_Edge& b) {
  TopoDS_Compound c;
  BRep_Builder builder;
  builder.MakeCompound(c);
  builder.Add(c, a);
  builder.Add(c, b);
  return c;
}

// The area enclosed by a closed polyline in the plane z = const (shoelace).
double plane_area(const std::vector<Vec3>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& u = p[i];
    const Vec3& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return std::abs(a) / 2;
}

std::string drape_args(const std::string& boundary, const std::string& out) {
  return "drape --mold builtin:plate --seed 50,30,0 --rosette 1,0,0 --boundary '" + boundary +
         "' --spacing 1 --quiet -o '" + out + "'";
}

// report.json of a drape of the plate inside the boundary file `boundary` (it must succeed).
json drape_report(const std::string& boundary, const Scratch& tmp) {
  const std::string out = tmp.file("out");
  const CliRun r = plyfit_run(drape_args(boundary, out), tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(slurp(out + "/report.json"));
}

}  // namespace

TEST_CASE("occt curves: a STEP or IGES circle reads as one closed curve within the chord") {
  Scratch tmp("curves_circle");
  const TopoDS_Edge edge = BRepBuilderAPI_MakeEdge(circle()).Edge();
  write_step(edge, tmp.file("circle.step"));
  write_iges(edge, tmp.file("circle.igs"));
  for (const std::string name : {"circle.step", "circle.igs"}) {
    INFO(name);
    const importers::ImportOptions options;
    auto r = importers::read_curves(tmp.file(name), options);
    INFO((r ? std::string() : exporters::describe(r.error())));
    REQUIRE(r.ok());
    REQUIRE(r->size() == 1);
    const importers::FileCurve& c = r->front();
    CHECK(c.index == 0);
    CHECK(c.kind == "circle");
    CHECK(c.closed);
    CHECK(c.length == Approx(2 * kPiC * kRadius).epsilon(1e-9));
    // Every point on the circle; the chord's sagitta within curve_chord_rel of the curves'
    // size (their bounding box: 2r x 2r x 0, diagonal 2r sqrt 2, to OpenCASCADE's enlargement).
    const double chord = options.tolerances.curve_chord_rel * 2 * kRadius * std::sqrt(2.0);
    double off = 0.0, sagitta = 0.0;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Vec3& p = c.points[i];
      const Vec3& q = c.points[(i + 1) % c.points.size()];
      off = std::max(off, std::abs(std::hypot(p.x() - 50, p.y() - 30) - kRadius) + std::abs(p.z()));
      const Vec3 mid = (p + q) / 2;
      sagitta = std::max(sagitta, kRadius - std::hypot(mid.x() - 50, mid.y() - 30));
    }
    CHECK(off < 1e-9 * kRadius);
    CHECK(sagitta <= chord * 1.01);
    CHECK(plane_area(c.points) == Approx(kPiC * kRadius * kRadius).epsilon(1e-4));
  }
}

TEST_CASE("occt curves: two arcs are two open curves in file order") {
  Scratch tmp("curves_arcs");
  write_step(compound(arc(0, kPiC), arc(kPiC, 2 * kPiC)), tmp.file("arcs.step"));
  auto r = importers::read_curves(tmp.file("arcs.step"));
  REQUIRE(r.ok());
  REQUIRE(r->size() == 2);
  for (int k = 0; k < 2; ++k) {
    const importers::FileCurve& c = (*r)[static_cast<std::size_t>(k)];
    CHECK(c.index == k);
    CHECK_FALSE(c.closed);
    CHECK(c.length == Approx(kPiC * kRadius).epsilon(1e-9));
  }
}

TEST_CASE("cli: a STEP circle bounds the plate's ply: outline area 400 pi to 0.1 %") {
  Scratch tmp("curves_cli_circle");
  write_step(BRepBuilderAPI_MakeEdge(circle()).Edge(), tmp.file("circle.step"));
  for (const std::string spec : {"circle.step", "circle.step:0"}) {
    INFO(spec);
    const json j = drape_report(tmp.file(spec), tmp);
    const double exact = 400 * kPiC;
    CHECK(j["flat_outline_exact"]["area"].get<double>() == Approx(exact).epsilon(1e-3));
    CHECK(j["ply"]["boundary"]["area"].get<double>() == Approx(exact).epsilon(1e-3));
  }
}

TEST_CASE("cli: two open STEP edges chain into the loop; a gap too large is boundary_gap") {
  Scratch tmp("curves_cli_arcs");
  write_step(compound(arc(0, kPiC), arc(kPiC, 2 * kPiC)), tmp.file("arcs.step"));
  write_iges(compound(arc(0, kPiC), arc(kPiC, 2 * kPiC)), tmp.file("arcs.igs"));
  for (const std::string name : {"arcs.step", "arcs.igs"}) {
    INFO(name);
    const json j = drape_report(tmp.file(name), tmp);
    CHECK(j["flat_outline_exact"]["area"].get<double>() == Approx(400 * kPiC).epsilon(1e-3));
    REQUIRE(j["ply"]["boundary"]["loops"].size() == 1);
  }
  // The second arc 1 mm off: its ends 1 mm from the first's, past 0.1 % of the plate's size.
  write_step(compound(arc(0, kPiC), arc(kPiC, 2 * kPiC, 1.0)), tmp.file("gap.step"));
  const CliRun g = plyfit_run(drape_args(tmp.file("gap.step"), tmp.file("gap")), tmp);
  INFO(g.err);
  CHECK(g.code != 0);
  CHECK(error_code(g) == "boundary_gap");
}

TEST_CASE("cli: STEP curve files: a pick past the curves, an unreadable file") {
  Scratch tmp("curves_cli_errors");
  write_step(BRepBuilderAPI_MakeEdge(circle()).Edge(), tmp.file("circle.step"));
  const CliRun p = plyfit_run(drape_args(tmp.file("circle.step") + ":3", tmp.file("o")), tmp);
  INFO(p.err);
  CHECK(error_code(p) == "curve_not_found");
  spit(tmp.file("junk.step"), "not a step file\n");
  const CliRun u = plyfit_run(drape_args(tmp.file("junk.step"), tmp.file("o")), tmp);
  INFO(u.err);
  CHECK(error_code(u) == "curve_file_unreadable");
  CHECK(u.err.find("junk.step") != std::string::npos);
}

TEST_CASE("cli: info --curves lists a STEP file's curves, as a table and as JSON") {
  Scratch tmp("curves_cli_info");
  write_step(compound(arc(0, kPiC), arc(kPiC, 2 * kPiC)), tmp.file("arcs.step"));
  const CliRun t = plyfit_run("info '" + tmp.file("arcs.step") + "' --curves", tmp);
  INFO(t.err);
  REQUIRE(t.code == 0);
  CHECK(t.out.find("index") != std::string::npos);
  CHECK(t.out.find("circle") != std::string::npos);
  CHECK(t.out.find("2 curves") != std::string::npos);
  const CliRun j = plyfit_run("info '" + tmp.file("arcs.step") + "' --curves --json", tmp);
  INFO(j.err);
  REQUIRE(j.code == 0);
  const json r = json::parse(j.out);
  REQUIRE(r["curves"].size() == 2);
  for (int k = 0; k < 2; ++k) {
    const json& c = r["curves"][static_cast<std::size_t>(k)];
    CHECK(c["index"] == k);
    CHECK(c["kind"] == "circle");
    CHECK(c["closed"] == false);
    CHECK(c["length_mm"].get<double>() == Approx(kPiC * kRadius).epsilon(1e-9));
    // Each arc's ends on the circle, at angles 0 and pi: x = 50 +- 20, y = 30.
    for (const char* end : {"start", "end"}) {
      const json& p = c[end];
      CHECK(std::abs(std::abs(p[0].get<double>() - 50) - kRadius) < 1e-9);
      CHECK(std::abs(p[1].get<double>() - 30) < 1e-9);
    }
  }
  const CliRun both = plyfit_run("info '" + tmp.file("arcs.step") + "' --curves --neighbours", tmp);
  CHECK(both.code == 2);
  CHECK(error_code(both) == "options_exclusive");
}
