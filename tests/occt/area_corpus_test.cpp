// Face areas (importers/src/face_measure.cpp) on the shared CAD files: the integration along u
// against the one along v (another path of quadratures for the same integral) to the accuracy
// asked, at the listing's 1e-6 and a described face's 1e-9; an invalid face ends within the work
// cap, its area marked. Closed forms: area_test.cpp.

#include <catch2/catch.hpp>

#include "corpus.hpp"
#include "face_measure.hpp"  // occt/src
#include "occt/occt_reference.hpp"
#include "support/warnings.hpp"

#include <BRepCheck_Analyzer.hxx>
#include <nlohmann/json.hpp>

#include <algorithm>
#include "surface/face.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

// The accuracies the importer asks for (occt_mold.cpp): the listing, and a described face.
constexpr double kListingRel = 1e-6;
constexpr double kDescribedRel = 1e-9;

}  // namespace

TEST_CASE(
    "importers: face areas integrated along u and along v agree to the accuracy asked (shared "
    "CAD files)") {
  for (const std::string name :
       {"BUC50025.igs", "PRO20359-L1.igs", "occ22470.igs", "surf114.igs", "example_45_faces.iges",
        "bug27693_cornetta-step.stp", "trj7_c2-td-203.stp", "trj8_c2-db-214.stp"}) {
    const Reference ref = read_reference(shared_cad(name), is_iges(name));
    int unconverged = 0;
    double worst = 0.0;
    for (int i = 0; i < ref.count(); ++i) {
      INFO(name << " face " << i);
      for (const double rel : {kListingRel, kDescribedRel}) {
        const auto along_u = importers::occt::measure_face(ref.face(i), rel, false, false);
        const auto along_v = importers::occt::measure_face(ref.face(i), rel, false, true);
        INFO("asked " << rel << ": " << along_u.area << " +- " << along_u.error << " along u, "
                      << along_v.area << " +- " << along_v.error << " along v");
        // Each is asked for `rel` and, when it says it converged, is within `rel` (its error
        // estimate is an estimate: on these files it falls short of the actual error by up to
        // 10 times, still far below `rel`); when it says it did not, within its estimate.
        const double claim_u =
            std::max(rel * along_u.area, along_u.converged ? 0.0 : along_u.error);
        const double claim_v =
            std::max(rel * along_v.area, along_v.converged ? 0.0 : along_v.error);
        CHECK(std::abs(along_u.area - along_v.area) <=
              (along_u.converged && along_v.converged ? rel * along_u.area : claim_u + claim_v));
        unconverged += !along_u.converged + !along_v.converged;
        if (!along_u.converged || !along_v.converged) WARN("short of " << rel);
        worst = std::max(worst, std::abs(along_u.area - along_v.area) / along_u.area);
      }
    }
    WARN(name << ": largest |u - v| " << worst << " of the area; " << unconverged
              << " integrations short of their accuracy");
    // Every integration converges but surf114's face 3 along v at 1e-9 (5e-8 reached: its
    // bands in v, the surface's u, meet the edges where |S_u| vanishes). With the inner rule's
    // columns in equal parts, three surf114 faces fell short at 1e-9 along u as well; the
    // importer integrates along u.
    CHECK(unconverged <= (name == "surf114.igs" ? 1 : 0));
  }
}

namespace {

// bug27693_cornetta-step.stp with records 510 to 552 cut out: face 73, a rational B-spline
// face, keeps one edge of its wire, whose pcurve runs a little outside its surface's domain;
// the face fails OpenCASCADE's BRepCheck. Its area integration once never ended.
constexpr int kInvalidFace = 73;
std::string invalid_brep_file(const TempDir& dir) {
  const std::string bytes = read_bytes(shared_cad("bug27693_cornetta-step.stp"));
  std::vector<std::string> lines;
  size_t pos = 0;
  while (pos < bytes.size()) {
    const size_t eol = std::min(bytes.find('\n', pos), bytes.size());
    lines.push_back(bytes.substr(pos, eol + 1 - pos));
    pos = eol + 1;
  }
  REQUIRE(lines.size() > 552);
  lines.erase(lines.begin() + 509, lines.begin() + 552);
  std::string cut;
  for (const auto& l : lines) cut += l;
  const std::string path = dir.file("invalid_brep.stp");
  write_bytes(path, cut);
  return path;
}

}  // namespace

TEST_CASE("importers: the area integration of an invalid face ends within its work cap") {
  TempDir dir("invalid_brep_measure");
  const Reference ref = read_reference(invalid_brep_file(dir), false);
  REQUIRE(ref.count() > kInvalidFace);
  const TopoDS_Face face = ref.face(kInvalidFace);
  REQUIRE_FALSE(BRepCheck_Analyzer(face).IsValid());
  const auto surface = Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(face));
  REQUIRE_FALSE(surface.IsNull());
  const long cap = importers::occt::kMaxMeasureEvaluations +
                   importers::occt::kMeasureEvaluationsPerPatch * (surface->NbUKnots() - 1) *
                       (surface->NbVKnots() - 1);
  for (const bool transposed : {false, true}) {
    const auto m = importers::occt::measure_face(face, kDescribedRel, true, transposed);
    INFO("transposed " << transposed << ": " << m.evaluations << " evaluations");
    CHECK_FALSE(m.measured);
    CHECK(m.area == 0.0);
    CHECK(m.evaluations <= cap + 1);
    CHECK_FALSE(m.bbox.empty);
  }
}

TEST_CASE("importers: plyfit info lists a file with an invalid face, its area marked invalid") {
  TempDir dir("invalid_brep_cli");
  const std::string path = invalid_brep_file(dir);
  const Run list = run_plyfit("info --json '" + path + "'", dir);
  INFO("exit " << list.code << ", stderr: " << list.err);
  REQUIRE(list.code == 0);
  const auto j = nlohmann::json::parse(list.out);
  REQUIRE(j["faces"].size() > static_cast<size_t>(kInvalidFace));
  for (const auto& f : j["faces"]) {
    INFO("face " << f["index"]);
    if (f["index"] == kInvalidFace)
      CHECK(f["area_mm2"].is_null());
    else
      CHECK(f["area_mm2"].get<double>() > 0.0);
  }
  bool warned = false;
  for (const auto& w : j["warnings"]) warned = warned || w["code"] == "unmeasured_faces";
  CHECK(warned);
  const Run one = run_plyfit("info '" + path + "' --face " + std::to_string(kInvalidFace), dir);
  INFO("exit " << one.code << ", stderr: " << one.err);
  CHECK(one.code == 1);
  CHECK(std::count(one.err.begin(), one.err.end(), '\n') == 1);
  CHECK(one.err.find(path) != std::string::npos);
  CHECK(one.err.find("face " + std::to_string(kInvalidFace)) != std::string::npos);
}

TEST_CASE(
    "importers: a face whose area cannot be measured is a warning of the listing and of the face") {
  TempDir dir("invalid_brep_warnings");
  auto file = importers::open_mold(invalid_brep_file(dir));
  REQUIRE(file.ok());
  const auto listing = support::with_code((*file)->mold().warnings, WarningCode::kUnmeasuredFaces);
  REQUIRE(listing.size() == 1);
  CHECK(support::value(listing[0], 0) == 1);  // faces
  CHECK(support::value(listing[0], 1) == kInvalidFace);
  CHECK_FALSE(support::text(listing[0], 3).empty());  // why
  // Converting it fails; the face's own warning says why too.
  auto face = (*file)->convert_face(kInvalidFace);
  REQUIRE_FALSE(face.ok());
  CHECK(face.error().code == ErrorCode::kFaceAreaNotMeasured);
  CHECK(face.error().face == kInvalidFace);
  const auto own =
      support::with_code((*file)->summary().warnings, WarningCode::kFaceAreaUnmeasured);
  REQUIRE(own.size() == 1);
  CHECK(support::value(own[0], 0) == kInvalidFace);
}
