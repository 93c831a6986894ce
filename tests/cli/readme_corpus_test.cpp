// The README's first drape on a shared CAD file (../shared/cad), run as the README writes it:
// each command of its section, from the repository root, prints the lines the README shows
// (a line "..." stands for lines left out; the time and the output folder of a drape's summary
// line vary), and the drape writes the files the README names.

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/markdown.hpp"
#include "corpus.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

using namespace plyfit::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// A command of the README and the output it shows.
struct Shown {
  std::string command;
  std::vector<std::string> lines;
};

/// The ```sh blocks of `section`, each with the ```text block that follows it.
std::vector<Shown> shown_commands(const std::string& section) {
  std::vector<Shown> out;
  std::istringstream in(section);
  std::string line, kind;
  while (std::getline(in, line)) {
    if (line == "```sh" || line == "```text") {
      kind = line.substr(3);
      if (kind == "sh") out.push_back({});
      continue;
    }
    if (line == "```") {
      kind.clear();
      continue;
    }
    if (kind == "sh") {
      const bool continued = !line.empty() && line.back() == '\\';
      out.back().command +=
          trimmed(continued ? line.substr(0, line.size() - 1) : line) + (continued ? " " : "");
    } else if (kind == "text" && !out.empty()) {
      out.back().lines.push_back(line);
    }
  }
  return out;
}

/// A drape's summary line without what varies from run to run (its time and output folder).
std::string steady(const std::string& line) {
  static const std::regex varying("; [0-9]+ ms -> .*$");
  return std::regex_replace(line, varying, "; N ms -> DIR");
}

/// Runs each command of `commands` as the README writes it, from the repository root, its
/// output folder (`-o NAME`) made s.file(NAME), and checks it prints the lines shown.
void run_as_shown(const std::vector<Shown>& commands, const Scratch& s) {
  const std::string program = "build/bin/plyfit ";
  static const std::regex output(" -o ([^ ']+)$");
  for (const auto& c : commands) {
    INFO(c.command);
    REQUIRE(c.command.rfind(program, 0) == 0);
    std::string args = c.command.substr(program.size());
    std::smatch m;
    if (std::regex_search(args, m, output))
      args = m.prefix().str() + " -o '" + s.file(m[1].str()) + "'";
    const CliRun run = plyfit_run(args, s, PLYFIT_SOURCE_DIR);
    INFO(run.err);
    REQUIRE(run.code == 0);
    // The lines shown, in order, among the lines printed.
    std::istringstream printed(run.out);
    std::string line;
    std::size_t next = 0;
    auto skip_elided = [&] {
      while (next < c.lines.size() && c.lines[next] == "...") ++next;
    };
    skip_elided();
    while (next < c.lines.size() && std::getline(printed, line))
      if (steady(c.lines[next]) == steady(line)) {
        ++next;
        skip_elided();
      }
    INFO("first line not printed: " << (next < c.lines.size() ? c.lines[next] : ""));
    CHECK(next == c.lines.size());
  }
}

}  // namespace

TEST_CASE("cli: the README's first drape on a shared CAD file runs as the README shows it") {
  const std::string section =
      md_section(source_file("README.md"), "## A first drape on a real CAD file");
  REQUIRE(!section.empty());
  const auto commands = shown_commands(section);
  REQUIRE(commands.size() >= 2);
  Scratch s("readme_corpus");
  run_as_shown(commands, s);
  // The files the README says the drape writes into first/: all there, and nothing else.
  std::set<std::string> said, written;
  const std::regex file("`([a-z]+\\.(dxf|step|svg|vtk|glb|json))`");
  const std::string after = section.substr(section.rfind("```"));
  for (auto it = std::sregex_iterator(after.begin(), after.end(), file);
       it != std::sregex_iterator(); ++it)
    said.insert((*it)[1]);
  for (const auto& e : fs::directory_iterator(s.file("first")))
    written.insert(e.path().filename().string());
  CHECK(said == written);
}

TEST_CASE(
    "cli: the README's ply definition runs as shown: a 45 deg ply, then the 0/45/90/-45 set") {
  const std::string section = md_section(source_file("README.md"), "## Defining a ply");
  REQUIRE(!section.empty());
  const auto commands = shown_commands(section);
  REQUIRE(commands.size() == 3);
  Scratch s("readme_corpus_ply");
  run_as_shown(commands, s);
  const json p45 = json::parse(slurp(s.file("P45") + "/report.json"));
  CHECK(p45["ply"]["laid_angle_deg"].get<double>() == Approx(45.0).margin(1e-9));
  CHECK(!p45["ply"]["boundary"].is_null());
  // Every ply of the set bounded, at the four angles.
  const json book = json::parse(slurp(s.file("plies") + "/plybook.json"));
  std::set<double> angles;
  int bounded = 0;
  for (const auto& ply : book["plies"]) {
    angles.insert(ply["angle_deg"].get<double>());
    const std::string name = ply["name"].get<std::string>();
    const json r = json::parse(slurp(s.file("plies") + "/" + name + "/report.json"));
    bounded += r["ply"]["boundary"].is_null() ? 0 : 1;
  }
  CHECK(book["plies"].size() >= 8);
  CHECK(bounded == static_cast<int>(book["plies"].size()));
  CHECK(angles == std::set<double>{-45.0, 0.0, 45.0, 90.0});
}
