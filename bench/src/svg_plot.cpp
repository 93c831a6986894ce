// The time-against-error plot of the report: drape time per node against the measured
// link-length error, one polyline per face, each point labelled with its Newton tolerance.

#include <plyfit/exporters/svg_chart.hpp>

#include "tables.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace plyfit::bench {

namespace {
// Plot geometry (SVG user units).
constexpr double kWidth = 760, kHeight = 460;
constexpr double kLeft = 80, kRight = 170, kTop = 40, kBottom = 60;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
}  // namespace

std::string time_error_svg(const std::vector<TolerancePoint>& points, double default_tol) {
  std::map<std::string, std::vector<const TolerancePoint*>> series;
  std::vector<std::string> order;
  for (const auto& p : points) {
    if (!series.count(p.face)) order.push_back(p.face);
    series[p.face].push_back(&p);
  }
  // Axes: log10 of the error (x), time relative to the face's time at the default (y).
  auto rel_time = [&](const TolerancePoint& p) {
    for (const auto* q : series[p.face])
      if (q->tol == default_tol) return p.ms / q->ms;
    return 1.0;
  };
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : points) {
    const double x = std::log10(std::max(p.link_rel, 1e-17));
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, rel_time(p));
    y1 = std::max(y1, rel_time(p));
  }
  x0 = std::floor(x0);
  x1 = std::ceil(x1);
  if (x1 <= x0) x1 = x0 + 1;
  y0 = std::floor(y0 * 10) / 10;
  y1 = std::ceil(y1 * 10) / 10;
  if (y1 <= y0) y1 = y0 + 0.1;
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  auto X = [&](double e) { return kLeft + pw * (std::log10(std::max(e, 1e-17)) - x0) / (x1 - x0); };
  auto Y = [&](double t) { return kTop + ph * (1.0 - (t - y0) / (y1 - y0)); };
  std::string s = exporters::svg_chart_open(kWidth, kHeight);
  s += format(
      "<text x=\"%.0f\" y=\"22\" font-size=\"15\">Drape time against link-length error "
      "(Newton tolerance 1e-3 .. 1e-14 x d)</text>\n",
      kLeft);
  // Grid and ticks.
  for (int e = static_cast<int>(x0); e <= static_cast<int>(x1); ++e) {
    const double x = X(std::pow(10.0, e));
    s += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x,
                kTop, x, kTop + ph);
    s += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">1e%d</text>\n", x,
                kTop + ph + 18, e);
  }
  const int ny = static_cast<int>(std::round((y1 - y0) / 0.1));
  const int ystep = std::max(1, ny / 8);
  for (int k = 0; k <= ny; k += ystep) {
    const double t = y0 + 0.1 * k, y = Y(t);
    s += format("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", kLeft,
                y, kLeft + pw, y);
    s += format("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.1f</text>\n", kLeft - 6, y + 4,
                t);
  }
  s += format(
      "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
      "stroke=\"black\"/>\n",
      kLeft, kTop, pw, ph);
  s += format(
      "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">max link-length error / d "
      "(measured from the nodes)</text>\n",
      kLeft + pw / 2, kHeight - 15);
  s += format(
      "<text transform=\"translate(18 %.1f) rotate(-90)\" text-anchor=\"middle\">drape "
      "time / time at the default tolerance</text>\n",
      kTop + ph / 2);
  // Series.
  for (std::size_t k = 0; k < order.size(); ++k) {
    const char* col = kColours[k % 4];
    auto pts = series[order[k]];
    std::string poly;
    for (const auto* p : pts) poly += format("%.1f,%.1f ", X(p->link_rel), Y(rel_time(*p)));
    s += format("<polyline points=\"%s\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\"/>\n",
                poly.c_str(), col);
    for (std::size_t q = 0; q < pts.size(); ++q) {
      const TolerancePoint* p = pts[q];
      const double x = X(p->link_rel), y = Y(rel_time(*p));
      const bool def = p->tol == default_tol;
      s += format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%s\" fill=\"%s\"%s/>\n", x, y,
                  def ? "6" : "3.5", def ? "none" : col,
                  def ? format(" stroke=\"%s\" stroke-width=\"2\"", col).c_str() : "");
      // Tolerances below the rounding floor give the same net (same error): one label.
      if (q > 0 && pts[q - 1]->link_rel == p->link_rel) continue;
      std::size_t last = q;
      while (last + 1 < pts.size() && pts[last + 1]->link_rel == p->link_rel) ++last;
      const std::string label =
          last > q ? format("%.0e .. %.0e", p->tol, pts[last]->tol) : format("%.0e", p->tol);
      s += format("<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"%s\">%s</text>\n", x + 5,
                  y - 6 - 10.0 * k, col, label.c_str());
    }
    const double ly = kTop + 20 + 20.0 * k;
    s += format(
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
        "stroke-width=\"2\"/>\n",
        kLeft + pw + 12, ly, kLeft + pw + 32, ly, col);
    s += format("<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", kLeft + pw + 36, ly + 4,
                order[k].c_str());
  }
  s += format("<text x=\"%.1f\" y=\"%.1f\" font-size=\"11\">open circle: the default</text>\n",
              kLeft + pw + 12, kTop + 30 + 20.0 * static_cast<double>(order.size()));
  s += "</svg>\n";
  return s;
}

}  // namespace plyfit::bench
