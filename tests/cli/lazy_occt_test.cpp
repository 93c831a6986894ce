// OpenCASCADE is loaded only when a mold file is read or written: the plyfit binary does not
// link it, and its module (build/lib/plyfit-occt.so) is loaded on first use. The shared objects
// a run had mapped are listed by the binary itself at exit (PLYFIT_DEBUG_LIBRARIES); a run
// that reads a file is the control that the listing does show OpenCASCADE when it is loaded.

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace plyfit::test;
namespace fs = std::filesystem;

namespace {

const std::string kHemisphereDrape =
    "drape --mold builtin:hemisphere --spacing 0.1 --start2d 0,0 --base2d 0,1 --sweep2d -1,0 "
    "--sweep2d 1,0 --start3d 0,0,1 --base-normal 1,0,0 --sweep3d 1,0,0 --sweep3d -1,0,0 --quiet";

// The shared objects mapped at the end of `plyfit ARGS`, and the run.
std::vector<std::string> libraries_of(const std::string& args, const Scratch& s, CliRun& run) {
  const std::string list = s.file("libraries.txt");
  fs::remove(list);
  ::setenv("PLYFIT_DEBUG_LIBRARIES", list.c_str(), 1);
  run = plyfit_run(args, s);
  ::unsetenv("PLYFIT_DEBUG_LIBRARIES");
  std::vector<std::string> libs;
  std::istringstream is(slurp(list));
  for (std::string line; std::getline(is, line);) libs.push_back(line);
  return libs;
}

bool any_contains(const std::vector<std::string>& libs, const std::string& part) {
  for (const auto& l : libs)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& libs) {
  std::string s;
  for (const auto& l : libs) s += l + "\n";
  return s;
}

// The file of the shared object `soname` as the dynamic loader finds it.
std::string shared_object_path(const char* soname) {
  void* handle = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
  REQUIRE(handle);
  link_map* map = nullptr;
  REQUIRE(dlinfo(handle, RTLD_DI_LINKMAP, &map) == 0);
  const std::string path = map->l_name;
  dlclose(handle);
  return path;
}

}  // namespace

TEST_CASE("cli: a drape of a built-in mold with every output loads no OpenCASCADE library") {
  Scratch s("lazy_occt");
  CliRun run;
  const auto libs = libraries_of(kHemisphereDrape + " -o '" + s.file("out") + "'", s, run);
  INFO(run.err);
  REQUIRE(run.code == 0);
  for (const char* f : {"flat.dxf", "net.step", "flat.svg", "drape.svg", "shear.svg", "net.vtk",
                        "view.svg", "net.glb", "report.json"})
    CHECK(fs::exists(s.path / "out" / f));
  INFO(joined(libs));
  // The listing works: the C library is always there.
  REQUIRE(any_contains(libs, "libc.so"));
  CHECK_FALSE(any_contains(libs, "libTK"));
  CHECK_FALSE(any_contains(libs, "plyfit-occt"));
}

TEST_CASE("cli: reading or writing a mold file loads the OpenCASCADE module") {
  Scratch s("lazy_occt_read");
  CliRun run;
  const std::string mold = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/hemisphere.igs";
  auto libs = libraries_of("info '" + mold + "'", s, run);
  INFO(run.err << joined(libs));
  REQUIRE(run.code == 0);
  CHECK(run.out.find("bspline") != std::string::npos);
  CHECK(any_contains(libs, "plyfit-occt.so"));
  CHECK(any_contains(libs, "libTKernel"));
  libs = libraries_of("sample hemisphere -o '" + s.file("h.step") + "'", s, run);
  REQUIRE(run.code == 0);
  CHECK(any_contains(libs, "libTKSTEP"));
}

TEST_CASE(
    "cli: without its OpenCASCADE module plyfit still drapes built-in molds, and a mold "
    "file is a one-line error") {
  Scratch s("lazy_occt_missing");
  // A copy of the binary in a folder with neither the module nor a ../lib holding it.
  const fs::path bin = s.path / "bin" / "plyfit";
  fs::create_directories(bin.parent_path());
  fs::copy_file(PLYFIT_BIN, bin);
  auto run_copy = [&](const std::string& args) {
    const std::string cmd = "'" + bin.string() + "' " + args + " > '" + s.file("o.txt") + "' 2> '" +
                            s.file("e.txt") + "' < /dev/null";
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(s.file("o.txt"));
    r.err = slurp(s.file("e.txt"));
    return r;
  };
  const CliRun drape = run_copy(kHemisphereDrape + " -o '" + s.file("out") + "'");
  INFO(drape.err);
  CHECK(drape.code == 0);
  CHECK(fs::exists(s.path / "out" / "net.step"));
  const std::string mold = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/hemisphere.igs";
  const CliRun info = run_copy("info '" + mold + "'");
  CHECK(info.code == 1);
  CHECK(lines(info.err) == 1);
  CHECK(info.err.rfind("plyfit: error: " + mold + ": ", 0) == 0);
  CHECK(error_code(info) == "occt_module_missing");
  CHECK(info.err.find("plyfit-occt.so") != std::string::npos);
  const CliRun sample = run_copy("sample hemisphere -o '" + s.file("h.igs") + "'");
  CHECK(sample.code == 1);
  CHECK(lines(sample.err) == 1);
  CHECK(error_code(sample) == "occt_module_missing");
  CHECK_FALSE(fs::exists(s.path / "h.igs"));
}

TEST_CASE("cli: a module that does not load, or lacks its entry point, is a one-line error") {
  Scratch s("lazy_occt_broken");
  const fs::path bin = s.path / "bin" / "plyfit";
  fs::create_directories(bin.parent_path());
  fs::copy_file(PLYFIT_BIN, bin);
  const std::string mold = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/hemisphere.igs";
  const fs::path module = bin.parent_path() / "plyfit-occt.so";
  auto info = [&] {
    const std::string cmd = "'" + bin.string() + "' info '" + mold + "' > /dev/null 2> '" +
                            s.file("e.txt") + "' < /dev/null";
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = slurp(s.file("e.txt"));
    return r;
  };
  // Not a shared object at all: dlopen fails.
  { std::ofstream(module) << "not an ELF file\n"; }
  CliRun r = info();
  INFO(r.err);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "occt_module_not_loaded");
  CHECK(r.err.find(module.string()) != std::string::npos);
  // A shared object that loads but is not plyfit's module (the C math library).
  fs::remove(module);
  fs::copy_file(shared_object_path("libm.so.6"), module);
  r = info();
  INFO(r.err);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "occt_module_no_entry");
}
