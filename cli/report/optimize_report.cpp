// What `plyfit optimize` prints and writes: the table on stdout, optimize.json and front.svg.

#include "report/optimize_report.hpp"

#include "job/scene_file.hpp"
#include "report/text_format.hpp"

#include <plyfit/exporters/messages.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace plyfit::cli {

std::string note_of(const Evaluation& e) {
  if (e.error) return exporters::describe(*e.error);
  // A partial drape is not judged (judge() leaves its note empty): its warnings say why.
  if (e.note.empty() && e.status == "partial" && !e.warnings.empty())
    return "partial: " + exporters::messages(e.warnings);
  return e.note;
}

namespace {

std::string vary_text(const OptimizeOptions& o) {
  std::string s;
  for (const auto& [on, name] :
       {std::pair{o.vary_start, "start"}, {o.vary_angle, "angle"}, {o.vary_path, "path"}})
    if (on) {
      if (!s.empty()) s += ',';
      s += name;
    }
  return s;
}

std::string objectives_text(const OptimizeOptions& o) {
  std::string s;
  for (Objective ob : o.objectives) {
    if (!s.empty()) s += ',';
    s += to_string(ob);
  }
  return s;
}

/// Rows of text, columns padded: the first left-aligned, the others right-aligned.
std::string columns(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> w;
  for (const auto& r : rows) {
    w.resize(std::max(w.size(), r.size()), 0);
    for (std::size_t c = 0; c < r.size(); ++c) w[c] = std::max(w[c], r[c].size());
  }
  std::string out;
  for (const auto& r : rows) {
    std::string line;
    for (std::size_t c = 0; c < r.size(); ++c) {
      const std::string pad(w[c] - r[c].size(), ' ');
      line += (c ? "  " : "") + (c ? pad + r[c] : r[c] + pad);
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

std::vector<std::string> drape_cells(const Evaluation& e) {
  const Figures& f = e.figures;
  return {format("#%d", e.index),
          format("%.3f, %.3f, %.3f", e.seed.x(), e.seed.y(), e.seed.z()),
          format("%.3f", e.candidate.angle * kRadToDeg),
          format("%.3f", e.candidate.path * kRadToDeg),
          format("%.3f", f.energy),
          format("%.3f", f.max_shear_deg),
          format("%.2f", f.flat_area),
          format("%.2f", 100.0 * f.coverage),
          format("%.2f", 100.0 * f.cell_coverage),
          format("%llu", static_cast<unsigned long long>(f.mapped))};
}

const std::vector<std::string>& drape_header() {
  static const std::vector<std::string> h = {
      "drape",        "seed x, y, z (mm)", "angle (deg)", "path (deg)", "energy", "max shear (deg)",
      "flat area",  // mm^2
      "coverage (%)", "cells (%)",         "mapped"};
  return h;
}

bool refined(const OptimizeOptions& o, Objective ob) {
  return std::find(o.objectives.begin(), o.objectives.end(), ob) != o.objectives.end();
}

}  // namespace

int feasible_count(const OptimizeResult& r) {
  return static_cast<int>(std::count_if(r.evaluations.begin(), r.evaluations.end(),
                                        [](const Evaluation& e) { return e.feasible; }));
}

std::string optimize_table(const DrapeJob& scene, const OptimizeResult& r, const OptimizeOptions& o,
                           double seconds, int jobs) {
  const Evaluation& s = r.evaluations.front();
  std::string out =
      format("plyfit optimize: %s: %d drapes (vary %s; refined for %s) in %.2f s on %d thread%s\n",
             scene.scene.c_str(), static_cast<int>(r.evaluations.size()) - 1, vary_text(o).c_str(),
             objectives_text(o).c_str(), seconds, jobs, jobs == 1 ? "" : "s");
  out += format("feasible: drape ok and coverage >= %.2f%% of the face", 100.0 * r.min_coverage);
  if (r.min_coverage_default)
    out += format(" (the best coverage, %.2f%%, at most 100%%, less %.2f%%) and at most %.2f%%",
                  100.0 * r.best_coverage, 100.0 * kCoverageSlack, 100.0 * (1 + kCoverageSlack));
  out += format("; %d of %d drapes\n\n", feasible_count(r), static_cast<int>(r.evaluations.size()));
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> head = {""};
  head.insert(head.end(), drape_header().begin(), drape_header().end());
  rows.push_back(head);
  auto row = [&](const std::string& label, const Evaluation& e) {
    std::vector<std::string> line = {label};
    const auto cells = drape_cells(e);
    line.insert(line.end(), cells.begin(), cells.end());
    rows.push_back(line);
  };
  row(s.feasible ? "scene" : "scene (not feasible)", s);
  for (int k = 0; k < kObjectiveCount; ++k) {
    const auto ob = static_cast<Objective>(k);
    const std::string label = std::string("best ") + to_string(ob) + (refined(o, ob) ? " *" : "");
    if (r.best[k] >= 0)
      row(label, r.evaluations[static_cast<std::size_t>(r.best[k])]);
    else
      rows.push_back({label, "none feasible"});
  }
  out += columns(rows);
  out +=
      "* refined (the others: the best of the same drapes). angle, path: the ply's threads "
      "and the base path turned on the mold about the normal at the seed, counter-clockwise, "
      "from the scene's directions. "
      "coverage: the cut ply's share of the face; cells: the mapped cells' (report.json's "
      "coverage).\n";
  if (!s.feasible && !note_of(s).empty()) out += "scene: " + note_of(s) + "\n";
  out += format("\nPareto front over energy, max shear and flat area (%d drapes, by energy):\n",
                static_cast<int>(r.front.size()));
  rows.clear();
  rows.push_back(drape_header());
  for (int i : r.front) rows.push_back(drape_cells(r.evaluations[static_cast<std::size_t>(i)]));
  out += columns(rows);
  return out;
}

std::string optimize_json(const DrapeJob& scene, const OptimizeResult& r, const OptimizeOptions& o,
                          double seconds, int jobs) {
  using nlohmann::ordered_json;
  auto drape_json = [](const Evaluation& e) {
    const Figures& f = e.figures;
    ordered_json j;
    j["index"] = e.index;
    j["phase"] = e.phase;
    j["seed"] = {e.seed.x(), e.seed.y(), e.seed.z()};
    j["uv"] = {e.candidate.uv.x(), e.candidate.uv.y()};
    j["angle_deg"] = e.candidate.angle * kRadToDeg;
    j["path_deg"] = e.candidate.path * kRadToDeg;
    j["status"] = e.status;
    j["feasible"] = e.feasible;
    j["note"] = note_of(e);
    j["energy"] = f.energy;
    j["max_shear_deg"] = f.max_shear_deg;
    j["flat_area"] = f.flat_area;
    j["coverage"] = f.coverage;
    j["cell_coverage"] = f.cell_coverage;
    j["mapped"] = f.mapped;
    j["shear_limit"] = f.shear_limit;
    j["overlap"] = f.overlap;
    j["off_ply"] = f.off_ply;
    return j;
  };
  ordered_json j;
  j["scene"] = scene.scene;
  j["mold"] = scene.mold;
  j["face"] = scene.face;
  ordered_json search;
  search["vary"] = vary_text(o);
  search["objectives"] = ordered_json::array();
  for (Objective ob : o.objectives) search["objectives"].push_back(to_string(ob));
  search["evaluations"] = o.evaluations;
  search["min_coverage"] = r.min_coverage;
  search["min_coverage_from"] = r.min_coverage_default ? "best coverage" : "option";
  search["best_coverage"] = r.best_coverage;
  search["coverage_slack"] = kCoverageSlack;
  search["radius"] = r.radius ? ordered_json(*r.radius) : ordered_json(nullptr);
  search["angle_range_deg"] = r.angle_range * kRadToDeg;
  search["angle_period_deg"] = r.angle_period * kRadToDeg;
  search["path_range_deg"] = r.path_range * kRadToDeg;
  search["uv_box"] = {r.uv_lo.x(), r.uv_lo.y(), r.uv_hi.x(), r.uv_hi.y()};
  search["design"] = r.design;
  search["design_skipped"] = r.skipped;
  j["search"] = search;
  j["drapes"] = static_cast<int>(r.evaluations.size()) - 1;
  j["feasible"] = feasible_count(r);
  j["scene_drape"] = drape_json(r.evaluations.front());
  ordered_json best;
  for (int k = 0; k < kObjectiveCount; ++k) {
    const auto ob = static_cast<Objective>(k);
    if (r.best[k] < 0) {
      best[to_string(ob)] = nullptr;
      continue;
    }
    ordered_json b = drape_json(r.evaluations[static_cast<std::size_t>(r.best[k])]);
    b["refined"] = refined(o, ob);
    best[to_string(ob)] = b;
  }
  j["best"] = best;
  j["pareto_front"] = r.front;
  j["evaluations"] = ordered_json::array();
  for (const auto& e : r.evaluations) j["evaluations"].push_back(drape_json(e));
  j["run"] = {{"threads", jobs}, {"seconds", seconds}};
  return j.dump(2) + "\n";
}

std::string best_scene_ini(const DrapeJob& scene, const MoldSurface& face, const OptimizeResult& r,
                           Objective ob, const std::string& path) {
  const Evaluation& e = r.evaluations[static_cast<std::size_t>(r.best[static_cast<int>(ob)])];
  std::ostringstream ini;
  ini.precision(17);
  ini << "# plyfit optimize: the lowest " << to_string(ob) << " of " << path << " (drape #"
      << e.index << ": energy " << e.figures.energy << ", max shear " << e.figures.max_shear_deg
      << " deg, flat area " << e.figures.flat_area << " mm^2, coverage "
      << 100.0 * e.figures.coverage << "%; ply angle " << e.candidate.angle / kDegToRad
      << " deg from the scene's)\n";
  ini << dump_scene(candidate_job(scene, face, r, e.candidate));
  return ini.str();
}

}  // namespace plyfit::cli
