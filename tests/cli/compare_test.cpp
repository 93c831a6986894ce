// plyfit compare: the paper's Table 2 and 4 figures per scene, the best marks (checked
// against the goldens of the sample scenes), ties, formats and refusing different molds.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <cmath>
#include <sstream>

using namespace plyfit::test;
using nlohmann::json;

namespace {

std::string sample(const std::string& name) {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples/" + name;
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        row.push_back(cell), cell.clear();
      else
        cell += c;
    }
    row.push_back(cell);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("cli: compare marks the best sphere-octant scene per criterion, as the goldens say") {
  Scratch tmp("compare_octant");
  const std::vector<std::string> names = {"sphere-octant-a", "sphere-octant-b", "sphere-octant-c"};
  std::string args;
  for (const auto& n : names) args += " '" + sample(n + ".ini") + "'";
  const CliRun r = plyfit_run("compare --csv" + args, tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = parse_csv(r.out);
  REQUIRE(rows.size() == 4);
  const std::vector<std::string> header = {
      "scene",  "status",       "area",        "flat_area", "gamma_min_deg", "gamma_max_deg",
      "energy", "coverage_pct", "shear_limit", "best",      "error"};
  CHECK(rows[0] == header);
  // Each criterion: the golden figure, and whether larger is better.
  struct Crit {
    std::string column, pointer;
    double scale;
    bool larger;
  };
  const double deg = 180.0 / 3.14159265358979323846;
  const std::vector<Crit> crits = {{"area", "/area_mesh_points", 1, false},
                                   {"flat_area", "/flat_outline/area", 1, false},
                                   {"gamma_min_deg", "/thread_angle/min", deg, true},
                                   {"gamma_max_deg", "/thread_angle/max", deg, false},
                                   {"energy", "/shear_energy", 1, false},
                                   {"coverage_pct", "/coverage", 100, true},
                                   {"shear_limit", "/nodes/shear_limit", 1, false}};
  std::vector<json> goldens;
  for (const auto& n : names)
    goldens.push_back(json::parse(slurp(sample("golden/" + n + ".json"))));
  for (std::size_t c = 0; c < crits.size(); ++c) {
    INFO(crits[c].column);
    double best = crits[c].larger ? -1e300 : 1e300;
    for (const auto& g : goldens) {
      const double v = g[crits[c].pointer].get<double>() * crits[c].scale;
      best = crits[c].larger ? std::max(best, v) : std::min(best, v);
    }
    for (std::size_t k = 0; k < names.size(); ++k) {
      const auto& row = rows[k + 1];
      CHECK(row[0] == names[k]);
      CHECK(row[1] == "ok");
      const double v = goldens[k][crits[c].pointer].get<double>() * crits[c].scale;
      CHECK(std::abs(std::stod(row[2 + c]) - v) <= 1e-9 * std::abs(v));
      const bool marked =
          (";" + row[9] + ";").find(";" + crits[c].column + ";") != std::string::npos;
      CHECK(marked == (std::abs(v - best) <= 1e-9 * std::abs(best)));
    }
  }
  // The text table: a header, three rows and the legend; marks shown as '*'.
  const CliRun t = plyfit_run("compare" + args, tmp);
  REQUIRE(t.code == 0);
  CHECK(lines(t.out) == 5);
  CHECK(t.out.find(" *") != std::string::npos);
  // Markdown: header, separator, rows, best in bold.
  const CliRun m = plyfit_run("compare --markdown" + args, tmp);
  REQUIRE(m.code == 0);
  CHECK(m.out.rfind("| scene | area (mesh points) |", 0) == 0);
  CHECK(m.out.find("\n|---|---:|") != std::string::npos);
  CHECK(m.out.find("| sphere-octant-b | **658** |") != std::string::npos);
  // No output files unless asked for.
  CHECK(std::filesystem::is_empty(tmp.path / ".") == false);
  const CliRun o = plyfit_run("compare -o '" + tmp.file("outs") + "'" + args, tmp);
  REQUIRE(o.code == 0);
  CHECK(std::filesystem::exists(tmp.file("outs/sphere-octant-b/report.json")));
}

TEST_CASE("cli: compare marks every tied scene") {
  Scratch tmp("compare_ties");
  const std::string a = sample("sphere-octant-a.ini");
  const CliRun r = plyfit_run("compare --csv '" + a + "' '" + a + "'", tmp);
  REQUIRE(r.code == 0);
  const auto rows = parse_csv(r.out);
  REQUIRE(rows.size() == 3);
  CHECK(rows[1][0] == "sphere-octant-a");
  CHECK(rows[2][0] == "sphere-octant-a-2");
  const std::string all =
      "area;flat_area;gamma_min_deg;gamma_max_deg;energy;coverage_pct;shear_limit";
  CHECK(rows[1][9] == all);
  CHECK(rows[2][9] == all);
}

TEST_CASE("cli: compare refuses scenes on different molds unless --force") {
  Scratch tmp("compare_molds");
  const std::string a = sample("sphere-octant-a.ini"), r3 = sample("revolution-third-a.ini");
  CliRun r = plyfit_run("compare '" + a + "' '" + r3 + "'", tmp);
  CHECK(r.code == 2);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find("scenes on different molds") != std::string::npos);
  CHECK(r.err.find("revolution-third.step") != std::string::npos);
  CHECK(r.out.empty());
  r = plyfit_run("compare --force '" + a + "' '" + r3 + "'", tmp);
  CHECK(r.code == 0);
  CHECK(r.err.find("warning: comparing scenes on different molds") != std::string::npos);
  CHECK(lines(r.out) == 4);
  // The same mold through another path is the same mold.
  spit(tmp.file("a.ini"), slurp(a));
  std::string text = slurp(a);
  text.replace(text.find("molds/"), 6, std::string(PLYFIT_SOURCE_DIR) + "/samples/./molds/");
  spit(tmp.file("a.ini"), text);
  r = plyfit_run("compare '" + a + "' '" + tmp.file("a.ini") + "'", tmp);
  CHECK(r.code == 0);
  // A scene that fails to drape is reported; the others are still compared; exit 1.
  spit(tmp.file("gone.ini"), "mold = gone.step\n" + text.substr(text.find("[ply]")));
  r = plyfit_run("compare --force '" + a + "' '" + tmp.file("gone.ini") + "'", tmp);
  CHECK(r.code == 1);
  CHECK(r.out.find("gone: error: ") != std::string::npos);
  // Usage errors.
  CHECK(plyfit_run("compare", tmp).code == 2);
  CHECK(plyfit_run("compare --csv --markdown '" + a + "'", tmp).code == 2);
  CHECK(plyfit_run("compare '" + tmp.file("none.ini") + "'", tmp).code == 1);
}
