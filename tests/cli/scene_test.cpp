// Scene files: INI with sections, relative paths against the scene's folder, flags override
// keys, one-line errors naming the file, the key and the problem, and --dump-scene output that
// loads back to the same job.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

using namespace plyfit::test;
using nlohmann::json;

namespace {

/// Table 1 case (a) on the built-in octant, as flags.
const std::string& kFlags = kOctantFlags;

/// The same drape as a scene file with sections.
const std::string kScene =
    "# Table 1 (a)\n[mold]\nmold = builtin:sphere-octant\n\n[ply]\nspacing = 1\n\n[start]\n"
    "start2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\nstart3d = 0,0,20\nbase-normal = 0,1,0\n"
    "sweep3d = 0,1,0\n";

json report(const std::string& dir) {
  return json::parse(slurp(dir + "/report.json"));
}

/// The figures of a report that depend on the job only (not on timings or paths).
json figures(const json& r) {
  return {r["status"],
          r["nodes"],
          r["flat_area"],
          r["surface_area"],
          r["thread_angle"],
          r["shear_energy"],
          r["inputs"]["spacing_weft"],
          r["inputs"]["sweep3d"]};
}

}  // namespace

TEST_CASE("cli: a scene file gives the same drape as the flags") {
  Scratch tmp("scene_same");
  spit(tmp.file("a.ini"), kScene);
  CliRun r = plyfit_run("drape " + kFlags + " -o '" + tmp.file("flags") + "' --quiet", tmp);
  REQUIRE(r.code == 0);
  r = plyfit_run("drape '" + tmp.file("a.ini") + "' -o '" + tmp.file("scene") + "' --quiet", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(figures(report(tmp.file("flags"))) == figures(report(tmp.file("scene"))));
}

TEST_CASE("cli: scene paths are relative to the scene file, flags to the working folder") {
  Scratch tmp("scene_paths");
  std::filesystem::create_directories(tmp.path / "scenes" / "molds");
  std::filesystem::create_directories(tmp.path / "elsewhere");
  CliRun r =
      plyfit_run("sample sphere-octant -o '" + tmp.file("scenes/molds/octant.step") + "'", tmp);
  REQUIRE(r.code == 0);
  std::string scene = kScene;
  scene.replace(scene.find("builtin:sphere-octant"), 21, "molds/octant.step");
  spit(tmp.file("scenes/a.ini"), scene + "\n[output]\noutput = out-from-scene\n");
  // Run from another folder: the mold and the output are found next to the scene.
  r = plyfit_run("drape ../scenes/a.ini --quiet", tmp, tmp.file("elsewhere"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(std::filesystem::exists(tmp.file("scenes/out-from-scene/report.json")));
  CHECK(report(tmp.file("scenes/out-from-scene"))["nodes"]["mapped"] == 716);
  // -o on the command line overrides the scene's output and is relative to the working folder.
  r = plyfit_run("drape ../scenes/a.ini -o out-from-flag --quiet", tmp, tmp.file("elsewhere"));
  REQUIRE(r.code == 0);
  CHECK(std::filesystem::exists(tmp.file("elsewhere/out-from-flag/report.json")));
}

TEST_CASE("cli: flags override scene keys") {
  Scratch tmp("scene_override");
  spit(tmp.file("a.ini"), kScene);
  CliRun r = plyfit_run(
      "drape '" + tmp.file("a.ini") + "' --spacing 2 -o '" + tmp.file("o") + "' --quiet", tmp);
  REQUIRE(r.code == 0);
  CHECK(report(tmp.file("o"))["inputs"]["spacing_weft"] == 2.0);
  // A repeatable key given as a flag replaces the scene's whole list.
  r = plyfit_run("drape '" + tmp.file("a.ini") + "' --sweep2d 0,-1 --dump-scene", tmp);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("sweep2d = 0,-1\n") != std::string::npos);
  CHECK(r.out.find("sweep2d = 0,1\n") == std::string::npos);
}

TEST_CASE("cli: scene errors name the file, the line or key, and the problem's code, on one line") {
  Scratch tmp("scene_errors");
  // The error's code and what its line starts with after "plyfit: error: " (kScene is 14
  // lines: a line added after it is line 15).
  struct Case {
    std::string text, code, starts;
  };
  const std::string f = tmp.file("s.ini");
  const std::vector<Case> cases = {
      {kScene + "colour = red\n", "unknown_key", f + ":15: "},
      {kScene + "[material]\nlock = 40\n", "unknown_key", f + ":16: "},
      {"[mold]\nmold = builtin:sphere-octant\nspacing = 1\n", "missing_option", f + ": "},
      {[] {
         std::string s = kScene;
         return s.replace(s.find("spacing = 1"), 11, "spacing = one");
       }(),
       "not_a_number", f + ": key 'spacing': "},
      {[] {
         std::string s = kScene;
         return s.replace(s.find("start3d = 0,0,20"), 16, "start3d = 0,20");
       }(),
       "vector_size", f + ": key 'start3d': "},
      {kScene + "spacing = 2\n", "option_repeated", f + ": key 'spacing': "},
      {kScene + "this line has no equals sign\n", "ini_syntax", f + ":15: "},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    spit(f, c.text);
    const CliRun r = plyfit_run("drape '" + f + "' -o '" + tmp.file("o") + "'", tmp);
    INFO(r.err);
    CHECK(r.code == 1);
    CHECK(error_code(r) == c.code);
    CHECK(r.err.rfind("plyfit: error: " + c.starts, 0) == 0);
    CHECK_FALSE(std::filesystem::exists(tmp.file("o")));
  }
  // A missing scene file.
  CliRun r = plyfit_run("drape '" + tmp.file("none.ini") + "' -o '" + tmp.file("o") + "'", tmp);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "scene_cannot_open");
  CHECK(r.err.rfind("plyfit: error: " + tmp.file("none.ini") + ": ", 0) == 0);
  // A bad flag overriding a good scene is named as the flag (a bad command line: 2).
  spit(f, kScene);
  r = plyfit_run("drape '" + f + "' --spacing abc -o '" + tmp.file("o") + "'", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "not_a_number");
  CHECK(r.err.rfind("plyfit: error: --spacing: ", 0) == 0);
  r = plyfit_run("drape '" + f + "' --no-such-flag 1 -o '" + tmp.file("o") + "'", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "unknown_option");
  CHECK(r.err.find("--no-such-flag") != std::string::npos);
}

TEST_CASE("cli: a dumped scene loads back to the same job") {
  Scratch tmp("scene_dump");
  // Every kind of key: switches, repeatable keys, defaults, non-default numerics.
  const std::string flags =
      kFlags +
      " --ply 30,25 --lock-angle 60 --warn-angle 50 --material carbon-twill "
      "--ply-name P1 --tolerance 1e-13 --max-iterations 30 --guess parallelogram "
      "--flip-normal --view 0,0,1 -o '" +
      tmp.file("out") + "'";
  const CliRun d1 = plyfit_run("drape " + flags + " --dump-scene", tmp);
  INFO(d1.err);
  REQUIRE(d1.code == 0);
  CHECK(d1.out.find("[start]") != std::string::npos);
  CHECK(d1.out.find("lock-angle = 60") != std::string::npos);
  CHECK(d1.out.find("max-nodes = 50000000") != std::string::npos);  // defaults filled in
  spit(tmp.file("dumped.ini"), d1.out);
  // Loading the dump and dumping again gives the same text: the same job.
  const CliRun d2 = plyfit_run("drape '" + tmp.file("dumped.ini") + "' --dump-scene", tmp);
  REQUIRE(d2.code == 0);
  CHECK(d2.out == d1.out);
  // And the same drape.
  CliRun r = plyfit_run("drape " + flags + " --quiet", tmp);
  REQUIRE(r.code == 0);
  r = plyfit_run("drape '" + tmp.file("dumped.ini") + "' -o '" + tmp.file("out2") + "' --quiet",
                 tmp);
  REQUIRE(r.code == 0);
  CHECK(figures(report(tmp.file("out"))) == figures(report(tmp.file("out2"))));
  // A scene file needs no output folder to be dumped.
  spit(tmp.file("a.ini"), kScene);
  r = plyfit_run("drape '" + tmp.file("a.ini") + "' --dump-scene", tmp);
  CHECK(r.code == 0);
  CHECK(r.out.find("output =") == std::string::npos);
}

TEST_CASE("cli: plyfit sample writes a named mold file, with exit codes for bad input") {
  Scratch tmp("sample_cli");
  CliRun r =
      plyfit_run("sample saddle:size=30 --name 'my saddle' -o '" + tmp.file("s.igs") + "'", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.empty());
  r = plyfit_run("info --json '" + tmp.file("s.igs") + "'", tmp);
  REQUIRE(r.code == 0);
  const json info = json::parse(r.out);
  REQUIRE(info["faces"].size() == 1);
  CHECK(info["faces"][0]["name"] == "my saddle");
  CHECK(info["faces"][0]["reversed"] == false);
  // --format overrides the extension.
  r = plyfit_run("sample cone --format step -o '" + tmp.file("c.dat") + "'", tmp);
  REQUIRE(r.code == 0);
  CHECK(slurp(tmp.file("c.dat")).rfind("ISO-10303-21;", 0) == 0);
  // Bad command lines exit 2, a failed write 1; each with one line and its code (any code for
  // the errors of other modules not yet given one of their own) and no file left behind.
  struct Bad {
    std::string args;
    int exit;
    std::string code;
  };
  for (const auto& b :
       std::vector<Bad>{{"sample wave -o '" + tmp.file("w.obj") + "'", 2, "unknown_mold_format"},
                        {"sample nope -o '" + tmp.file("n.step") + "'", 2, ""},
                        {"sample wave:n=2 -o '" + tmp.file("n.step") + "'", 2, ""},
                        {"sample wave", 2, "missing_option"},
                        {"sample wave -o '" + tmp.file("no/such/folder/w.step") + "'", 1, ""}}) {
    INFO(b.args);
    r = plyfit_run(b.args, tmp);
    CHECK(r.code == b.exit);
    CHECK((b.code.empty() ? !error_code(r).empty() : error_code(r) == b.code));
  }
  CHECK_FALSE(std::filesystem::exists(tmp.file("w.obj")));
  CHECK_FALSE(std::filesystem::exists(tmp.file("n.step")));
}
