// The importers against the real CAD files of ../shared/cad: counts from PROPERTIES.txt (as
// read with OCCT 7.6 by whoever wrote it), surfaces against OCCT's evaluation of the original
// faces, trims against OCCT's classifier.

#include <plyfit/importers/importers.hpp>

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "occt/occt_reference.hpp"
#include "support/warnings.hpp"

#include "surface/face.hpp"

#include <BRepMesh_IncrementalMesh.hxx>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

using namespace plyfit;
using namespace plyfit::test;

namespace {

struct Expected {
  int faces = -1, bspline = 0, rational = -1, bs_trimmed = -1, bs_with_holes = -1;
  int maxdeg_u = -1, maxdeg_v = -1, maxpoles = -1;
  std::map<std::string, int> types;
  std::string schema;
  /// A line in words ("58 faces (8 B-spline ..., 28 cylinders ...; 21 trimmed, 12 with holes)"):
  /// faces, kinds, and trimmed faces and faces with holes over every face, not only B-splines.
  bool in_words = false;
  int trimmed = -1, with_holes = -1;
};

// The facts of a line in words: "N faces", "N B-spline", "N cylinders", ..., "N trimmed",
// "N with holes".
void read_words(const std::string& text, Expected& e) {
  e.in_words = true;
  e.bspline = -1;
  auto count = [&](const std::string& what) {
    const std::regex re("(\\d+) " + what);
    std::smatch m;
    return std::regex_search(text, m, re) ? std::stoi(m[1]) : -1;
  };
  e.faces = count("faces");
  const std::pair<const char*, const char*> kinds[] = {
      {"B-spline", "bspline"}, {"cylinders", "cylinder"}, {"planes", "plane"},
      {"tori", "torus"},       {"cones", "cone"},         {"spheres", "sphere"}};
  for (const auto& [words, kind] : kinds)
    if (const int n = count(words); n >= 0) e.types[kind] = n;
  e.trimmed = count("trimmed");
  e.with_holes = count("with holes");
}

// key=value pairs of the fourth and fifth columns of PROPERTIES.txt.
std::map<std::string, Expected> read_properties() {
  std::ifstream in(shared_cad("PROPERTIES.txt"));
  REQUIRE(in);
  std::map<std::string, Expected> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '|');) cols.push_back(c);
    REQUIRE(cols.size() >= 4);
    std::string file = cols[0];
    file.erase(file.find_last_not_of(' ') + 1);
    Expected e;
    std::stringstream kv(cols[3] + " " + (cols.size() > 4 ? cols[4] : ""));
    for (std::string tok; kv >> tok;) {
      const auto eq = tok.find('=');
      if (eq == std::string::npos) continue;
      const std::string k = tok.substr(0, eq), v = tok.substr(eq + 1);
      if (k == "faces") e.faces = std::stoi(v);
      if (k == "bspline") e.bspline = std::stoi(v);
      if (k == "rational") e.rational = std::stoi(v);
      if (k == "bs_trimmed") e.bs_trimmed = std::stoi(v);
      if (k == "bs_with_holes") e.bs_with_holes = std::stoi(v);
      if (k == "maxpoles") e.maxpoles = std::stoi(v);
      if (k == "schema") e.schema = v;
      if (k == "maxdeg") {
        e.maxdeg_u = std::stoi(v.substr(0, v.find('x')));
        e.maxdeg_v = std::stoi(v.substr(v.find('x') + 1));
      }
      if (k == "types") {
        std::stringstream ts(v);
        for (std::string t; std::getline(ts, t, ',');)
          e.types[t.substr(0, t.find(':'))] = std::stoi(t.substr(t.find(':') + 1));
      }
    }
    if (e.faces < 0) read_words(cols[2], e);
    out[file] = e;
  }
  return out;
}

// OpenCASCADE's areas (BRepGProp asked for 1e-12) are off by up to 2.2e-4 on these files
// (bug27693_cornetta-step.stp faces 4 to 104, trj7 face 1: against plyfit's integration along u
// and along v, which agree to 1e-11, area_test.cpp); they still tell the faces apart.
constexpr double kOcctAreaRel = 5e-4;
// The listed box is the box of points sampled on the face (its boundary, 64 points per edge,
// and a 32 x 32 grid inside): it lies within the true box and misses extremes between samples
// by at most this fraction of its diagonal (1.7e-3 at worst on the test files).
constexpr double kBoxSampledRel = 3e-3;
// Deflection of the reference mesh, relative to the face's diagonal.
constexpr double kMeshDeflectionRel = 1e-4;

// The listed box against the box of OpenCASCADE's mesh of the face (its nodes lie on the face
// and the face within the deflection of its triangles): not beyond the mesh box by more than
// the deflection, not short of it by more than kBoxSampledRel.
void check_box(const BBox3& listed, const TopoDS_Face& f) {
  REQUIRE_FALSE(listed.empty);
  const double diag = listed.diagonal(), defl = kMeshDeflectionRel * diag;
  TopoDS_Face copy = TopoDS::Face(f.Located(f.Location()));
  BRepTools::Clean(copy);
  BRepMesh_IncrementalMesh mesh(copy, defl, Standard_False, 0.1, Standard_False);
  Bnd_Box b;
  BRepBndLib::Add(copy, b, Standard_True);
  REQUIRE_FALSE(b.IsVoid());
  b.SetGap(0.0);
  double x0, y0, z0, x1, y1, z1;
  b.Get(x0, y0, z0, x1, y1, z1);
  const Vec3 lo(x0, y0, z0), hi(x1, y1, z1);
  const double beyond = std::max((lo - listed.min).maxCoeff(), (listed.max - hi).maxCoeff());
  const double short_of = std::max((listed.min - lo).maxCoeff(), (hi - listed.max).maxCoeff());
  INFO("listed box beyond the mesh's by " << beyond / diag << ", short of it by " << short_of / diag
                                          << " of its diagonal");
  CHECK(beyond <= defl);
  CHECK(short_of <= kBoxSampledRel * diag);
}

const std::vector<std::string> kFiles = {
    "BUC50025.igs",       "PRO20359-L1.igs",       "occ22470.igs",
    "surf114.igs",        "example_45_faces.iges", "bug27693_cornetta-step.stp",
    "trj7_c2-td-203.stp", "trj8_c2-db-214.stp",    "bm2_ec_exhaust-A.stp"};

// Calls check(face, reference) on every face of a shared file, converted (its trims and
// orientation as the mold lists them) and as OpenCASCADE reads it.
template <typename Check>
void for_each_file_face(const std::string& name, Check&& check) {
  auto file = importers::open_mold(shared_cad(name));
  REQUIRE(file.ok());
  const Reference ref = read_reference(shared_cad(name), is_iges(name));
  REQUIRE(ref.count() == static_cast<int>((*file)->mold().faces.size()));
  for (int i = 0; i < ref.count(); ++i) {
    INFO("face " << i);
    auto data = (*file)->convert_face(i);
    REQUIRE(data.ok());
    CHECK(data->loops.empty() == !(*file)->mold().faces[i].trimmed);
    CHECK(data->reversed == (*file)->mold().faces[i].reversed);
    auto face = Face::create(std::move(data).value());
    REQUIRE(face.ok());
    check(*face, ref.face(i));
  }
}

// Checks every face of a file against OCCT's surface; reports the worst deviation.
void check_file_surfaces(const std::string& name) {
  INFO(name);
  Rng rng(7);
  double worst = 0.0;
  for_each_file_face(name, [&](const Face& face, const TopoDS_Face& ref) {
    worst = std::max(worst, check_surface(face, ref, 30, rng));
  });
  WARN(name << ": worst surface deviation " << worst << " of the face size");
}

void check_file_contains(const std::string& name) {
  INFO(name);
  Rng rng(11);
  int trimmed = 0;
  for_each_file_face(name, [&](const Face& face, const TopoDS_Face& ref) {
    const TopoDS_Face classified = face_in_converted_parameters(ref);
    // Trimmed faces: >= 1000 compared points; untrimmed ones (no loops) a few hundred, which
    // also checks that calling them untrimmed was right.
    const int n = face.trimmed() ? 1300 : 300;
    const int compared = check_contains(face, classified, n, rng);
    if (face.trimmed()) {
      ++trimmed;
      CHECK(compared >= 1000);
    }
  });
  WARN(name << ": " << trimmed << " trimmed faces compared with the classifier");
}

}  // namespace

TEST_CASE("importers: trim polylines follow the face edges within the trim tolerance") {
  for (const std::string name :
       {"bug27693_cornetta-step.stp", "occ22470.igs", "example_45_faces.iges", "PRO20359-L1.igs"}) {
    const double worst = check_trim_accuracy(shared_cad(name));
    WARN(name << ": worst trim deviation " << worst << " of the allowed");
  }
}

TEST_CASE("importers: every shared CAD file lists the faces PROPERTIES.txt describes") {
  const auto props = read_properties();
  REQUIRE(props.size() == kFiles.size());
  for (const auto& name : kFiles) {
    INFO(name);
    REQUIRE(props.count(name) == 1);
    const Expected& e = props.at(name);
    auto file = importers::open_mold(shared_cad(name));
    REQUIRE(file.ok());
    const Mold& m = (*file)->mold();
    CHECK(static_cast<int>(m.faces.size()) == e.faces);
    std::map<std::string, int> kinds;
    int bspline = 0, rational = 0, trimmed = 0, holes = 0, du = 0, dv = 0, poles = 0;
    for (const auto& f : m.faces) {
      kinds[f.kind]++;
      if (f.kind != "bspline") continue;
      ++bspline;
      rational += f.rational;
      trimmed += f.trimmed;
      holes += f.holes > 0;
      du = std::max(du, f.degree_u);
      dv = std::max(dv, f.degree_v);
      poles = std::max(poles, f.poles_u * f.poles_v);
    }
    CHECK(kinds == e.types);
    if (e.in_words) {
      int all_trimmed = 0, all_holes = 0;
      for (const auto& f : m.faces) {
        all_trimmed += f.trimmed;
        all_holes += f.holes > 0;
      }
      CHECK(all_trimmed == e.trimmed);
      CHECK(all_holes == e.with_holes);
    } else {
      CHECK(bspline == e.bspline);
      CHECK(rational == e.rational);
      CHECK(trimmed == e.bs_trimmed);
      CHECK(holes == e.bs_with_holes);
      CHECK(du == e.maxdeg_u);
      CHECK(dv == e.maxdeg_v);
      CHECK(poles == e.maxpoles);
    }
    if (!e.schema.empty()) CHECK(m.schema.rfind(e.schema, 0) == 0);
    CHECK(m.format == (is_iges(name) ? "iges" : "step"));
    // Face order is TopExp::MapShapes over OCCT's transfer: the areas follow it.
    const Reference ref = read_reference(shared_cad(name), is_iges(name));
    REQUIRE(ref.count() == e.faces);
    for (int i = 0; i < ref.count(); ++i) {
      INFO("face " << i);
      GProp_GProps g;
      // OpenCASCADE's adaptive integration identifies the faces here (the listing is plyfit's
      // own integration; its accuracy is checked in area_test.cpp).
      BRepGProp::SurfaceProperties(ref.face(i), g, 1e-12);
      CHECK(m.faces[i].index == i);
      CHECK(m.faces[i].area == Approx(g.Mass()).epsilon(kOcctAreaRel));
      check_box(m.faces[i].bbox, ref.face(i));
    }
  }
}

TEST_CASE("importers: names, units and schemas come from the files") {
  auto trj8 = importers::open_mold(shared_cad("trj8_c2-db-214.stp"));
  REQUIRE(trj8.ok());
  CHECK((*trj8)->mold().faces[0].name == "127");  // ADVANCED_FACE('127',...)
  CHECK((*trj8)->mold().unit == "millimetre");
  auto pro = importers::open_mold(shared_cad("PRO20359-L1.igs"));
  REQUIRE(pro.ok());
  CHECK((*pro)->mold().faces[0].name.rfind("FAC418", 0) == 0);  // the 144's label
  CHECK((*pro)->mold().schema.rfind("IGES 5.1", 0) == 0);
  auto s114 = importers::open_mold(shared_cad("surf114.igs"));
  REQUIRE(s114.ok());
  CHECK((*s114)->mold().unit.rfind("inch", 0) == 0);  // unit flag 1, 4HINCH
  CHECK((*s114)->mold().schema.rfind("IGES 5.3", 0) == 0);
  // Reader messages are summarised, not printed: one warning of the load, its 12 fails.
  auto trj7 = importers::open_mold(shared_cad("trj7_c2-td-203.stp"));
  REQUIRE(trj7.ok());
  const auto read = support::with_code((*trj7)->mold().warnings, WarningCode::kReaderMessages);
  REQUIRE_FALSE(read.empty());
  CHECK(support::text(read[0], 0) == "load");
  CHECK(support::value(read[0], 1) == 12);
}

TEST_CASE("importers: converted surfaces of the shared files agree with OCCT's evaluation") {
  for (const auto& name : kFiles) check_file_surfaces(name);
}

TEST_CASE("importers: contains() agrees with OCCT's classifier on the cornetta faces", "[slow]") {
  check_file_contains("bug27693_cornetta-step.stp");
}

TEST_CASE("importers: contains() agrees with OCCT's classifier on the IGES files", "[slow]") {
  for (const auto& name : kFiles)
    if (is_iges(name)) check_file_contains(name);
}

TEST_CASE("importers: contains() agrees with OCCT's classifier on the small STEP files") {
  check_file_contains("trj7_c2-td-203.stp");
  check_file_contains("trj8_c2-db-214.stp");
}
