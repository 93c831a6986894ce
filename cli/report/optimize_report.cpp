// What `plyfit optimize` prints and writes: the table on stdout, optimize.json and front.svg.

#include "report/optimize_report.hpp"

#include <plyfit/exporters/messages.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace plyfit::cli {

std::string note_of(const Evaluation& e) {
  return e.error ? exporters::describe(*e.error) : e.note;
}

namespace {

template <typename... Args>
std::string fmt(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  std::string s(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(s.data(), s.size(), format, args...);
  s.resize(static_cast<std::size_t>(std::max(n, 0)));
  return s;
}

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
  return {fmt("#%d", e.index),
          fmt("%.3f, %.3f, %.3f", e.seed.x(), e.seed.y(), e.seed.z()),
          fmt("%.3f", e.candidate.angle * kRadToDeg),
          fmt("%.3f", e.candidate.path * kRadToDeg),
          fmt("%.3f", f.energy),
          fmt("%.3f", f.max_shear_deg),
          fmt("%.2f", f.flat_area),
          fmt("%.2f", 100.0 * f.coverage),
          fmt("%.2f", 100.0 * f.cell_coverage),
          fmt("%llu", static_cast<unsigned long long>(f.mapped))};
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

int feasible_count(const OptimizeResult& r) {
  return static_cast<int>(std::count_if(r.evaluations.begin(), r.evaluations.end(),
                                        [](const Evaluation& e) { return e.feasible; }));
}

}  // namespace

std::string optimize_table(const DrapeJob& scene, const OptimizeResult& r, const OptimizeOptions& o,
                           double seconds, int jobs) {
  const Evaluation& s = r.evaluations.front();
  std::string out =
      fmt("plyfit optimize: %s: %d drapes (vary %s; refined for %s) in %.2f s on %d thread%s\n",
          scene.scene.c_str(), static_cast<int>(r.evaluations.size()) - 1, vary_text(o).c_str(),
          objectives_text(o).c_str(), seconds, jobs, jobs == 1 ? "" : "s");
  out += fmt("feasible: drape ok and coverage >= %.2f%% of the face", 100.0 * r.min_coverage);
  if (r.min_coverage_default)
    out += fmt(" (the best coverage, %.2f%%, at most 100%%, less %.2f%%) and at most %.2f%%",
               100.0 * r.best_coverage, 100.0 * kCoverageSlack, 100.0 * (1 + kCoverageSlack));
  out += fmt("; %d of %d drapes\n\n", feasible_count(r), static_cast<int>(r.evaluations.size()));
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
  out += fmt("\nPareto front over energy, max shear and flat area (%d drapes, by energy):\n",
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

namespace {

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `count` ticks over `span`.
double tick_step(double span, int count) {
  const double raw = span / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

}  // namespace

std::string optimize_svg(const DrapeJob& scene, const OptimizeResult& r) {
  // Three panels side by side (SVG user units).
  constexpr double kPanel = 300, kGap = 70, kLeft = 70, kTop = 50, kBottom = 95;
  constexpr int kTicks = 5;
  const double width = kLeft + 3 * kPanel + 2 * kGap + 30, height = kTop + kPanel + kBottom;
  const char* names[3] = {"energy (sum cos^2 gamma)", "max shear (deg)", "flat area (mm^2)"};
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  auto value = [](const Evaluation& e, int k) {
    return k == 0 ? e.figures.energy : k == 1 ? e.figures.max_shear_deg : e.figures.flat_area;
  };
  std::vector<const Evaluation*> shown;
  for (const auto& e : r.evaluations)
    if (e.feasible || e.index == 0) shown.push_back(&e);
  std::vector<bool> on_front(r.evaluations.size(), false);
  for (int i : r.front) on_front[static_cast<std::size_t>(i)] = true;
  std::string s =
      fmt("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
          "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"12\">\n",
          width, height, width, height);
  s += fmt("<rect width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", width, height);
  std::string title;
  for (char c : "plyfit optimize: " + scene.scene)
    title += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
  s +=
      fmt("<text x=\"%.0f\" y=\"24\" font-size=\"15\">%s: %d feasible drapes, Pareto front "
          "of %d</text>\n",
          kLeft, title.c_str(), feasible_count(r), static_cast<int>(r.front.size()));
  for (int p = 0; p < 3; ++p) {
    const int kx = pairs[p][0], ky = pairs[p][1];
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto* e : shown) {
      x0 = std::min(x0, value(*e, kx));
      x1 = std::max(x1, value(*e, kx));
      y0 = std::min(y0, value(*e, ky));
      y1 = std::max(y1, value(*e, ky));
    }
    if (shown.empty()) x0 = y0 = 0, x1 = y1 = 1;
    const double padx = std::max(0.05 * (x1 - x0), 1e-9 * std::max(1.0, std::abs(x1)));
    const double pady = std::max(0.05 * (y1 - y0), 1e-9 * std::max(1.0, std::abs(y1)));
    x0 -= padx, x1 += padx, y0 -= pady, y1 += pady;
    const double ox = kLeft + p * (kPanel + kGap);
    auto X = [&](double v) { return ox + kPanel * (v - x0) / (x1 - x0); };
    auto Y = [&](double v) { return kTop + kPanel * (1.0 - (v - y0) / (y1 - y0)); };
    const double sx = tick_step(x1 - x0, kTicks), sy = tick_step(y1 - y0, kTicks);
    for (double t = std::ceil(x0 / sx) * sx; t <= x1; t += sx) {
      s += fmt("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", X(t),
               kTop, X(t), kTop + kPanel);
      s += fmt("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", X(t),
               kTop + kPanel + 16, t);
    }
    for (double t = std::ceil(y0 / sy) * sy; t <= y1; t += sy) {
      s += fmt("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", ox,
               Y(t), ox + kPanel, Y(t));
      s += fmt("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", ox - 5, Y(t) + 4, t);
    }
    s +=
        fmt("<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
            "stroke=\"black\"/>\n",
            ox, kTop, kPanel, kPanel);
    s += fmt("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", ox + kPanel / 2,
             kTop + kPanel + 36, names[kx]);
    s +=
        fmt("<text transform=\"translate(%.1f %.1f) rotate(-90)\" "
            "text-anchor=\"middle\">%s</text>\n",
            ox - 45, kTop + kPanel / 2, names[ky]);
    // The feasible drapes, the front over them, the scene.
    for (const auto* e : shown)
      if (e->index != 0 && !on_front[static_cast<std::size_t>(e->index)])
        s += fmt("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2\" fill=\"#aaa\"/>\n", X(value(*e, kx)),
                 Y(value(*e, ky)));
    for (int i : r.front) {
      const Evaluation& e = r.evaluations[static_cast<std::size_t>(i)];
      s += fmt("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"#1f77b4\"/>\n", X(value(e, kx)),
               Y(value(e, ky)));
    }
    if (r.best[0] >= 0) {
      const Evaluation& e = r.evaluations[static_cast<std::size_t>(r.best[0])];
      s +=
          fmt("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"7\" fill=\"none\" stroke=\"#2ca02c\" "
              "stroke-width=\"2\"/>\n",
              X(value(e, kx)), Y(value(e, ky)));
    }
    const Evaluation& sc = r.evaluations.front();
    s += fmt("<rect x=\"%.1f\" y=\"%.1f\" width=\"8\" height=\"8\" fill=\"#d62728\"/>\n",
             X(value(sc, kx)) - 4, Y(value(sc, ky)) - 4);
  }
  const double ly = kTop + kPanel + 70;
  s +=
      fmt("<circle cx=\"%.0f\" cy=\"%.0f\" r=\"2\" fill=\"#aaa\"/><text x=\"%.0f\" "
          "y=\"%.0f\">feasible drape</text>\n",
          kLeft, ly, kLeft + 8, ly + 4);
  s +=
      fmt("<circle cx=\"%.0f\" cy=\"%.0f\" r=\"3.5\" fill=\"#1f77b4\"/><text x=\"%.0f\" "
          "y=\"%.0f\">Pareto front (energy, max shear, flat area)</text>\n",
          kLeft + 130, ly, kLeft + 138, ly + 4);
  s +=
      fmt("<circle cx=\"%.0f\" cy=\"%.0f\" r=\"7\" fill=\"none\" stroke=\"#2ca02c\" "
          "stroke-width=\"2\"/><text x=\"%.0f\" y=\"%.0f\">lowest energy</text>\n",
          kLeft + 430, ly, kLeft + 442, ly + 4);
  s +=
      fmt("<rect x=\"%.0f\" y=\"%.0f\" width=\"8\" height=\"8\" fill=\"#d62728\"/><text "
          "x=\"%.0f\" y=\"%.0f\">the scene as given</text>\n",
          kLeft + 560, ly - 4, kLeft + 574, ly + 4);
  s += "</svg>\n";
  return s;
}

}  // namespace plyfit::cli
