// --min-width / scene key min-width: the cut outline (kernel/include/plyfit/kernel/
// outline_cleanup.hpp) in report.json and flat.dxf, the exact outline beside it.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/drape_report.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

using namespace plyfit::test;
using nlohmann::json;

namespace {

// tests/kernel/outline_quality_test.cpp's hemisphere drape with a strip of cloth 0.18 d wide
// between the face edge and a row stopped by overlap (one sweep).
const std::string kStrip =
    "--mold builtin:hemisphere --spacing 0.10973817914653033 --start2d 0,0 "
    "--base2d 0.99834856016847195,-0.057446953004828792 "
    "--sweep2d 0.057446953004828792,0.99834856016847195 "
    "--start3d 0.23447179449406841,0.13044943651281971,0.54521187752363209 "
    "--base-normal -0.99580287622940966,-0.064639367141352835,0.064794937370141345 "
    "--sweep3d -0.43134763568172607,-0.55503042602519637,0.71125272820430974";

// report.json (and flat.dxf) of a drape with `flags` into the scratch folder's `out`.
json report(const std::string& flags, const std::string& out, const Scratch& tmp) {
  return drape_report(flags + " --outputs json,dxf --quiet", tmp, out);
}

// The number of LWPOLYLINEs on layer OUTLINE or HOLES of a DXF, and their vertices.
std::pair<int, int> cut_polylines(const std::string& dxf) {
  std::istringstream in(dxf);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) {
    while (!l.empty() && (l.back() == '\r' || l.back() == ' ')) l.pop_back();
    lines.push_back(l);
  }
  int polys = 0, verts = 0;
  for (std::size_t k = 0; k + 1 < lines.size(); k += 2) {
    if (lines[k].find_first_not_of(' ') == std::string::npos) continue;
    if (std::stoi(lines[k]) != 0 || lines[k + 1] != "LWPOLYLINE") continue;
    std::string layer;
    int count = 0;
    for (std::size_t j = k + 2; j + 1 < lines.size() && std::stoi(lines[j]) != 0; j += 2) {
      if (std::stoi(lines[j]) == 8) layer = lines[j + 1];
      if (std::stoi(lines[j]) == 90) count = std::stoi(lines[j + 1]);
    }
    if (layer == "OUTLINE" || layer == "HOLES") {
      ++polys;
      verts += count;
    }
  }
  return {polys, verts};
}

int vertices(const json& outline) {
  int n = 0;
  for (const auto& l : outline["loops"]) n += static_cast<int>(l["points"].size());
  return n;
}

}  // namespace

TEST_CASE("cli: --min-width cuts the strip off the outline, 0 keeps the exact one") {
  Scratch tmp("min_width");
  const double d = 0.10973817914653033;
  const json def = report(kStrip, "def", tmp);
  const json& cut = def["flat_outline"];
  const json& exact = def["flat_outline_exact"];
  CHECK(cut["min_width"].get<double>() == 0.5 * d);
  CHECK(cut["slivers"].get<int>() >= 1);
  CHECK(cut["removed_area"].get<double>() > 0.0);
  // The strip's two ends lie beyond the seam (cut off by the overlap row and the face's edge):
  // left out before the clean-up.
  CHECK(cut["laid_twice_area"].get<double>() > 0.0);
  CHECK(std::abs(cut["area"].get<double>() -
                 (exact["area"].get<double>() - cut["laid_twice_area"].get<double>() -
                  cut["removed_area"].get<double>() + cut["added_area"].get<double>())) <
        1e-9 * exact["area"].get<double>());
  CHECK(cut["loops"] != exact["loops"]);
  // flat.dxf's contours are the cut outline's loops.
  const auto [polys, verts] = cut_polylines(slurp(tmp.file("def") + "/flat.dxf"));
  CHECK(polys == static_cast<int>(cut["loops"].size()));
  CHECK(verts == vertices(cut));

  // Off, the exact outline's loops less those beyond the seam, as they are.
  const json off = report(kStrip + " --min-width 0", "off", tmp);
  const json& off_cut = off["flat_outline"];
  for (const auto& l : off_cut["loops"])
    CHECK(std::find(exact["loops"].begin(), exact["loops"].end(), l) != exact["loops"].end());
  CHECK(off_cut["area"].get<double>() ==
        Approx(exact["area"].get<double>() - off_cut["laid_twice_area"].get<double>())
            .epsilon(1e-12));
  CHECK(off_cut["slivers"].get<int>() == 0);
  CHECK(off["flat_outline_exact"] == exact);
  const auto [polys0, verts0] = cut_polylines(slurp(tmp.file("off") + "/flat.dxf"));
  CHECK(polys0 == static_cast<int>(off_cut["loops"].size()));
  CHECK(verts0 == vertices(off_cut));

  // The scene key, and --dump-scene echoes it.
  const std::string scene = tmp.file("strip.ini");
  {
    const CliRun dump = plyfit_run("drape " + kStrip + " --min-width 0.02 --dump-scene", tmp);
    REQUIRE(dump.code == 0);
    CHECK(dump.out.find("min-width = 0.02") != std::string::npos);
    std::ofstream(scene) << dump.out;
  }
  const json sc = report("'" + scene + "'", "scene", tmp);
  CHECK(sc["flat_outline"]["min_width"].get<double>() == 0.02);
}

TEST_CASE("cli: a bad --min-width is a one-line error naming it") {
  Scratch tmp("min_width_bad");
  for (const auto& [v, code] : std::vector<std::pair<std::string, std::string>>{
           {"-1", "out_of_range"}, {"abc", "not_a_number"}, {"nan", "not_finite"}}) {
    const CliRun r =
        plyfit_run("drape " + kStrip + " --min-width " + v + " -o '" + tmp.file("o") + "'", tmp);
    INFO(v << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(error_code(r) == code);
    CHECK(r.err.rfind("plyfit: error: --min-width: ", 0) == 0);
    CHECK_FALSE(std::filesystem::exists(tmp.file("o")));
  }
}
