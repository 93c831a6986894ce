// The mold's warnings (Mold::warnings) as codes with data: what the OpenCASCADE module finds in
// a file it reads (OpenCASCADE's own messages), lists and sews, and their sentences
// (exporters::message, as plyfit info and report.json print them).

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/types.hpp>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"
#include "occt/shell_checks.hpp"
#include "occt/write_shapes.hpp"
#include "support/warnings.hpp"

#include <cmath>

using namespace plyfit;
using namespace plyfit::test;

namespace {

std::string text_of(WarningCode code, std::vector<MessageValue> values) {
  return exporters::message(Warning{code, std::move(values)});
}

// A Moebius band of 2 * n flat triangles, each its own face (the importer sews them): centre
// circle of radius 100, half-width 20, half a turn of twist along it.
TopoDS_Shape moebius_triangles(int n) {
  auto at = [](int k, double s, int n_steps) {
    const double t = 2.0 * kPi * k / n_steps;
    const double r = 100.0 + s * std::cos(t / 2);
    return gp_Pnt(r * std::cos(t), r * std::sin(t), s * std::sin(t / 2));
  };
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  auto add = [&](const gp_Pnt& p, const gp_Pnt& q, const gp_Pnt& r) {
    b.Add(c,
          BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(p, q, r, true).Wire(), true).Face());
  };
  for (int k = 0; k < n; ++k) {
    // Point k + 1 = n is point 0 with the band's sides swapped (P(2 pi, s) = P(0, -s)).
    const gp_Pnt a0 = at(k, 20, n), b0 = at(k, -20, n), a1 = at(k + 1, 20, n),
                 b1 = at(k + 1, -20, n);
    add(a0, b0, a1);
    add(b0, b1, a1);
  }
  return c;
}

}  // namespace

TEST_CASE("importers: a Moebius band's faces sew into a shell that cannot be oriented") {
  TempDir dir("mold_warnings_moebius");
  const std::string path = dir.file("moebius.step");
  write_step(moebius_triangles(24), path);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  REQUIRE((*file)->face_count() == 48);
  auto shell = (*file)->convert_shell({});
  INFO((shell.ok() ? std::string() : exporters::describe(shell.error())));
  REQUIRE(shell.ok());
  const auto& warnings = (*file)->summary().warnings;
  // One part (every triangle reached across shared edges), some edge used the same way by its
  // two faces whatever the orientation.
  CHECK(support::with_code(warnings, WarningCode::kSeparateShells).empty());
  const auto w = the_warning(warnings, WarningCode::kShellNotOrientable);
  REQUIRE(w.size() == 1);
  CHECK(w[0] >= 1);
}

TEST_CASE("importers: OpenCASCADE's reader messages are one warning, its words the data") {
  // OpenCASCADE's STEP reader makes the closed B-spline of the tube periodic, and says so.
  auto file = importers::open_mold(sample_mold("tube-window.step"));
  REQUIRE(file.ok());
  const auto read = support::with_code((*file)->summary().warnings, WarningCode::kReaderMessages);
  REQUIRE(read.size() == 1);
  CHECK(support::text(read[0], 0) == "transfer");
  // No fail; 1 warning of 1 kind, shown: given once, in OpenCASCADE's words.
  const std::vector<double> counts = support::numbers(read[0]);
  REQUIRE(counts.size() == 9);
  CHECK(std::vector<double>(counts.begin() + 1, counts.begin() + 8) ==
        std::vector<double>{0, 0, 0, 1, 1, 1, 1});
  CHECK(support::text(read[0], 8) == "Surface forced to be periodic");
}

TEST_CASE("messages: the mold's warnings read as plyfit has always printed them") {
  using W = WarningCode;
  CHECK(text_of(W::kReaderMessages, {"transfer", std::int64_t{0}, std::int64_t{0}, std::int64_t{0},
                                     std::int64_t{1}, std::int64_t{1}, std::int64_t{1},
                                     std::int64_t{1}, "Surface forced to be periodic"}) ==
        "transfer: 1 warning (1x 'Surface forced to be periodic')");
  CHECK(text_of(W::kReaderMessages, {"load", std::int64_t{12}, std::int64_t{4}, std::int64_t{3},
                                     std::int64_t{5}, "A", std::int64_t{4}, "B", std::int64_t{2},
                                     "C", std::int64_t{0}, std::int64_t{0}, std::int64_t{0}}) ==
        "load: 12 fails (5x 'A', 4x 'B', 2x 'C', ...)");
  CHECK(text_of(W::kReaderMessages,
                {"load", std::int64_t{1}, std::int64_t{1}, std::int64_t{1}, std::int64_t{1}, "F",
                 std::int64_t{2}, std::int64_t{1}, std::int64_t{1}, std::int64_t{2}, "W"}) ==
        "load: 1 fail (1x 'F'), 2 warnings (2x 'W')");
  CHECK(text_of(W::kSeparateShells, {std::int64_t{4}, std::int64_t{4}}) ==
        "sewing: the 4 faces form 4 separate shells that no shared edge joins; a drape stays on "
        "the one it starts on");
  CHECK(text_of(W::kNonManifoldEdges, {std::int64_t{1}}) ==
        "sewing: 1 edge bounds more than two faces (non-manifold), treated as free");
  CHECK(text_of(W::kNonManifoldEdges, {std::int64_t{2}}) ==
        "sewing: 2 edges bound more than two faces (non-manifold), treated as free");
  CHECK(text_of(W::kFacesReoriented, {std::int64_t{3}}) ==
        "sewing: face 3 reversed to orient the shell consistently");
  CHECK(text_of(W::kFacesReoriented, {std::int64_t{0}, std::int64_t{1}, std::int64_t{2},
                                      std::int64_t{5}, std::int64_t{7}, std::int64_t{8}}) ==
        "sewing: faces 0-2, 5, 7, 8 reversed to orient the shell consistently");
  std::vector<MessageValue> even;
  for (std::int64_t f = 0; f < 28; f += 2) even.emplace_back(f);
  CHECK(text_of(W::kFacesReoriented, even) ==
        "sewing: faces 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, ... reversed to orient the shell "
        "consistently");
  CHECK(text_of(W::kShellNotOrientable, {std::int64_t{1}}) ==
        "sewing: 1 shared edge joins faces oriented against each other (a non-orientable shell)");
  CHECK(text_of(W::kFaceAreaShort, {std::int64_t{3}, "#12", 1e-9, 1.2e-7}) ==
        "face 3 (#12): area to 1.2e-07 relative (estimated), not the 1e-09 asked");
  CHECK(text_of(W::kFaceAreaShort, {std::int64_t{3}, "", 1e-6}) ==
        "face 3: area by OpenCASCADE's integration (no pcurves), accuracy unknown");
  CHECK(text_of(W::kFaceAreaUnmeasured, {std::int64_t{73}, "#4242", "why"}) ==
        "face 73 (#4242): area not measured (why): an invalid face");
  CHECK(text_of(W::kUnmeasuredFaces, {std::int64_t{1}, std::int64_t{73}, "#4242", "why"}) ==
        "listing: 1 faces whose area could not be measured (first: face 73 (#4242): area not "
        "measured (why): an invalid face)");
  // The first face's failure: an error and its cause, each its code's name, value count, values.
  CHECK(text_of(W::kListingFailedFaces,
                {std::int64_t{2}, std::int64_t{5}, "DE 9", "face_not_described", std::int64_t{0},
                 "occt_failed", std::int64_t{2}, "Standard_DomainError", "no pole"}) ==
        "listing: 2 faces could not be described (first: face 5 (DE 9): could not be described: "
        "OpenCASCADE failed (Standard_DomainError: no pole))");
  CHECK(text_of(W::kListingFailedFaces, {std::int64_t{1}, std::int64_t{0}, "", "face_not_measured",
                                         std::int64_t{0}, "out_of_memory", std::int64_t{0}}) ==
        "listing: 1 faces could not be described (first: face 0: could not be measured: out of "
        "memory)");
  CHECK(text_of(W::kShortAreaFaces, {std::int64_t{2}, std::int64_t{3}, "#12", 1e-6, 2e-6}) ==
        "listing: 2 face areas short of the accuracy asked (first: face 3 (#12): area to 2.0e-06 "
        "relative (estimated), not the 1e-06 asked)");
  // A file of no faces names the reader's first messages.
  CHECK(exporters::message(
            Error{ErrorCode::kFileNoFaces,
                  "f.igs",
                  {"load", std::int64_t{1}, std::int64_t{1}, std::int64_t{1}, std::int64_t{1}, "F",
                   std::int64_t{0}, std::int64_t{0}, std::int64_t{0}}}) ==
        "no faces (nothing in the file transfers to a surface; load: 1 fail (1x 'F'))");
  CHECK(exporters::message(Error{ErrorCode::kFileNoFaces, "f.igs"}) ==
        "no faces (nothing in the file transfers to a surface)");
}

TEST_CASE(
    "messages: the module's errors read as plyfit printed them, OpenCASCADE's words as data") {
  using E = ErrorCode;
  const auto text = [](Error e) { return exporters::describe(e); };
  CHECK(text(Error{E::kOcctFailed, "m.step", {"Standard_DomainError", "no pole"}}) ==
        "m.step: OpenCASCADE failed (Standard_DomainError: no pole)");
  CHECK(text(Error{E::kOcctFailed, "m.step", {"OSD_SIGSEGV", ""}}) ==
        "m.step: OpenCASCADE failed (OSD_SIGSEGV)");
  CHECK(text(Error{E::kFileNotParsed, "m.igs", {"IGES", std::int64_t{1}}}) ==
        "m.igs: not a readable IGES file (the IGES parser failed: nothing to read)");
  CHECK(text(Error{E::kFileNotParsed, "m.step", {"STEP", std::int64_t{0}}}) ==
        "m.step: not a readable STEP file (the STEP parser failed)");
  // A face: the file, the face and its entity, then the error and its cause.
  Error face = Error{E::kFaceNotDescribed}.because(Error{E::kOutOfMemory});
  face.input = "m.step";
  face.face = 3;
  face.where = "#120";
  CHECK(text(face) == "m.step: face 3: #120: could not be described: out of memory");
  CHECK(text(Error{E::kNurbsConversionType, {}, {"offset", "Geom_OffsetSurface"}}) ==
        "conversion of the offset surface to NURBS gave a Geom_OffsetSurface");
  CHECK(text(Error{E::kTrimPointBudget, {}, {std::int64_t{2'000'000}}}) ==
        "trim polylines exceed the point budget (2000000 points for a face)");
  CHECK(text(Error{E::kSewingRemovedFace, {}, {0.0125}}) ==
        "the sewing removed it (smaller than the sewing tolerance, 0.0125 mm?)");
  CHECK(text(Error{E::kSewingTimeLimit, {}, {std::int64_t{120}}}) ==
        "sewing took longer than the time limit (120 s)");
  CHECK(text(Error{E::kWriterValueTooLarge, "p.step", {1e99}}) ==
        "p.step: a pole, weight or knot is 1e+99 or larger: not written");
  CHECK(text(Error{E::kWriterNoFace, "p.igs", {"IGES", "lid"}}) ==
        "p.igs: the IGES writer made no surface of 'lid'");
  CHECK(text(Error{E::kWriterNoFace, "p.step", {"STEP", "lid"}}) ==
        "p.step: the STEP writer made no face of 'lid'");
  CHECK(text(Error{E::kWriterOcctFailed, "p.step", {"Standard_ConstructionError", ""}}) ==
        "p.step: OpenCASCADE failed writing the file (Standard_ConstructionError)");
  CHECK(text(Error{E::kOcctModuleOtherBuild,
                   "m.step",
                   {"plyfit-occt.so", std::int64_t{5}, std::int64_t{6}}}) ==
        "m.step: plyfit's OpenCASCADE module plyfit-occt.so is from another build of plyfit "
        "(interface 5, expected 6)");
}
