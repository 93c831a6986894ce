#pragma once
// Regression over the sample scenes (samples/*.ini): each is draped by the built plyfit and
// its report.json figures are compared with samples/golden/<scene>.json. Counts must match
// exactly; angles, areas, energies and the start's move to kGoldenRel relative; residuals
// are only bounded. PLYFIT_UPDATE_GOLDENS=1 rewrites the goldens instead (see
// scripts/update-goldens); every change of a golden figure is explained in its commit.
// Scenes on plyfit's own molds run in golden_test.cpp, scenes on the CAD corpus
// (../shared/cad) in golden_corpus_test.cpp.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace plyfit::test {

using nlohmann::json;
namespace fs = std::filesystem;

/// Relative agreement of the real-valued golden figures.
inline constexpr double kGoldenRel = 1e-9;
/// Bounds of the residuals: thread and base-path links keep their length, and the base path
/// its plane, to this fraction of the spacing; mapped points lie on the face to this fraction
/// of the face size.
inline constexpr double kLinkResidualRel = 1e-9;
inline constexpr double kSurfaceResidualRel = 1e-9;
/// Figures that are zero in exact arithmetic come out as round-off (a developable face's shear
/// energy ~1e-24, a start on the face moving ~1e-15): a relative test is meaningless there, so
/// these absolute floors are added to the tolerance: energy (a sum of cos^2) and the start's
/// move as a fraction of the face size.
inline constexpr double kEnergyRoundoff = 1e-18;
inline constexpr double kMoveRoundoffRel = 1e-12;

inline const std::vector<std::string> kExact = {
    "/status",        "/nodes/mapped",      "/nodes/auxiliary", "/nodes/outside",
    "/nodes/off_ply", "/nodes/shear_limit", "/nodes/failed",    "/area_mesh_points"};
inline const std::vector<std::string> kRelative = {"/flat_area",
                                                   "/surface_area",
                                                   "/coverage",
                                                   "/thread_angle/min",
                                                   "/thread_angle/max",
                                                   "/shear_energy",
                                                   "/flat_outline/area",
                                                   "/flat_outline/perimeter",
                                                   "/mold/face/area",
                                                   "/start/moved",
                                                   "/paper_metrics/gamma_min",
                                                   "/paper_metrics/gamma_max",
                                                   "/paper_metrics/energy"};

inline std::string samples_dir() {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples";
}

/// The folders of sample scenes under samples/: the scenes, and the plies (samples/plies).
inline const std::vector<std::string> kSceneFolders = {"", "plies"};

inline std::vector<fs::path> sample_scenes() {
  std::vector<fs::path> v;
  for (const auto& folder : kSceneFolders)
    for (const auto& e : fs::directory_iterator(samples_dir() + "/" + folder))
      if (e.path().extension() == ".ini") v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

/// A scene's name: its path under samples/ without the extension (`plies/plate-45`); its
/// golden is samples/golden/<name>.json.
inline std::string scene_name(const fs::path& scene) {
  return fs::relative(scene, samples_dir()).replace_extension().generic_string();
}

/// The figures of a ply with a boundary (compared to kGoldenRel too): the angle laid, the
/// region's area on the mold and the exact flat outline's area and perimeter.
inline const std::vector<std::string> kBoundaryRelative = {
    "/ply/laid_angle_deg", "/ply/boundary/area", "/flat_outline_exact/area",
    "/flat_outline_exact/perimeter"};
/// A 0 deg ply's laid angle comes out as round-off: this absolute floor (degrees) is added.
inline constexpr double kAngleRoundoffDeg = 1e-9;

/// The figures of each dart (darts.md), compared to kGoldenRel (areas) or exactly (counts,
/// whether it is a seam), and with darts the drapes made, whether the ply was laid and the
/// conflict nodes left (exactly).
inline std::vector<std::string> dart_figures(const json& report, bool exact) {
  std::vector<std::string> out;
  if (!report.contains("darts")) return out;
  static const std::vector<std::string> counts = {"links_cut", "nodes_cut_out", "seam"};
  static const std::vector<std::string> areas = {"removed_area", "opening_area"};
  if (exact) out = {"/darts/drapes", "/darts/laid", "/nodes/conflict"};
  for (std::size_t k = 0; k < report["darts"]["darts"].size(); ++k)
    for (const std::string& f : exact ? counts : areas)
      out.push_back("/darts/darts/" + std::to_string(k) + "/" + f);
  return out;
}

inline bool has_boundary(const json& report) {
  return !report.at("ply").at("boundary").is_null();
}

/// The figures of a ply split for the roll (compared to kGoldenRel too): each piece's area and
/// width, each seam's place; the golden's "pieces" holds their number (compared exactly).
inline std::vector<std::string> splice_relative(const json& report) {
  std::vector<std::string> out;
  if (!report.contains("pieces")) return out;
  for (std::size_t k = 0; k < report["pieces"].size(); ++k)
    for (const char* f : {"area", "width"}) out.push_back("/pieces/" + std::to_string(k) + "/" + f);
  for (std::size_t k = 0; k < report["splices"]["seams"].size(); ++k)
    out.push_back("/splices/seams/" + std::to_string(k) + "/x");
  return out;
}

/// The compared figures of a report, keyed by JSON pointer.
inline json golden_of(const json& report) {
  json g = json::object();
  for (const auto& p : kExact) g[p] = report.at(json::json_pointer(p));
  for (const auto& p : kRelative) g[p] = report.at(json::json_pointer(p));
  if (has_boundary(report))
    for (const auto& p : kBoundaryRelative) g[p] = report.at(json::json_pointer(p));
  if (report.contains("pieces")) g["pieces"] = report["pieces"].size();
  for (const auto& p : splice_relative(report)) g[p] = report.at(json::json_pointer(p));
  for (bool exact : {true, false})
    for (const auto& p : dart_figures(report, exact)) g[p] = report.at(json::json_pointer(p));
  return g;
}

inline json drape_report(const fs::path& scene, const Scratch& tmp) {
  const std::string out = tmp.file(scene_name(scene));
  const CliRun r =
      plyfit_run("drape '" + scene.string() + "' -o '" + out + "' --outputs json --quiet", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(slurp(out + "/report.json"));
}

/// True when the scene's mold is a file of the CAD corpus (a `mold =` path into shared/cad).
inline bool scene_uses_corpus(const fs::path& scene) {
  std::istringstream in(slurp(scene.string()));
  for (std::string line; std::getline(in, line);) {
    const auto eq = line.find('=');
    if (eq == std::string::npos || line.compare(0, 4, "mold") != 0) continue;
    if (line.find("shared/cad/", eq) != std::string::npos) return true;
  }
  return false;
}

/// The sample scenes on the corpus (corpus true) or on plyfit's own molds (false).
inline std::vector<fs::path> scenes_of(bool corpus) {
  std::vector<fs::path> v;
  for (const auto& s : sample_scenes())
    if (scene_uses_corpus(s) == corpus) v.push_back(s);
  return v;
}

/// Drapes every scene of `scenes` and compares its report with its golden (or rewrites the
/// golden when PLYFIT_UPDATE_GOLDENS is set).
inline void check_goldens(const std::vector<fs::path>& scenes) {
  Scratch tmp("goldens");
  const bool update = std::getenv("PLYFIT_UPDATE_GOLDENS") != nullptr;
  const std::string golden_dir = samples_dir() + "/golden";
  for (const auto& scene : scenes) {
    const std::string name = scene_name(scene);
    INFO("scene " << name);
    const json report = drape_report(scene, tmp);
    const std::string golden_path = golden_dir + "/" + name + ".json";
    if (update) {
      fs::create_directories(fs::path(golden_path).parent_path());
      json g = golden_of(report);
      g["scene"] = name + ".ini";
      spit(golden_path, g.dump(2) + "\n");
      continue;
    }
    REQUIRE(fs::exists(golden_path));
    const json golden = json::parse(slurp(golden_path));
    std::vector<std::string> exact = kExact;
    const auto dart_exact = dart_figures(report, true);
    exact.insert(exact.end(), dart_exact.begin(), dart_exact.end());
    for (const auto& p : exact) {
      INFO(p);
      REQUIRE(golden.contains(p));
      CHECK(report.at(json::json_pointer(p)) == golden.at(p));
    }
    const json& box = report["mold"]["face"]["bbox"];
    double size2 = 0.0;
    for (int k = 0; k < 3; ++k)
      size2 += std::pow(box["max"][k].get<double>() - box["min"][k].get<double>(), 2);
    const double size = std::sqrt(size2);
    std::vector<std::string> relative = kRelative;
    // A golden with the boundary's figures needs a report with them, and the other way round.
    CHECK(has_boundary(report) == golden.contains(kBoundaryRelative.front()));
    if (has_boundary(report))
      relative.insert(relative.end(), kBoundaryRelative.begin(), kBoundaryRelative.end());
    // A golden with pieces needs a report with as many, and the other way round.
    CHECK(report.contains("pieces") == golden.contains("pieces"));
    if (report.contains("pieces") && golden.contains("pieces")) {
      CHECK(report["pieces"].size() == golden["pieces"].get<std::size_t>());
      if (report["pieces"].size() != golden["pieces"].get<std::size_t>()) continue;
    }
    const auto spliced = splice_relative(report);
    relative.insert(relative.end(), spliced.begin(), spliced.end());
    const auto dart_relative = dart_figures(report, false);
    relative.insert(relative.end(), dart_relative.begin(), dart_relative.end());
    for (const auto& p : relative) {
      INFO(p);
      const double a = report.at(json::json_pointer(p)).get<double>();
      REQUIRE(golden.contains(p));
      const double g = golden.at(p).get<double>();
      const double floor = p == "/shear_energy" || p == "/paper_metrics/energy" ? kEnergyRoundoff
                           : p == "/start/moved"        ? kMoveRoundoffRel * size
                           : p == "/ply/laid_angle_deg" ? kAngleRoundoffDeg
                                                        : 0.0;
      CHECK(std::abs(a - g) <= kGoldenRel * std::abs(g) + floor);
    }
    CHECK(report["residual"]["edge_length_max_rel"].get<double>() <= kLinkResidualRel);
    CHECK(report["residual"]["base_plane_max_rel"].get<double>() <= kLinkResidualRel);
    CHECK(report["residual"]["surface_distance_max"].get<double>() <= kSurfaceResidualRel * size);
  }
}

}  // namespace plyfit::test
