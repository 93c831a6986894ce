// The importers on plyfit's own trimmed, holed, rational and closed sample molds
// (samples/molds, written by `plyfit sample` in STEP and IGES), as the corpus tests do on real
// files: OpenCASCADE finds the written faces valid, the listing agrees with OpenCASCADE's own
// reading (kind, rational, trims, holes, seams), converted surfaces agree with OpenCASCADE's
// evaluation, contains() with its classifier, and the trim polylines with its edges.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <BRepCheck_Analyzer.hxx>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"
#include "support/face_of.hpp"

using namespace plyfit;
using namespace plyfit::test;

namespace {

struct Sample {
  std::string file;  ///< stem under samples/molds
  std::string spec;  ///< the built-in it was written from (tests/samples/sample_list.hpp)
  bool rational, trimmed;
  int holes;
};

const std::vector<Sample> kSamples = {
    {"plate-hole", "plate:W=100,H=60,hole_r=10,hole_x=50,hole_y=30", false, true, 1},
    {"dish", "dish:R=30,rho=40,hole_r=8", false, true, 1},
    {"tube", "cylinder:angle=360", true, false, 0},
    {"tube-window", "cylinder:angle=360,window_angle=60,window_height=8", true, true, 1},
};

FaceData builtin_of(const Sample& s) {
  auto spec = parse_builtin_spec(s.spec);
  REQUIRE(spec.ok());
  auto fd = builtin_mold(spec->first, spec->second);
  REQUIRE(fd.ok());
  return std::move(fd).value();
}

int wires_of(const TopoDS_Face& f) {
  int n = 0;
  for (TopExp_Explorer ex(f, TopAbs_WIRE); ex.More(); ex.Next()) ++n;
  return n;
}

// Calls check(path, face, reference) on face 0 of each sample mold (the trimmed ones alone
// when `trimmed_only`), as STEP and as IGES, converted and as OpenCASCADE reads it.
template <typename Check>
void for_each_sample_face(bool trimmed_only, Check&& check) {
  for (const auto& s : kSamples) {
    if (trimmed_only && !s.trimmed) continue;
    for (const char* ext : {".step", ".igs"}) {
      const std::string path = sample_mold(s.file + ext);
      INFO(path);
      auto face = importers::load_face(path, 0);
      REQUIRE(face.ok());
      const Reference ref = read_reference(path, is_iges(path));
      check(path, *face, ref);
    }
  }
}

}  // namespace

TEST_CASE("importers: plyfit's sample molds are valid shapes for OpenCASCADE") {
  for (const auto& s : kSamples) {
    for (const char* ext : {".step", ".igs"}) {
      const std::string path = sample_mold(s.file + ext);
      INFO(path);
      const Reference ref = read_reference(path, is_iges(path));
      REQUIRE(ref.count() == 1);
      BRepCheck_Analyzer check(ref.face(0));
      CHECK(check.IsValid());
      CHECK(wires_of(ref.face(0)) == 1 + s.holes);
    }
  }
}

TEST_CASE("importers: the sample molds list the trims, holes and seams OpenCASCADE reads") {
  for (const auto& s : kSamples) {
    const FaceData built = builtin_of(s);
    for (const char* ext : {".step", ".igs"}) {
      const std::string path = sample_mold(s.file + ext);
      INFO(path);
      auto file = importers::open_mold(path);
      REQUIRE(file.ok());
      const Mold& m = (*file)->mold();
      REQUIRE(m.faces.size() == 1);
      const FaceInfo& info = m.faces[0];
      CHECK(info.kind == "bspline");
      CHECK(info.rational == s.rational);
      CHECK(info.trimmed == s.trimmed);
      CHECK(info.holes == s.holes);
      CHECK_FALSE(info.reversed);
      CHECK(info.name == s.file);
      CHECK(m.format == (is_iges(path) ? "iges" : "step"));
      auto data = (*file)->convert_face(0);
      INFO((data.ok() ? std::string() : exporters::describe(data.error())));
      REQUIRE(data.ok());
      CHECK(data->loops.empty() == !s.trimmed);
      // Seams as the built-in has them (the full tubes close around their axis); OpenCASCADE's
      // STEP and IGES readers make such a surface periodic, which the importer undoes.
      CHECK(data->closed_u == built.closed_u);
      CHECK(data->closed_v == built.closed_v);
      CHECK(data->loops.size() == built.loops.size());
    }
  }
}

TEST_CASE("importers: converted sample molds agree with OpenCASCADE's evaluation") {
  Rng rng(5);
  for_each_sample_face(false, [&](const std::string& path, const auto& face, const Reference& ref) {
    const double worst = check_surface(test::face_of(face), ref.face(0), 200, rng);
    WARN(path << ": worst surface deviation " << worst << " of the face size");
  });
}

TEST_CASE("importers: contains() agrees with OpenCASCADE's classifier on the sample molds") {
  Rng rng(9);
  for_each_sample_face(true, [&](const std::string&, const auto& face, const Reference& ref) {
    CHECK(check_contains(test::face_of(face), face_in_converted_parameters(ref.face(0)), 3000,
                         rng) >= 2500);
  });
}

TEST_CASE("importers: sample mold trim polylines follow the face edges within the trim tolerance") {
  for (const auto& s : kSamples) {
    if (!s.trimmed) continue;
    for (const char* ext : {".step", ".igs"}) {
      const std::string path = sample_mold(s.file + ext);
      const double worst = check_trim_accuracy(path);
      WARN(path << ": worst trim deviation " << worst << " of the allowed");
    }
  }
}
