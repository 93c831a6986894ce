#pragma once
// The drapes the writers' tests write (tests/occt/exporters_test.cpp, net_step_test.cpp): the
// paper's sphere-octant cases, a two-sided sweep, a torus, a trimmed IGES face with a hole, a
// plate the cloth flows round and a shell, each with everything the writers need; and scratch
// folders removed when the test program ends.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "support/face_of.hpp"
#include "surface/shell/shell.hpp"

#include <unistd.h>
#include <catch2/catch.hpp>

#include "occt_reference.hpp"  // read_bytes
#include "support/problems.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace plyfit::test {

namespace fs = std::filesystem;

// A drape with everything the writers need, kept alive together.
struct Case {
  std::string name;
  MoldSurface surface;                  ///< a face or a shell
  std::vector<NurbsSurfaceData> molds;  ///< the surfaces of its faces
  DrapeProblem problem;
  DrapeResult result;
  FlatPattern flat;
  exporters::RunInfo run;
  exporters::ExportOptions options;
  exporters::ExportContext ctx() const { return {problem, result, surface, &flat, run, options}; }
};

inline std::unique_ptr<Case> make_case(const std::string& mold,
                                       std::shared_ptr<const DrapeSurface> surface,
                                       std::vector<NurbsSurfaceData> molds, DrapeProblem pb) {
  auto r = drape(*surface, pb);  // the kernel's own drape() of a Face or Shell
  INFO(mold << ": " << (r.ok() ? std::string() : exporters::describe(r.error())));
  REQUIRE(r.ok());
  FlatPattern flat = flat_pattern(*surface, *r);
  auto c = std::unique_ptr<Case>(new Case{mold,
                                          MoldSurface(std::move(surface)),
                                          std::move(molds),
                                          pb,
                                          std::move(r).value(),
                                          std::move(flat),
                                          {},
                                          {}});
  c->run.mold = mold;
  c->run.ply_name = "test ply";
  c->run.material = "plain weave";
  return c;
}

inline std::unique_ptr<Case> make_case(const std::string& mold, Result<Face> face,
                                       DrapeProblem pb) {
  INFO(mold << ": " << (face.ok() ? std::string() : exporters::describe(face.error())));
  REQUIRE(face.ok());
  std::vector<NurbsSurfaceData> molds = {face->surface().data()};
  return make_case(mold, std::make_shared<const Face>(std::move(face).value()), std::move(molds),
                   std::move(pb));
}

inline std::unique_ptr<Case> make_case(const std::string& mold, Result<MoldSurface> surface,
                                       DrapeProblem pb) {
  INFO(mold << ": " << (surface.ok() ? std::string() : exporters::describe(surface.error())));
  REQUIRE(surface.ok());
  return make_case(mold, Face(test::face_of(*surface)), std::move(pb));
}

// A drape across the faces of built-in shell `name`.
inline std::unique_ptr<Case> make_shell_case(const std::string& name, DrapeProblem pb) {
  auto data = builtin_shell(name, {});
  REQUIRE(data.ok());
  std::vector<NurbsSurfaceData> molds;
  for (const FaceData& f : data->faces) molds.push_back(f.surface);
  auto shell = Shell::create(std::move(data).value());
  INFO(name << ": " << (shell.ok() ? std::string() : exporters::describe(shell.error())));
  REQUIRE(shell.ok());
  return make_case("builtin:" + name, std::make_shared<const Shell>(std::move(shell).value()),
                   std::move(molds), std::move(pb));
}

inline std::unique_ptr<Case> make_case(const std::string& mold,
                                       std::map<std::string, double> params, DrapeProblem pb) {
  auto fd = builtin_mold(mold, params);
  REQUIRE(fd.ok());
  return make_case("builtin:" + mold, Face::create(std::move(fd).value()), std::move(pb));
}

using support::problem;

// The paper's sphere-octant cases (a) and (c), a base path off the grid (auxiliary points),
// a two-sided sweep on the surface of revolution and a torus.
inline std::vector<std::unique_ptr<Case>> cases() {
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
  // A trimmed face with a hole read from IGES (plyfit's sample dish: the corpus's trimmed
  // CATIA face PRO20359-L1 runs in the exporter case of tests/CMakeLists.txt), swept both ways.
  const std::string dish = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/dish.igs";
  v.push_back(make_case(dish, importers::load_face(dish, 0),
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {18, 0, 4.05}, {0, 1, 0},
                                {{0, 1, 0}, {0, -1, 0}})));
  // A plate with a hole that the cloth flows round: the outline has a hole.
  v.push_back(make_case("plate",
                        {{"W", 100}, {"H", 60}, {"hole_r", 10}, {"hole_x", 50}, {"hole_y", 30}},
                        problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {20, 10, 0}, {0, 1, 0},
                                {{0, 1, 0}, {0, -1, 0}})));
  // A shell: from the flange over the fillet onto the wall, swept both ways.
  v.push_back(make_shell_case("flange-fillet-wall",
                              problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {-20, 30, 0}, {0, 1, 0},
                                      {{0, 1, 0}, {0, -1, 0}})));
  return v;
}

// Scratch folders, one per name and process (test runs of several clones at once, or ctest
// -j, must not share one), removed when the test program ends.
struct ScratchDirs {
  std::vector<fs::path> made;
  ~ScratchDirs() {
    std::error_code ec;
    for (const auto& p : made) fs::remove_all(p, ec);
  }
};
inline ScratchDirs scratch_dirs;

inline fs::path fresh_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("plyfit_exporters_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  scratch_dirs.made.push_back(p);
  fs::create_directories(p);
  return p;
}

}  // namespace plyfit::test
