// The README documents every command, every drape option (= scene key), every built-in
// mold, every output file and every report.json node status; its test command is the one CI
// runs. Read from the built plyfit's own listings, so a new option without documentation
// fails here.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <regex>
#include <sstream>

using namespace plyfit;
using namespace plyfit::test;

namespace {
std::string readme() {
  return slurp(std::string(PLYFIT_SOURCE_DIR) + "/README.md");
}
}  // namespace

TEST_CASE("cli: the README documents every command, option, mold, output and status") {
  const std::string doc = readme();
  REQUIRE(doc.size() > 1000);
  Scratch s("readme");
  // Commands, as plyfit --help lists them.
  const CliRun help = plyfit_run("--help", s);
  REQUIRE(help.code == 0);
  std::istringstream lines(help.out.substr(help.out.find("commands:")));
  std::string line;
  std::getline(lines, line);
  int commands = 0;
  while (std::getline(lines, line)) {
    std::istringstream w(line);
    std::string name;
    if (!(w >> name)) continue;
    INFO("command " << name);
    CHECK(doc.find("plyfit " + name) != std::string::npos);
    ++commands;
  }
  CHECK(commands >= 5);
  // Drape options: every key of the scene-key table, as a flag or a key.
  const CliRun keys = plyfit_run("drape --scene-keys", s);
  REQUIRE(keys.code == 0);
  const std::regex key_row(R"(^\| `([a-z0-9-]+)`)");
  int options = 0;
  std::istringstream kl(keys.out);
  while (std::getline(kl, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, key_row)) continue;
    INFO("option --" << m[1]);
    CHECK(doc.find("`--" + m[1].str() + "`") != std::string::npos);
    ++options;
  }
  CHECK(options >= 25);
  // Built-in molds and their parameters.
  for (const auto& b : builtin_molds()) {
    INFO("built-in mold " << b.name);
    CHECK(doc.find("`" + b.name + "`") != std::string::npos);
    for (const auto& p : b.params) CHECK(doc.find(p.key + "=") != std::string::npos);
  }
  // Output files of every writer, in the README's "Output files" section.
  const auto sec = doc.find("## Output files");
  REQUIRE(sec != std::string::npos);
  const std::string outputs = doc.substr(sec, doc.find("\n## ", sec + 3) - sec);
  for (const auto& e : exporters::registry())
    for (const auto& f : e.files) {
      INFO("output " << f);
      CHECK(outputs.find(f) != std::string::npos);
    }
  // Node statuses (report.json's nodes).
  for (const char* st : {"mapped", "auxiliary", "outside", "off_ply", "shear_limit", "failed",
                         "overlap", "conflict", "path_end", "failed_reasons", "conflict_reasons"}) {
    INFO("status " << st);
    std::string quoted = "`";
    quoted += st;
    quoted += '`';
    CHECK(doc.find(quoted) != std::string::npos);
  }
}

TEST_CASE("cli: the README's test command is the one .ci/run runs") {
  const std::string ci = slurp(std::string(PLYFIT_SOURCE_DIR) + "/.ci/run");
  const auto a = ci.find("cmd='"), b = ci.find("'", a + 5);
  REQUIRE(a != std::string::npos);
  const std::string cmd = ci.substr(a + 5, b - a - 5);
  CHECK(readme().find(cmd) != std::string::npos);
}
