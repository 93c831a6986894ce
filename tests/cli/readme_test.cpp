// The README and the manual (docs/): the README gives the two commands (the second is the one
// CI runs) and links into docs/, whose pages document every command, every option of every
// command, every scene key, built-in mold and shell, output file and report.json field, each on
// its own page. Read from the built plyfit's own listings and outputs, so a new option, key or
// field without documentation fails here; every link of the README and of docs/ must lead to
// a file and heading that exist; docs/errors.md documents every error and warning code (read
// from the X-macros of result.hpp). (The README's first drape, on a shared CAD file, is run in
// readme_corpus_test.cpp.)

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/result.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/drape_report.hpp"
#include "cli/markdown.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>

using namespace plyfit;
using namespace plyfit::test;
namespace fs = std::filesystem;

namespace {

const std::string kReadme = "README.md";

/// The page of docs/ that documents each command's options.
const std::map<std::string, std::string> kCommandPages = {
    {"info", "docs/info.md"},        {"drape", "docs/options.md"},     {"batch", "docs/batch.md"},
    {"compare", "docs/compare.md"},  {"optimize", "docs/optimize.md"}, {"sample", "docs/sample.md"},
    {"laminate", "docs/laminate.md"}};

/// The commands `plyfit --help` lists.
std::vector<std::string> commands(const Scratch& s) {
  const CliRun help = plyfit_run("--help", s);
  REQUIRE(help.code == 0);
  std::vector<std::string> out;
  std::istringstream lines(help.out.substr(help.out.find("commands:")));
  std::string line, name;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    std::istringstream w(line);
    if (w >> name) out.push_back(name);
  }
  REQUIRE(out.size() >= 6);
  return out;
}

/// The options (without the dashes) that `plyfit COMMAND --help` lists, one per line:
/// "  --name ..." or Boost's "  -j [ --jobs ] ...".
std::vector<std::string> help_options(const std::string& command, const Scratch& s) {
  const CliRun help = plyfit_run(command + " --help", s);
  REQUIRE(help.code == 0);
  std::vector<std::string> out;
  const std::regex option(R"(^  (?:-[a-z] \[ )?--([a-z][a-z0-9-]*))");
  std::istringstream lines(help.out);
  std::string line;
  std::smatch m;
  while (std::getline(lines, line))
    if (std::regex_search(line, m, option)) out.push_back(m[1]);
  return out;
}

/// The text between the first pair of backticks of `cell`.
std::string code_of(const std::string& cell) {
  const auto a = cell.find('`'), b = cell.find('`', a + 1);
  return a == std::string::npos || b == std::string::npos ? std::string()
                                                          : cell.substr(a + 1, b - a - 1);
}

/// The rows of `plyfit drape --scene-keys`: key -> its cells (section, value, default, ...).
std::map<std::string, std::vector<std::string>> scene_keys(const Scratch& s) {
  const CliRun keys = plyfit_run("drape --scene-keys", s);
  REQUIRE(keys.code == 0);
  std::map<std::string, std::vector<std::string>> out;
  for (const auto& row : table_rows(keys.out))
    if (row.size() == 5 && row[0].rfind("`", 0) == 0) out[code_of(row[0])] = row;
  REQUIRE(out.size() >= 25);
  return out;
}

/// Every field path of a report.json (`a.b`, `a[].b` for the elements of array a), but not the
/// keys of the maps keyed by a failure's reason.
void field_paths(const nlohmann::json& j, const std::string& at, std::set<std::string>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string path = at.empty() ? it.key() : at + "." + it.key();
    out.insert(path);
    if (path == "nodes.failed_reasons" || path == "nodes.conflict_reasons" ||
        path == "nodes.shear_limit_reasons" || path == "nodes.overlap_reasons")
      continue;
    if (it->is_object()) field_paths(*it, path, out);
    if (it->is_array() && !it->empty() && it->front().is_object())
      field_paths(it->front(), path + "[]", out);
  }
}

/// Every error code's name (PLYFIT_ERROR_CODES) and every warning code's
/// (PLYFIT_WARNING_CODES), in order.
#define PLYFIT_CODE_NAME(name, snake) #snake,
const std::vector<std::string> kErrorCodes = {PLYFIT_ERROR_CODES(PLYFIT_CODE_NAME)};
const std::vector<std::string> kWarningCodes = {PLYFIT_WARNING_CODES(PLYFIT_CODE_NAME)};
#undef PLYFIT_CODE_NAME

/// The codes a section of docs/errors.md documents: the first cells `name` of its table rows,
/// each row with a meaning and what to do.
std::set<std::string> documented_codes(const std::string& section) {
  std::set<std::string> out;
  for (const auto& row : table_rows(section)) {
    if (row.empty() || row[0].size() < 3 || row[0].front() != '`' || row[0].back() != '`') continue;
    INFO("docs/errors.md: " << row[0]);
    CHECK(row.size() == 3);
    CHECK((row.size() > 2 && !row[1].empty() && !row[2].empty()));
    out.insert(row[0].substr(1, row[0].size() - 2));
  }
  return out;
}

/// The markdown files of the manual: the README and every page under docs/.
std::vector<std::string> manual_files() {
  std::vector<std::string> out = {kReadme};
  const fs::path root(PLYFIT_SOURCE_DIR);
  for (const auto& e : fs::recursive_directory_iterator(root / "docs"))
    if (e.is_regular_file() && e.path().extension() == ".md")
      out.push_back(fs::relative(e.path(), root).string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("cli: the README gives both commands, and its first one drapes into the files it names") {
  const std::string readme = source_file(kReadme);
  const auto block = readme.find("```sh\n");
  REQUIRE(block != std::string::npos);
  std::istringstream lines(readme.substr(block + 6));
  std::string first, second;
  std::getline(lines, first);
  std::getline(lines, second);
  // The second is the one .ci/run runs.
  const std::string ci = source_file(".ci/run");
  const auto a = ci.find("cmd='"), b = ci.find("'", a + 5);
  REQUIRE(a != std::string::npos);
  CHECK(second == ci.substr(a + 5, b - a - 5));
  // The first builds plyfit and drapes a sample into ./out: run that drape.
  const std::string drape = "&& build/bin/plyfit ";
  const auto at = first.rfind(drape);
  REQUIRE(at != std::string::npos);
  std::string args = first.substr(at + drape.size());
  REQUIRE(args.size() > 7);
  REQUIRE(args.substr(args.size() - 7) == " -o out");
  Scratch s("readme_first");
  args = args.substr(0, args.size() - 3) + "'" + s.file("out") + "'";
  const CliRun run = plyfit_run(args, s, PLYFIT_SOURCE_DIR);
  INFO(run.err);
  REQUIRE(run.code == 0);
  // The files the README says it writes: every file of every writer, and they are there.
  const auto into = readme.find("into `./out`:");
  REQUIRE(into != std::string::npos);
  const std::string named = readme.substr(into, readme.find(". ", into) - into);
  std::set<std::string> said, written;
  const std::regex file("`([a-z]+\\.[a-z]+)`");
  for (auto it = std::sregex_iterator(named.begin(), named.end(), file);
       it != std::sregex_iterator(); ++it)
    said.insert((*it)[1]);
  for (const auto& e : exporters::registry())
    for (const auto& f : e.files) {
      INFO("output " << f);
      CHECK(fs::exists(s.file("out/" + f)));
      written.insert(f);
    }
  CHECK(said == written);
}

TEST_CASE(
    "cli: every command has its page in docs/, linked from the README and listed in "
    "docs/exit-codes.md") {
  Scratch s("readme_commands");
  const std::string readme = source_file(kReadme);
  const std::string exits = source_file("docs/exit-codes.md");
  for (const auto& c : commands(s)) {
    INFO("plyfit " << c);
    const auto page = kCommandPages.find(c);
    REQUIRE(page != kCommandPages.end());
    CHECK(source_file(page->second).find("plyfit " + c) != std::string::npos);
    const auto row = table_row(readme, "`plyfit " + c + "`");
    REQUIRE(row);
    CHECK(row->back().find("(" + page->second + ")") != std::string::npos);
    CHECK(table_row(exits, "`plyfit " + c + "`"));
  }
  CHECK(table_row(exits, "`plyfit`"));
}

TEST_CASE("cli: docs/index.md lists every page of the manual, and the README links to it") {
  const std::string index = source_file("docs/index.md");
  const auto links = link_targets(index);
  const std::set<std::string> linked(links.begin(), links.end());
  int pages = 0;
  for (const auto& f : manual_files()) {
    if (f == kReadme || f == "docs/index.md") continue;
    const std::string rel = f.substr(5);  // without "docs/"
    if (rel.find('/') != std::string::npos && rel != "decisions/README.md") continue;
    INFO(f);
    CHECK(linked.count(rel) == 1);
    ++pages;
  }
  CHECK(pages >= 15);
  const auto readme_links = link_targets(source_file(kReadme));
  CHECK(std::find(readme_links.begin(), readme_links.end(), "docs/index.md") != readme_links.end());
}

TEST_CASE("cli: docs/options.md documents every plyfit drape option, with plyfit's defaults") {
  Scratch s("readme_options");
  const std::string doc = source_file("docs/options.md");
  const auto keys = scene_keys(s);
  const auto options = help_options("drape", s);
  CHECK(options.size() >= keys.size() + 4);
  for (const auto& o : options) {
    INFO("--" << o);
    const auto row = table_row_holding(doc, "`--" + o + "`");
    REQUIRE(row);
    REQUIRE(row->size() == 4);
    // An option that is also a scene key has the key's default.
    if (const auto k = keys.find(o); k != keys.end()) CHECK((*row)[2] == k->second[3]);
  }
  CHECK(table_row_holding(doc, "`--help`"));
}

TEST_CASE("cli: docs/scene-files.md documents every scene key, with its section and default") {
  Scratch s("readme_keys");
  const std::string doc = md_section(source_file("docs/scene-files.md"), "## Keys");
  REQUIRE(!doc.empty());
  for (const auto& [key, cells] : scene_keys(s)) {
    INFO("key " << key);
    const auto row = table_row(doc, cells[0]);
    REQUIRE(row);
    REQUIRE(row->size() == 5);
    CHECK((*row)[1] == cells[1]);  // section
    CHECK((*row)[2] == cells[2]);  // value
    CHECK((*row)[3] == cells[3]);  // default
  }
}

TEST_CASE("cli: each command's page documents each of its options") {
  Scratch s("readme_command_options");
  for (const auto& [command, page] : kCommandPages) {
    if (command == "drape") continue;  // options.md, checked with the defaults above
    const std::string doc = source_file(page);
    const auto options = help_options(command, s);
    CHECK(options.size() >= 3);
    for (const auto& o : options) {
      INFO(page << ": --" << o);
      CHECK(table_row_holding(doc, "`--" + o + "`"));
    }
  }
}

TEST_CASE(
    "cli: docs/molds.md documents every built-in mold with its parameters, and every "
    "built-in shell") {
  Scratch s("readme_molds");
  const std::string doc = source_file("docs/molds.md");
  // "  NAME: k=v k=v" lines of plyfit drape --help.
  const CliRun help = plyfit_run("drape --help", s);
  REQUIRE(help.code == 0);
  const std::regex mold(R"(^  ([a-z0-9-]+):((?: [A-Za-z0-9_]+=[^ ]+)*)$)");
  std::istringstream lines(help.out.substr(help.out.find("built-in molds")));
  std::string line;
  std::smatch m;
  int molds = 0;
  while (std::getline(lines, line)) {
    if (!std::regex_search(line, m, mold)) continue;
    INFO("built-in mold " << m[1]);
    const auto row = table_row(doc, "`" + m[1].str() + "`");
    REQUIRE(row);
    std::string params = trimmed(m[2]);
    for (std::size_t p = 0; (p = params.find(' ', p)) != std::string::npos; p += 2)
      params.replace(p, 1, ", ");
    CHECK((*row)[1] == params);
    ++molds;
  }
  CHECK(molds >= 12);
  // "built-in shells: a b c" of plyfit sample --help.
  const CliRun sample = plyfit_run("sample --help", s);
  const auto at = sample.out.find("built-in shells:");
  REQUIRE(at != std::string::npos);
  std::istringstream shells(sample.out.substr(at + 16, sample.out.find('\n', at) - at - 16));
  int count = 0;
  for (std::string name; shells >> name; ++count) {
    INFO("built-in shell " << name);
    CHECK(table_row(doc, "`" + name + "`"));
  }
  CHECK(count >= 3);
}

TEST_CASE(
    "cli: the manual documents every output file: drape's under their keys, and those of "
    "batch and optimize") {
  const std::string doc = source_file("docs/outputs.md");
  const auto titles = headings(doc);
  for (const auto& e : exporters::registry()) {
    INFO("output " << e.key);
    const auto row = table_row(doc, "`" + e.key + "`");
    REQUIRE(row);
    std::string files;
    for (const auto& f : e.files) {
      files += (files.empty() ? "`" : ", `") + f + "`";
      INFO(f);
      CHECK(std::any_of(titles.begin(), titles.end(),
                        [&](const std::string& t) { return t.find(f) != std::string::npos; }));
    }
    CHECK((*row)[1] == files);
  }
  const auto batch = headings(source_file("docs/batch.md"));
  CHECK(std::find(batch.begin(), batch.end(), "summary.json and summary.csv") != batch.end());
  const std::string optimize = md_section(source_file("docs/optimize.md"), "## Output");
  for (const char* file : {"optimize.json", "front.svg", "best-OBJECTIVE.ini"}) {
    INFO(file);
    CHECK(table_row(optimize, std::string("`") + file + "`"));
  }
}

TEST_CASE("cli: docs/report-json.md lists every field of report.json, and no other") {
  Scratch s("readme_report");
  // One face and a shell (whose inputs name its faces).
  std::set<std::string> fields;
  const auto add_fields = [&](const std::string& flags, const std::string& dir) {
    field_paths(drape_report(flags + " --outputs json", s, dir), "", fields);
  };
  const std::string samples = std::string(PLYFIT_SOURCE_DIR) + "/samples/";
  add_fields(kOctantFlags, "face");
  add_fields("'" + samples + "sphere-8.ini'", "shell");
  // And a ply with a boundary (report.json's ply.boundary): a square loop on the plate, its
  // base path along a seed curve of a file (inputs.seed_curve_file), cut by a dart (darts).
  std::ofstream(s.file("square.csv")) << "30,10,0\n70,10,0\n70,50,0\n30,50,0\n";
  std::ofstream(s.file("line.csv")) << "30,30,0\n70,30,0\n";
  std::ofstream(s.file("dart.csv")) << "40,10,0\n45,25,0\n";
  add_fields("--mold builtin:plate --seed 50,30,0 --spacing 2 --seed-curve '" + s.file("line.csv") +
                 "' --boundary '" + s.file("square.csv") + "' --dart '" + s.file("dart.csv") + "'",
             "bounded");
  // And a ply split for its roll (pieces, splices): the sample on the cylinder sector.
  add_fields("'" + samples + "cylinder-spliced.ini'", "spliced");
  REQUIRE(fields.size() >= 100);
  const std::string doc = source_file("docs/report-json.md");
  std::set<std::string> documented;
  for (const auto& row : table_rows(doc))
    if (!row.empty() && row[0].size() > 2 && row[0].front() == '`' && row[0].back() == '`')
      documented.insert(row[0].substr(1, row[0].size() - 2));
  for (const auto& f : fields) {
    INFO("report.json field " << f);
    CHECK(documented.count(f) == 1);
  }
  for (const auto& d : documented) {
    INFO("documented field " << d << " is in no report");
    CHECK(fields.count(d) == 1);
  }
  // Every node status is described where the scan is (docs/method.md, "The scan").
  const std::string scan = md_section(source_file("docs/method.md"), "## The scan");
  const auto nodes = nlohmann::json::parse(slurp(s.file("face/report.json")))["nodes"];
  for (auto it = nodes.begin(); it != nodes.end(); ++it) {
    if (!it->is_number_integer() || it.key() == "with_angle") continue;
    if (it.key() == "mapped" || it.key() == "auxiliary") continue;  // statuses that go on
    INFO("status " << it.key());
    CHECK(scan.find("- `" + it.key() + "`:") != std::string::npos);
  }
}

TEST_CASE("cli: every link of the README and of docs/ leads to a file and heading that exist") {
  int links = 0;
  for (const auto& file : manual_files()) {
    const fs::path dir = fs::path(file).parent_path();
    for (const auto& target : link_targets(source_file(file))) {
      if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0) continue;
      INFO(file << ": link " << target);
      const auto hash = target.find('#');
      const std::string path = target.substr(0, hash);
      const std::string rel = path.empty() ? file : (dir / path).lexically_normal().string();
      CHECK(fs::exists(fs::path(PLYFIT_SOURCE_DIR) / rel));
      if (hash != std::string::npos) {
        const auto list = anchors(source_file(rel));
        CHECK(std::find(list.begin(), list.end(), target.substr(hash + 1)) != list.end());
      }
      ++links;
    }
  }
  CHECK(links >= 50);
}

TEST_CASE("cli: docs/errors.md documents every error and warning code, and no other") {
  const std::string doc = source_file("docs/errors.md");
  REQUIRE(!doc.empty());
  for (const auto& [heading, codes] : {std::pair{std::string("## Error codes"), kErrorCodes},
                                       std::pair{std::string("## Warning codes"), kWarningCodes}}) {
    const std::string section = md_section(doc, heading);
    INFO(heading);
    REQUIRE(!section.empty());
    const std::set<std::string> documented = documented_codes(section);
    for (const auto& code : codes) {
      INFO("code " << code << " is not in docs/errors.md");
      CHECK(documented.count(code) == 1);
    }
    const std::set<std::string> known(codes.begin(), codes.end());
    for (const auto& d : documented) {
      INFO("docs/errors.md documents " << d << ", which is no code");
      CHECK(known.count(d) == 1);
    }
  }
  CHECK(kErrorCodes.size() >= 50);
}
