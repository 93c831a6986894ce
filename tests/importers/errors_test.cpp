// Expected failures of the importers: missing, empty, truncated, corrupted and mislabelled
// files, files with no faces, bad face indices, and the registry's extension handling. Every
// one must come back as a one-line Error naming the file, never a crash or a hang; the
// corrupted copies are also run through the plyfit binary under a time limit.

#include <plyfit/importers/importers.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>

#include <catch2/catch.hpp>

#include "importers/occt_reference.hpp"

#include <sys/wait.h>
#include <cstdlib>

using namespace plyfit;
using namespace plyfit::test;

namespace {

// The error must be one line and name the file.
void check_error(const Error& e, const std::string& path) {
  INFO(e.message);
  CHECK(e.message.find('\n') == std::string::npos);
  CHECK(e.message.find(path) != std::string::npos);
}

// Opening a corrupted file gives an error naming it, or (when the damage is harmless) a mold
// whose faces all convert or fail with such an error. True when the file was rejected.
bool open_corrupted(const std::string& path) {
  auto file = importers::open_mold(path);
  if (!file) {
    check_error(file.error(), path);
    return true;
  }
  for (int i = 0; i < static_cast<int>((*file)->mold().faces.size()); ++i) {
    auto d = (*file)->convert_face(i);
    if (!d) check_error(d.error(), path);
  }
  return false;
}

// The binary on a bad file: exit code 1, one line on stderr naming the file, not a crash
// (128 + signal) nor a hang (124).
void binary_rejects(const std::string& path, const TempDir& dir) {
  const Run r = run_plyfit("info '" + path + "'", dir);
  INFO(path << ": exit " << r.code << ", stderr: " << r.err);
  CHECK(r.code != 124);
  CHECK(r.code < 128);
  if (r.code == 0) return;  // harmless damage: read fine
  CHECK(r.code == 1);
  CHECK(r.err.rfind("plyfit: error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(path) != std::string::npos);
}

std::vector<std::string> corrupted_copies(const std::string& source, const std::string& ext,
                                          const TempDir& dir, uint64_t seed) {
  const std::string bytes = read_bytes(source);
  REQUIRE(bytes.size() > 1000);
  std::vector<std::string> out;
  int n = 0;
  auto add = [&](const std::string& content) {
    out.push_back(dir.file("corrupt_" + std::to_string(n++) + "." + ext));
    write_bytes(out.back(), content);
  };
  for (double cut : {0.02, 0.3, 0.5, 0.9, 0.999})
    add(bytes.substr(0, static_cast<size_t>(cut * bytes.size())));
  // Middle cut out, header and end kept: the parser meets dangling references.
  add(bytes.substr(0, bytes.size() * 4 / 10) + bytes.substr(bytes.size() * 9 / 10));
  Rng rng(seed);
  for (int k = 0; k < 6; ++k) {
    std::string b = bytes;
    const int flips = k < 3 ? 20 : 400;
    for (int f = 0; f < flips; ++f) {
      const size_t at = static_cast<size_t>(
          rng.integer(static_cast<int>(b.size() / 20), static_cast<int>(b.size()) - 200));
      b[at] = static_cast<char>(k % 2 ? rng.integer(0, 255) : rng.integer('#', 'z'));
    }
    add(b);
  }
  std::string garbage(20000, '\0');
  for (auto& c : garbage) c = static_cast<char>(rng.integer(0, 255));
  add(garbage);
  return out;
}

}  // namespace

TEST_CASE("importers: missing, empty and unreadable files are errors naming the file") {
  TempDir dir("errors_basic");
  const std::string missing = dir.file("nope.step");
  auto r = importers::open_mold(missing);
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), missing);
  CHECK(r.error().message.find("no such file") != std::string::npos);

  std::filesystem::create_directories(dir.file("folder.igs"));
  r = importers::open_mold(dir.file("folder.igs"));
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("not a regular file") != std::string::npos);

  write_bytes(dir.file("empty.stp"), "");
  r = importers::open_mold(dir.file("empty.stp"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("empty.stp"));
  CHECK(r.error().message.find("empty") != std::string::npos);
}

TEST_CASE("importers: the registry picks importers by extension or --format") {
  CHECK(importers::find_importer("STEP") != nullptr);
  CHECK(importers::find_importer("stp")->key == "step");
  CHECK(importers::find_importer("IGS")->key == "iges");
  CHECK(importers::find_importer("dxf") == nullptr);
  CHECK(importers::supported_extensions() == "step, stp, iges, igs");
  TempDir dir("registry");
  const std::string bytes = read_bytes(shared_cad("trj8_c2-db-214.stp"));
  write_bytes(dir.file("UPPER.STP"), bytes);
  CHECK(importers::open_mold(dir.file("UPPER.STP")).ok());
  write_bytes(dir.file("model.dat"), bytes);
  auto r = importers::open_mold(dir.file("model.dat"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("model.dat"));
  CHECK(r.error().message.find("step, stp, iges, igs") != std::string::npos);
  importers::ImportOptions o;
  o.format = "stp";
  CHECK(importers::open_mold(dir.file("model.dat"), o).ok());
  o.format = "iges";  // a STEP file read as IGES
  r = importers::open_mold(dir.file("model.dat"), o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("looks like STEP") != std::string::npos);
  o.format = "obj";
  r = importers::open_mold(dir.file("model.dat"), o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("unknown format 'obj'") != std::string::npos);
}

TEST_CASE("importers: an IGES file renamed .step (and STEP renamed .igs) is rejected clearly") {
  TempDir dir("renamed");
  write_bytes(dir.file("really_iges.step"), read_bytes(shared_cad("PRO20359-L1.igs")));
  auto r = importers::open_mold(dir.file("really_iges.step"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("really_iges.step"));
  CHECK(r.error().message.find("not a STEP file") != std::string::npos);
  CHECK(r.error().message.find("looks like IGES") != std::string::npos);
  write_bytes(dir.file("really_step.igs"), read_bytes(shared_cad("trj8_c2-db-214.stp")));
  r = importers::open_mold(dir.file("really_step.igs"));
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("not a IGES file") != std::string::npos);
  binary_rejects(dir.file("really_iges.step"), dir);
}

TEST_CASE("importers: truncated and corrupted copies give errors, not crashes or hangs") {
  TempDir dir("corrupt");
  const auto step = corrupted_copies(shared_cad("trj8_c2-db-214.stp"), "stp", dir, 21);
  const auto iges = corrupted_copies(shared_cad("PRO20359-L1.igs"), "igs", dir, 22);
  int rejected = 0;
  for (const auto* set : {&step, &iges}) {
    for (const auto& path : *set) {
      INFO(path);
      rejected += open_corrupted(path);
    }
  }
  // Truncations, the cut-out middle and the garbage file cannot be read.
  CHECK(rejected >= 2 * 7);
  // Truncated copies say so.
  auto t = importers::open_mold(step[2]);
  REQUIRE_FALSE(t.ok());
  CHECK(t.error().message.find("truncated") != std::string::npos);
  t = importers::open_mold(iges[2]);
  REQUIRE_FALSE(t.ok());
  CHECK(t.error().message.find("truncated") != std::string::npos);
}

TEST_CASE("importers: the plyfit binary survives every corrupted copy within the time limit",
          "[slow]") {
  TempDir dir("corrupt_bin");
  for (const auto& p : corrupted_copies(shared_cad("trj8_c2-db-214.stp"), "stp", dir, 31))
    binary_rejects(p, dir);
  for (const auto& p : corrupted_copies(shared_cad("occ22470.igs"), "igs", dir, 32))
    binary_rejects(p, dir);
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
    CHECK(r.error().message.find("no faces") != std::string::npos);
  }

  const std::string path = shared_cad("trj7_c2-td-203.stp");
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  for (int bad : {-1, 4, 1000}) {
    auto d = (*file)->convert_face(bad);
    REQUIRE_FALSE(d.ok());
    check_error(d.error(), path);
    CHECK(d.error().message.find("out of range") != std::string::npos);
  }
  auto lf = importers::load_face(path, 9);
  REQUIRE_FALSE(lf.ok());
  check_error(lf.error(), path);

  importers::ImportOptions o;
  o.time_limit_s = 0.0;  // already past: the transfer is stopped at its first check
  auto slow = importers::open_mold(shared_cad("bug27693_cornetta-step.stp"), o);
  REQUIRE_FALSE(slow.ok());
  check_error(slow.error(), shared_cad("bug27693_cornetta-step.stp"));
  CHECK(slow.error().message.find("time limit") != std::string::npos);
}
