// Expected failures of the importers (error_checks.hpp) on plyfit's own sample molds: missing,
// empty, truncated, corrupted and mislabelled files, files with no faces, bad face indices,
// the time limit, and the registry's extension handling. The same checks run on the CAD
// corpus in errors_corpus_test.cpp.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>

#include <catch2/catch.hpp>

#include "occt/error_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: missing, empty and unreadable files are errors naming the file") {
  TempDir dir("errors_basic");
  const std::string missing = dir.file("nope.step");
  auto r = importers::open_mold(missing);
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), missing);
  CHECK(r.error().code == ErrorCode::kFileMissing);

  std::filesystem::create_directories(dir.file("folder.igs"));
  r = importers::open_mold(dir.file("folder.igs"));
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kFileNotRegular);

  write_bytes(dir.file("empty.stp"), "");
  r = importers::open_mold(dir.file("empty.stp"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("empty.stp"));
  CHECK(r.error().code == ErrorCode::kFileEmpty);
}

TEST_CASE("importers: the registry picks importers by extension or --format") {
  CHECK(importers::find_importer("STEP") != nullptr);
  CHECK(importers::find_importer("stp")->key == "step");
  CHECK(importers::find_importer("IGS")->key == "iges");
  CHECK(importers::find_importer("dxf") == nullptr);
  CHECK(importers::supported_extensions() == "step, stp, iges, igs");
  TempDir dir("registry");
  const std::string bytes = read_bytes(sample_mold("plate-hole.step"));
  write_bytes(dir.file("UPPER.STP"), bytes);
  CHECK(importers::open_mold(dir.file("UPPER.STP")).ok());
  write_bytes(dir.file("model.dat"), bytes);
  auto r = importers::open_mold(dir.file("model.dat"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("model.dat"));
  CHECK(r.error().code == ErrorCode::kFileExtensionUnknown);
  CHECK(r.error().values == std::vector<MessageValue>{"dat", "step, stp, iges, igs"});
  importers::ImportOptions o;
  o.format = "stp";
  CHECK(importers::open_mold(dir.file("model.dat"), o).ok());
  o.format = "iges";  // a STEP file read as IGES
  r = importers::open_mold(dir.file("model.dat"), o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kFileWrongFormat);
  CHECK(r.error().values == std::vector<MessageValue>{"IGES", "STEP"});
  o.format = "obj";
  r = importers::open_mold(dir.file("model.dat"), o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kImportFormatUnknown);
  CHECK(r.error().values == std::vector<MessageValue>{"obj", "step, stp, iges, igs"});
}

TEST_CASE("importers: renamed, truncated and corrupted copies give clear errors, not crashes") {
  TempDir dir("corrupt");
  check_damaged_copies({{sample_mold("dish.step"), sample_mold("plate-hole.igs"), 21},
                        {sample_mold("tube-window.step"), sample_mold("tube-window.igs"), 41}},
                       dir);
}

TEST_CASE("importers: the plyfit binary survives every corrupted copy within the time limit",
          "[slow]") {
  TempDir dir("corrupt_bin");
  binary_survives_corrupted(sample_mold("plate-hole.step"), sample_mold("dish.igs"), dir);
}

TEST_CASE("importers: a file without faces, a bad face index and a time limit are errors") {
  TempDir dir("nofaces");
  Message::DefaultMessenger()->ChangePrinters().Clear();
  const TopoDS_Edge edge = BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0)).Edge();
  {
    STEPControl_Controller::Init();
    STEPControl_Writer w;
    REQUIRE(w.Transfer(edge, STEPControl_AsIs) == IFSelect_RetDone);
    REQUIRE(w.Write(dir.file("edge.step").c_str()) == IFSelect_RetDone);
    IGESControl_Controller::Init();
    IGESControl_Writer wi("MM", 1);
    REQUIRE(wi.AddShape(edge));
    wi.ComputeModel();
    REQUIRE(wi.Write(dir.file("edge.igs").c_str()));
  }
  for (const std::string name : {"edge.step", "edge.igs"}) {
    auto r = importers::open_mold(dir.file(name));
    REQUIRE_FALSE(r.ok());
    check_error(r.error(), dir.file(name));
    CHECK(r.error().code == ErrorCode::kFileNoFaces);
  }

  for (const std::string name : {"plate-hole.step", "dish.igs"})
    check_bad_index_and_time_limit(sample_mold(name), 1);
}

TEST_CASE("importers: a STEP file its parser cannot read is file_not_parsed, naming the file") {
  TempDir dir("not_parsed");
  // The frame of a STEP file, which the checks before the reader pass, with an empty header.
  const std::string path = dir.file("empty.step");
  write_bytes(path, "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n");
  auto r = importers::open_mold(path);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kFileNotParsed);
  CHECK(r.error().input == path);
  CHECK(r.error().values == std::vector<MessageValue>{std::string("STEP"), std::int64_t{0}});
  auto curves = importers::read_curves(path);
  REQUIRE_FALSE(curves.ok());
  CHECK(curves.error().code == ErrorCode::kFileNotParsed);
  CHECK(curves.error().input == path);
}

TEST_CASE("importers: a fault inside the reader is a one-line error naming the file") {
  TempDir dir("reader_fault");
  const std::string path = sample_mold("dish.step");
  // A segmentation fault, and a stack overflow (a recursion that does not end), inside the read.
  for (const std::string fault : {"segv", "stack"}) {
    const Run r = run_plyfit("info '" + path + "'", dir, "PLYFIT_DEBUG_READER_FAULT=" + fault);
    INFO(fault << ": exit " << r.code << ", stderr: " << r.err);
    CHECK(r.code == 1);
    CHECK(r.err.rfind("plyfit: error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(path) != std::string::npos);
    CHECK(r.err.find(" [occt_failed]\n") != std::string::npos);
  }
}
