// front.svg of plyfit optimize: three panels (energy - max shear, energy - flat area, max shear
// - flat area), each with its grid, the feasible drapes, the Pareto front, the lowest energy
// and the scene as given, then a legend.

#include <plyfit/exporters/svg_chart.hpp>

#include "report/optimize_report.hpp"
#include "report/text_format.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace plyfit::cli {

namespace {

// Layout in SVG user units: three panels side by side.
constexpr double kPanel = 300, kGap = 70, kLeft = 70, kTop = 50, kBottom = 95;
constexpr int kTicks = 5;
// Each axis extends its data range by this share on both sides, and by at least this much
// relative to its values (a range of one value still has a width).
constexpr double kMarginRel = 0.05, kMinMarginRel = 1e-9;

const char* const kFigureNames[3] = {"energy (sum cos^2 gamma)", "max shear (deg)",
                                     "flat area (mm^2)"};
const int kPanelFigures[3][2] = {{0, 1}, {0, 2}, {1, 2}};

double figure(const Evaluation& e, int k) {
  return k == 0 ? e.figures.energy : k == 1 ? e.figures.max_shear_deg : e.figures.flat_area;
}

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `count` ticks over `span`.
double tick_step(double span, int count) {
  const double raw = span / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

/// A panel's two figures, their ranges (with margins) and where it stands.
struct Panel {
  int kx = 0, ky = 0;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  double ox = 0;  ///< left edge
  double X(double v) const { return ox + kPanel * (v - x0) / (x1 - x0); }
  double Y(double v) const { return kTop + kPanel * (1.0 - (v - y0) / (y1 - y0)); }
};

Panel panel(int p, const std::vector<const Evaluation*>& shown) {
  Panel a;
  a.kx = kPanelFigures[p][0];
  a.ky = kPanelFigures[p][1];
  a.ox = kLeft + p * (kPanel + kGap);
  if (!shown.empty()) {
    const double inf = std::numeric_limits<double>::infinity();
    a.x0 = a.y0 = inf;
    a.x1 = a.y1 = -inf;
    for (const auto* e : shown) {
      a.x0 = std::min(a.x0, figure(*e, a.kx));
      a.x1 = std::max(a.x1, figure(*e, a.kx));
      a.y0 = std::min(a.y0, figure(*e, a.ky));
      a.y1 = std::max(a.y1, figure(*e, a.ky));
    }
  }
  const double padx =
      std::max(kMarginRel * (a.x1 - a.x0), kMinMarginRel * std::max(1.0, std::abs(a.x1)));
  const double pady =
      std::max(kMarginRel * (a.y1 - a.y0), kMinMarginRel * std::max(1.0, std::abs(a.y1)));
  a.x0 -= padx, a.x1 += padx, a.y0 -= pady, a.y1 += pady;
  return a;
}

// The grid lines and tick labels, the frame and the axis names.
std::string grid(const Panel& a) {
  std::string s;
  const double sx = tick_step(a.x1 - a.x0, kTicks), sy = tick_step(a.y1 - a.y0, kTicks);
  for (double t = std::ceil(a.x0 / sx) * sx; t <= a.x1; t += sx) {
    s += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", a.X(t),
                kTop, a.X(t), kTop + kPanel);
    s += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", a.X(t),
                kTop + kPanel + 16, t);
  }
  for (double t = std::ceil(a.y0 / sy) * sy; t <= a.y1; t += sy) {
    s += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", a.ox,
                a.Y(t), a.ox + kPanel, a.Y(t));
    s += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", a.ox - 5, a.Y(t) + 4,
                t);
  }
  s += format(
      "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
      "stroke=\"black\"/>\n",
      a.ox, kTop, kPanel, kPanel);
  s += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", a.ox + kPanel / 2,
              kTop + kPanel + 36, kFigureNames[a.kx]);
  s += format(
      "<text transform=\"translate(%.1f %.1f) rotate(-90)\" "
      "text-anchor=\"middle\">%s</text>\n",
      a.ox - 45, kTop + kPanel / 2, kFigureNames[a.ky]);
  return s;
}

// The feasible drapes, the front over them, the lowest energy and the scene.
std::string points(const Panel& a, const OptimizeResult& r,
                   const std::vector<const Evaluation*>& shown) {
  std::vector<bool> on_front(r.evaluations.size(), false);
  for (int i : r.front) on_front[static_cast<std::size_t>(i)] = true;
  auto at = [&](const Evaluation& e) {
    return std::pair{a.X(figure(e, a.kx)), a.Y(figure(e, a.ky))};
  };
  std::string s;
  for (const auto* e : shown)
    if (e->index != 0 && !on_front[static_cast<std::size_t>(e->index)])
      s += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2\" fill=\"#aaa\"/>\n", at(*e).first,
                  at(*e).second);
  for (int i : r.front) {
    const auto [x, y] = at(r.evaluations[static_cast<std::size_t>(i)]);
    s += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"#1f77b4\"/>\n", x, y);
  }
  if (r.best[0] >= 0) {
    const auto [x, y] = at(r.evaluations[static_cast<std::size_t>(r.best[0])]);
    s += format(
        "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"7\" fill=\"none\" stroke=\"#2ca02c\" "
        "stroke-width=\"2\"/>\n",
        x, y);
  }
  const auto [x, y] = at(r.evaluations.front());
  s += format("<rect x=\"%.1f\" y=\"%.1f\" width=\"8\" height=\"8\" fill=\"#d62728\"/>\n", x - 4,
              y - 4);
  return s;
}

std::string legend() {
  const double ly = kTop + kPanel + 70;
  std::string s;
  s += format(
      "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"2\" fill=\"#aaa\"/><text x=\"%.0f\" "
      "y=\"%.0f\">feasible drape</text>\n",
      kLeft, ly, kLeft + 8, ly + 4);
  s += format(
      "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"3.5\" fill=\"#1f77b4\"/><text x=\"%.0f\" "
      "y=\"%.0f\">Pareto front (energy, max shear, flat area)</text>\n",
      kLeft + 130, ly, kLeft + 138, ly + 4);
  s += format(
      "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"7\" fill=\"none\" stroke=\"#2ca02c\" "
      "stroke-width=\"2\"/><text x=\"%.0f\" y=\"%.0f\">lowest energy</text>\n",
      kLeft + 430, ly, kLeft + 442, ly + 4);
  s += format(
      "<rect x=\"%.0f\" y=\"%.0f\" width=\"8\" height=\"8\" fill=\"#d62728\"/><text "
      "x=\"%.0f\" y=\"%.0f\">the scene as given</text>\n",
      kLeft + 560, ly - 4, kLeft + 574, ly + 4);
  return s;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
  return out;
}

}  // namespace

std::string optimize_svg(const DrapeJob& scene, const OptimizeResult& r) {
  const double width = kLeft + 3 * kPanel + 2 * kGap + 30, height = kTop + kPanel + kBottom;
  std::vector<const Evaluation*> shown;
  for (const auto& e : r.evaluations)
    if (e.feasible || e.index == 0) shown.push_back(&e);
  std::string s = exporters::svg_chart_open(width, height);
  s += format(
      "<text x=\"%.0f\" y=\"24\" font-size=\"15\">%s: %d feasible drapes, Pareto front "
      "of %d</text>\n",
      kLeft, escaped("plyfit optimize: " + scene.scene).c_str(), feasible_count(r),
      static_cast<int>(r.front.size()));
  for (int p = 0; p < 3; ++p) {
    const Panel a = panel(p, shown);
    s += grid(a) + points(a, r, shown);
  }
  s += legend();
  s += "</svg>\n";
  return s;
}

}  // namespace plyfit::cli
