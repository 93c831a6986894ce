// plyfit drape from the command line: bad input is one line on stderr, a non-zero exit and
// no output. Drapes on the real CAD files of ../shared/cad: drape_corpus_test.cpp.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/rejected.hpp"

#include <filesystem>
#include <sstream>
#include <utility>

using namespace plyfit;
using namespace plyfit::test;

namespace {
const std::string kCaseA =
    "--mold builtin:sphere-octant --spacing 1 --start2d 0,0 --base2d 1,0 --sweep2d 0,1 "
    "--start3d 0,0,20 --base-normal 0,1,0 --sweep3d 0,1,0";

// The case (a) command with one option replaced (or added).
std::string with(const std::string& opt, const std::string& value) {
  std::string s = kCaseA;
  const auto at = s.find("--" + opt + " ");
  if (at == std::string::npos) return s + " --" + opt + " " + value;
  const auto end = s.find(" --", at + 2);
  return s.substr(0, at) + "--" + opt + " " + value +
         (end == std::string::npos ? "" : s.substr(end));
}
// `plyfit drape ARGS --outputs json` into scratch folder o: the run and its report.json.
std::pair<CliRun, nlohmann::json> drape_report(const std::string& args, const Scratch& s) {
  const CliRun r = plyfit_run("drape " + args + " --outputs json -o '" + s.file("o") + "'", s);
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  return {r, nlohmann::json::parse(slurp(s.file("o") + "/report.json"))};
}

}  // namespace

TEST_CASE("cli: bad drape input is one line with its code, a non-zero exit and no output") {
  Scratch s("drape_bad");
  check_rejected(
      "drape",
      {
          {with("spacing", "0"), 2, "spacing_not_positive", "--spacing"},
          {with("spacing", "-1"), 2, "spacing_not_positive", "--spacing"},
          {with("spacing", "nan"), 2, "not_finite", "--spacing"},
          {with("spacing", "one"), 2, "not_a_number", "--spacing"},
          {with("start2d", "0,abc"), 2, "not_a_number", "--start2d"},
          {with("start3d", "0,0"), 2, "vector_size", "--start3d"},
          {with("sweep2d", "1,0"), 2, "sweep_along_path", "--sweep2d"},
          {with("base-normal", "0,0,1"), 1, "base_normal_tangent", "--base-normal"},
          {with("mold", "builtin:spere"), 1, "", "unknown built-in mold"},
          {with("mold", "builtin:sphere-octant:Q=3"), 1, "", "no parameter 'Q'"},
          {with("mold", "builtin:sphere-octant:R=abc"), 1, "", "malformed value"},
          {with("sweep3d", "1,0,0"), 1, "sweep3d_along_path", "--sweep3d"},
          {with("lock-angle", "120"), 2, "lock_angle_range", "--lock-angle"},
          {with("outputs", "json,pdf"), 2, "unknown_value", "--outputs"},
          {with("frobnicate", "3"), 2, "unknown_option", "--frobnicate"},
          {"--mold builtin:sphere-octant --spacing 1", 2, "missing_option", "--start2d"},
          {with("mold", "'" + s.file("missing.step") + "'"), 1, "", s.file("missing.step")},
      },
      s);
}

TEST_CASE("cli: a drape's input checked against the mold names the option; nonsense is partial") {
  Scratch s("drape_nonsense");
  // Half a degree off the base path (-X at the pole): an error naming --sweep3d, exit 1.
  CliRun r =
      plyfit_run("drape " + with("sweep3d", "-1,0.0087,0") + " -o '" + s.file("o1") + "'", s);
  INFO(r.err);
  CHECK(r.code == 1);
  CHECK(error_code(r) == "sweep3d_along_path");
  CHECK(r.err.rfind("plyfit: error: --sweep3d: ", 0) == 0);
  CHECK_FALSE(std::filesystem::exists(s.file("o1")));
  // A drape that ran but is not what was asked for: exit 0, status partial, the warning shown.
  struct Partial {
    std::string args, says;
  };
  std::string off_face = with("sweep2d", "0,-1");  // swept off the octant's edge y = 0
  off_face.replace(off_face.find("--sweep3d 0,1,0"), 15, "--sweep3d 0,-1,0");
  const std::vector<Partial> cases = {
      {with("start3d", "0,0,866"), "846 mm from the surface"},
      {off_face, exporters::message(Warning{WarningCode::kNoCellMapped, {}})},
  };
  for (const auto& c : cases) {
    const std::string& args = c.args;
    const std::string out = s.file("o2");
    std::filesystem::remove_all(out);
    r = plyfit_run("drape " + args + " --outputs json -o '" + out + "'", s);
    INFO(args << "\n-> exit " << r.code << ": " << r.err);
    CHECK(r.code == 0);
    CHECK(r.err.find("plyfit: warning: ") != std::string::npos);
    CHECK(r.err.find(c.says) != std::string::npos);
    const std::string report = slurp(out + "/report.json");
    CHECK(report.find("\"status\": \"partial\"") != std::string::npos);
    CHECK(report.find(c.says) != std::string::npos);
  }
}

TEST_CASE(
    "cli: where two fronts of cloth disagree, report.json counts conflict nodes, not failed") {
  // The kernel's hemisphere case (drape_test.cpp, a fuzz drape of seed 11): a node reached
  // from three sides that no point of the sphere fits. report.json gives it under
  // nodes.conflict with its reason in nodes.conflict_reasons; nothing under failed.
  Scratch s("drape_conflict");
  const std::string args =
      "--mold builtin:hemisphere:R=1 --spacing 0.0466772 --start2d 0,0 "
      "--base2d -0.971152,-0.238460 --sweep2d 0.238460,-0.971152 --sweep2d -0.238460,0.971152 "
      "--start3d -0.156435,-0.287080,0.517885 --base-normal -0.135449,0.932291,-0.335392 "
      "--sweep3d 0.259241,0.965348,0.029947 --sweep3d -0.259241,-0.965348,-0.029947";
  const auto [r, j] = drape_report(args, s);
  const auto& nodes = j.at("nodes");
  const auto conflict = nodes.at("conflict").get<std::uint64_t>();
  CHECK(conflict >= 1);
  CHECK(nodes.at("failed") == 0);
  CHECK(nodes.at("failed_reasons").empty());
  std::uint64_t counted = 0;
  for (const auto& [why, count] : nodes.at("conflict_reasons").items()) {
    CHECK(why.rfind("the fronts disagree: ", 0) == 0);
    counted += count.get<std::uint64_t>();
  }
  CHECK(counted == conflict);
  CHECK(j.at("status") == "partial");
  const std::string warning = exporters::message(
      Warning{WarningCode::kConflictNodes, {static_cast<std::int64_t>(conflict)}});
  bool in_report = false;
  for (const auto& w : j.at("warnings"))
    in_report = in_report || (w.at("code") == "conflict_nodes" && w.at("text") == warning);
  CHECK(in_report);
  CHECK(r.err.find("plyfit: warning: " + warning) != std::string::npos);
  CHECK(r.out.find(", " + std::to_string(conflict) + " in conflict;") != std::string::npos);
}

TEST_CASE("cli: a drape ok but short of its face by more than the coverage rule warns") {
  // One sweep from the middle line of the plate 100 x 60 at d = 10 covers its upper half: the
  // mapped cells' band test lets it pass (kernel coverage_test), the outline's coverage (50 %)
  // does not. The job warns outline_short, in report.json and on stderr; the status stays ok.
  Scratch s("drape_outline_short");
  const std::string args =
      "--mold builtin:plate --spacing 10 --start2d 0,0 --base2d 1,0 --sweep2d 0,1 "
      "--start3d 50,30,0 --base-normal 0,1,0 --sweep3d 0,1,0";
  const auto [r, j] = drape_report(args, s);
  CHECK(j.at("status") == "ok");
  REQUIRE(j.at("warnings").size() == 1);
  CHECK(j.at("warnings")[0].at("code") == "outline_short");
  const std::string warning = j.at("warnings")[0].at("text");
  CHECK(r.err.find("plyfit: warning: " + warning + "\n") != std::string::npos);
}
