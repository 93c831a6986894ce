// The paper's three graphical tools (§7, Figs. 11, 13-15) as self-contained SVG files (no
// external references, no scripts):
//   flat.svg   the plane development in ply coordinates (x right = weft, y up = warp): the
//              mapped cells coloured by shear, the thread grid, the mapped links in bold, the
//              staircase outline of the mapped cells, the exact outline, the base path as
//              dots, the start point P_s and the sweep arrows, shear-warning cells, a legend
//   drape.svg  the 3D fitting in an orthographic view along ExportOptions::view (towards the
//              viewer; default isometric (1, 1, 1), Z up on the page): the mapped cells
//              coloured by shear and shaded by their slope to the view, the threads, the base
//              path, the face boundary mapped to 3D; painter's algorithm (every cell, segment
//              and node sorted by depth, far first)
//   shear.svg  the thread-angle distribution as a height field over the plane development
//              (paper Fig. 15): height = gamma from 0 to pi, drawn in an oblique parallel
//              projection (x and height true, the ply's y axis receding at 40 degrees,
//              foreshortened to 0.75) with depth sorting
// Every mapped regular node is one element of class "node" in flat.svg and drape.svg; in
// shear.svg every mapped regular node with a thread angle is. Base-path nodes are class
// "path-node". Cell shear: the largest |90 deg - gamma| over the cell's corners (net_util).
// Coordinates are written with two decimals (pixels); equal inputs give equal bytes.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include "net_util.hpp"
#include "plugins.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

namespace plyfit::exporters {

namespace {

using detail::Box2;
using detail::fixed_text;
using detail::kPi;
using detail::kRadToDeg;
using detail::xml_escape;

constexpr double kPlotSize = 760.0;  // px: the longer side of the drawing
constexpr double kMargin = 40.0;     // px around the drawing
constexpr double kLegendWidth = 190.0;
constexpr double kLegendHeight = 520.0;
constexpr int kMaxGridLines = 400;     // thread grid lines per direction drawn in flat.svg
constexpr double kMinGridPitch = 3.0;  // px: a denser grid is left out
constexpr double kMaxTicks = 6.0;      // intervals of the shear colour scale
// A view direction within this angle (radians) of Z looks down Z: Y is up on the page then.
constexpr double kViewAlongZ = 1e-6;
// flat.svg is drawn in millimetres (1 user unit = 1 mm, printable 1:1); its annotation keeps
// the size it has in the pixel pictures: one CSS pixel is 1/96 inch.
constexpr double kMmPerPx = 25.4 / 96.0;
// The title block (px): baselines of the first title line and the first subtitle line below
// the last title line, line pitches, the depth below the last line, font sizes, and the
// widest average character of the DejaVu Sans/Verdana text (in em) used to wrap lines.
constexpr double kTitleBaseline = 28.0, kSubBelowTitle = 19.0, kTitlePitch = 21.0, kSubPitch = 16.0,
                 kTitleDepth = 9.0, kTitleEm = 17.0, kSubEm = 12.0, kCharEm = 0.62;
// The scale bar under flat.svg's drawing: at most this fraction of the drawing's width, and
// its room (px) below the drawing.
constexpr double kScaleBarRel = 0.5, kScaleBarRoom = 46.0;

std::string px(double v) {
  return fixed_text(v, 2);
}

// Maps drawing coordinates (y up) to the picture's user units (y down). Pixel pictures fit
// the box into kPlotSize; flat.svg draws it at 1 user unit per model unit (mm). Margins,
// legend and title sizes are in user units (`unit` user units per pixel).
struct Frame {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Ones();
  double scale = 1.0;
  double unit = 1.0;  // user units per px of annotation
  double left = kMargin, top = kMargin;
  double width = 1.0, height = 1.0;  // plot area, user units
  double bottom = 0.0;               // room below the plot area (the scale bar)
  static Frame fit(Box2 box, double fixed_scale = 0.0, double unit = 1.0) {
    if (box.empty()) {
      box.add(Vec2::Zero());
      box.add(Vec2::Ones());
    }
    Frame f;
    f.unit = unit;
    f.left = f.top = kMargin * unit;
    Vec2 s = box.size();
    const double ext = std::max(s.x(), s.y());
    const double pad = ext > 0 ? 0.0 : 1.0;
    f.lo = box.lo - Vec2::Constant(pad);
    f.hi = box.hi + Vec2::Constant(pad);
    s = f.hi - f.lo;
    f.scale = fixed_scale > 0 ? fixed_scale : kPlotSize / std::max(s.x(), s.y());
    f.width = s.x() * f.scale;
    f.height = s.y() * f.scale;
    return f;
  }
  Vec2 map(const Vec2& p) const {
    return {left + (p.x() - lo.x()) * scale, top + (hi.y() - p.y()) * scale};
  }
  double canvas_width() const { return left + width + (kMargin + kLegendWidth) * unit; }
  double canvas_height() const {
    return std::max(top + height + bottom + kMargin * unit, top + (kLegendHeight + kMargin) * unit);
  }
};

// Greedy word wrap to lines of at most `width` px at font size `em` (px); a word longer than
// a line gets a line of its own, never cut.
std::vector<std::string> wrap(const std::string& s, double width, double em) {
  const auto max_chars =
      static_cast<std::size_t>(std::max(10.0, std::floor(width / (kCharEm * em))));
  std::vector<std::string> lines;
  std::string line, word;
  std::size_t line_len = 0;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::size_t n = detail::utf8_decode(word).size();
    if (line_len > 0 && line_len + 1 + n > max_chars) {
      lines.push_back(line);
      line.clear();
      line_len = 0;
    }
    if (line_len > 0) {
      line += ' ';
      ++line_len;
    }
    line += word;
    line_len += n;
    word.clear();
  };
  for (const char c : s) {
    if (c == ' ')
      flush_word();
    else
      word += c;
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string text(double x, double y, const std::string& s, const std::string& cls,
                 const std::string& extra = "");

// The title and the subtitle, wrapped to `width` px, in px coordinates from the top-left
// corner of the picture; `height` is the room they take (px).
struct TitleBlock {
  std::string svg;
  double height = 0.0;
};
TitleBlock title_block(const std::string& title, const std::string& sub, double width) {
  TitleBlock b;
  b.svg = "<g id=\"title\">\n";
  double y = kTitleBaseline;
  bool first = true;
  for (const auto& l : wrap(title, width, kTitleEm)) {
    if (!first) y += kTitlePitch;
    b.svg += text(kMargin, y, l, "title");
    first = false;
  }
  first = true;
  for (const auto& l : wrap(sub, width, kSubEm)) {
    y += first ? kSubBelowTitle : kSubPitch;
    b.svg += text(kMargin, y, l, "sub");
    first = false;
  }
  b.svg += "</g>\n";
  b.height = y + kTitleDepth;
  return b;
}

std::string pt(const Vec2& p) {
  return px(p.x()) + "," + px(p.y());
}

std::string points_attr(const std::vector<Vec2>& pts) {
  std::string s;
  for (const Vec2& p : pts) {
    if (!s.empty()) s += ' ';
    s += pt(p);
  }
  return s;
}

// A closed path of loops (for fill-rule evenodd).
std::string loops_path(const std::vector<std::vector<Vec2>>& loops) {
  std::string d;
  for (const auto& l : loops) {
    for (std::size_t k = 0; k < l.size(); ++k) {
      d += k == 0 ? 'M' : 'L';
      d += pt(l[k]);
    }
    if (!l.empty()) d += "Z";
  }
  return d;
}

// The shear colour scale: its top (radians) and the step of its ticks (degrees), a round
// step with at most kMaxTicks intervals.
struct ShearScale {
  double top = 0.0;
  double step_deg = 5.0;
};
ShearScale shear_scale(const DrapeResult& r) {
  double top = 0.0;
  for (const DrapeNode& n : r.nodes) top = std::max(top, detail::node_shear(n));
  const double m = top * kRadToDeg;
  ShearScale s;
  for (const double step : {1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0}) {
    s.step_deg = step;
    const double t = std::max(step, std::ceil(m / step) * step);
    s.top = t / kRadToDeg;
    if (t / step <= kMaxTicks) break;
  }
  return s;
}

std::string cell_fill(double shear, double top) {
  return shear < 0 ? detail::no_shear_colour().hex() : detail::shear_colour(shear / top).hex();
}

// The svg element: `w` x `h` user units, in px (pixel pictures) or in mm (flat.svg, 1:1).
std::string svg_open(double w, double h, const std::string& title, bool mm = false) {
  const std::string u = mm ? "mm" : "";
  std::string o;
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(w) + u +
       "\" height=\"" + px(h) + u + "\" viewBox=\"0 0 " + px(w) + " " + px(h) + "\">\n";
  o += "<title>" + xml_escape(title) + "</title>\n";
  o += "<style>\n"
       "text{font-family:DejaVu Sans,Verdana,Arial,sans-serif;fill:#222}\n"
       ".title{font-size:17px;font-weight:bold}.sub{font-size:12px}.small{font-size:11px}\n"
       ".node{fill:#1a1a1a}.path-node{fill:#000}\n"
       ".halo{paint-order:stroke;stroke:#ffffff;stroke-width:3px;stroke-linejoin:round}\n"
       "</style>\n";
  o +=
      "<rect x=\"0\" y=\"0\" width=\"" + px(w) + "\" height=\"" + px(h) + "\" fill=\"#ffffff\"/>\n";
  return o;
}

std::string text(double x, double y, const std::string& s, const std::string& cls,
                 const std::string& extra) {
  return "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" class=\"" + cls + "\"" + extra + ">" +
         xml_escape(s) + "</text>\n";
}

std::string arrow(const Vec2& a, const Vec2& b, const std::string& colour, double width) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0)) return "";
  const Vec2 u = d / len, n(-u.y(), u.x());
  const double head = std::min(12.0, 0.35 * len);
  const Vec2 base = b - head * u;
  return "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(base.x()) +
         "\" y2=\"" + px(base.y()) + "\" stroke=\"" + colour + "\" stroke-width=\"" + px(width) +
         "\"/>\n<polygon points=\"" +
         points_attr({b, base + 0.4 * head * n, base - 0.4 * head * n}) + "\" fill=\"" + colour +
         "\"/>\n";
}

// The legend: the shear colour bar from 0 to `top`, the warning level, and symbol entries.
std::string legend(double x, double y, const ShearScale& scale, double warn,
                   const std::vector<std::pair<std::string, std::string>>& entries,
                   double* end_y = nullptr) {
  std::string o = "<g id=\"legend\">\n";
  const double top = scale.top;
  o += text(x, y, "shear |90\u00b0 \u2212 \u03b3|", "sub");
  const double bar_w = 22.0, bar_h = 220.0, y0 = y + 14.0;
  o += "<defs><linearGradient id=\"shear-scale\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n";
  constexpr int kStops = 16;
  for (int k = 0; k <= kStops; ++k) {
    const double t = static_cast<double>(k) / kStops;
    o += "<stop offset=\"" + fixed_text(t, 4) + "\" stop-color=\"" + detail::shear_colour(t).hex() +
         "\"/>\n";
  }
  o += "</linearGradient></defs>\n";
  o += "<rect x=\"" + px(x) + "\" y=\"" + px(y0) + "\" width=\"" + px(bar_w) + "\" height=\"" +
       px(bar_h) + "\" fill=\"url(#shear-scale)\" stroke=\"#333\" stroke-width=\"0.8\"/>\n";
  const double top_deg = top * kRadToDeg;
  const int ticks = static_cast<int>(std::lround(top_deg / scale.step_deg));
  for (int k = 0; k <= ticks; ++k) {
    const double v = scale.step_deg * k;
    const double yy = y0 + bar_h * (1.0 - v / top_deg);
    o += "<line x1=\"" + px(x + bar_w) + "\" y1=\"" + px(yy) + "\" x2=\"" + px(x + bar_w + 5) +
         "\" y2=\"" + px(yy) + "\" stroke=\"#333\"/>\n";
    o += text(x + bar_w + 8, yy + 4, fixed_text(v, 0) + "\u00b0", "small");
  }
  if (warn <= top) {
    const double yy = y0 + bar_h * (1.0 - warn / top);
    o += "<line x1=\"" + px(x - 4) + "\" y1=\"" + px(yy) + "\" x2=\"" + px(x + bar_w + 4) +
         "\" y2=\"" + px(yy) + "\" stroke=\"#e8112d\" stroke-width=\"2\"/>\n";
    o += text(x + bar_w + 46, yy + 4, "warn", "small", " fill=\"#e8112d\"");
  }
  double yy = y0 + bar_h + 26.0;
  o += "<rect x=\"" + px(x) + "\" y=\"" + px(yy - 9) + "\" width=\"14\" height=\"10\" fill=\"" +
       detail::no_shear_colour().hex() + "\"/>\n";
  o += text(x + 20, yy, "no thread angle", "small");
  for (const auto& [symbol, label] : entries) {
    yy += 18.0;
    std::string s = symbol;
    // Symbols are drawn in a 24 x 12 box at (x, yy - 9): placeholders X and Y.
    for (const auto& [key, v] : {std::pair{"{X}", x},
                                 {"{Y}", yy - 9},
                                 {"{XM}", x + 12},
                                 {"{YM}", yy - 3},
                                 {"{X2}", x + 24}}) {
      for (std::size_t at = s.find(key); at != std::string::npos; at = s.find(key))
        s.replace(at, std::string(key).size(), px(v));
    }
    o += s + "\n";
    o += text(x + 30, yy, label, "small");
  }
  if (end_y) *end_y = yy;
  o += "</g>\n";
  return o;
}

std::string sym_line(const std::string& colour, double w, const std::string& dash = "") {
  return "<line x1=\"{X}\" y1=\"{YM}\" x2=\"{X2}\" y2=\"{YM}\" stroke=\"" + colour +
         "\" stroke-width=\"" + px(w) + "\"" +
         (dash.empty() ? "" : " stroke-dasharray=\"" + dash + "\"") + "/>";
}

std::string shear_summary(const ExportContext& ctx) {
  const DrapeMetrics& m = ctx.result.metrics;
  const double shear_max = m.shear_max * kRadToDeg;
  return "max shear " + fixed_text(shear_max, 2) + "\u00b0, \u03b3 " +
         fixed_text(m.gamma_min * kRadToDeg, 2) + "\u00b0 \u2026 " +
         fixed_text(m.gamma_max * kRadToDeg, 2) + "\u00b0";
}

std::string source_line(const ExportContext& ctx) {
  const std::string& material =
      ctx.options.material_label.empty() ? ctx.run.material : ctx.options.material_label;
  return ctx.run.ply_name + " (" + material + ") on " + detail::mold_label(ctx.run.mold) + ", " +
         detail::faces_label(ctx.run.faces);
}

// ---------------------------------------------------------------------------------------
// flat.svg

// A round length for the scale bar: 1, 2 or 5 times a power of ten, at most `max_len`.
double scale_bar_length(double max_len) {
  if (!(max_len > 0)) return 0.0;
  const double p = std::pow(10.0, std::floor(std::log10(max_len)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= max_len) return m * p;
  return p;
}

// Annotation drawn in px at a point of a picture whose user units are `unit` per px.
std::string at_px(const Vec2& p, double unit, const std::string& svg) {
  return "<g transform=\"translate(" + px(p.x()) + " " + px(p.y()) + ") scale(" +
         fixed_text(unit, 6) + ")\">\n" + svg + "</g>\n";
}

std::string flat_svg(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  const auto cells = detail::mapped_cells(r);
  const ShearScale scale = shear_scale(r);
  const double top = scale.top;
  const double warn = ctx.options.warn_shear;
  const double u = kMmPerPx;  // user units (mm) per px of annotation

  Box2 box;
  if (ctx.flat)
    for (const auto& l : ctx.flat->outline)
      for (const Vec2& q : l.points) box.add(q);
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) box.add(n.ply);
  box.add(spec.start);
  const double ext = box.empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  const double arrow_len = 0.15 * std::max(ext, spec.d_weft);
  for (const Vec2& w : spec.sweeps) box.add(spec.start + arrow_len * w.normalized());
  // Room for labels of the start and arrows.
  Box2 padded = box;
  padded.add(box.lo - Vec2::Constant(0.04 * ext));
  padded.add(box.hi + Vec2::Constant(0.04 * ext));
  // 1:1: one user unit is one millimetre of the ply.
  Frame f = Frame::fit(padded, 1.0, u);
  f.bottom = kScaleBarRoom * u;
  const TitleBlock tb = title_block(
      "Plane development (ply coordinates, mm; 1:1 at 100 %)",
      source_line(ctx) + "; " + std::to_string(r.metrics.nodes.mapped) +
          " mapped nodes, outline area " + fixed_text(ctx.flat ? ctx.flat->area : 0.0, 2) +
          " mm\u00b2, " + shear_summary(ctx),
      f.canvas_width() / u - 2 * kMargin);
  f.top = tb.height * u + kMargin * u * 0.5;
  auto P = [&](const Vec2& p) { return f.map(p); };
  const double d = std::min(spec.d_weft, spec.d_warp);  // the thread spacing, user units

  std::string o = svg_open(f.canvas_width(), f.canvas_height(), "plyfit plane development", true);
  o += at_px(Vec2::Zero(), u, tb.svg);

  // The thread grid of the ply.
  const Box2 view{f.lo, f.hi};
  const double gx0 = std::ceil(view.lo.x() / spec.d_weft),
               gx1 = std::floor(view.hi.x() / spec.d_weft);
  const double gy0 = std::ceil(view.lo.y() / spec.d_warp),
               gy1 = std::floor(view.hi.y() / spec.d_warp);
  if (d >= kMinGridPitch * u && gx1 - gx0 < kMaxGridLines && gy1 - gy0 < kMaxGridLines) {
    std::string g;
    for (double i = gx0; i <= gx1; ++i) {
      const double x = i * spec.d_weft;
      g += "M" + pt(P({x, view.lo.y()})) + "L" + pt(P({x, view.hi.y()}));
    }
    for (double j = gy0; j <= gy1; ++j) {
      const double y = j * spec.d_warp;
      g += "M" + pt(P({view.lo.x(), y})) + "L" + pt(P({view.hi.x(), y}));
    }
    o += "<path id=\"grid\" d=\"" + g + "\" stroke=\"#dddddd\" stroke-width=\"" + px(0.6 * u) +
         "\" fill=\"none\"/>\n";
  }

  o += "<g id=\"cells\" stroke=\"none\">\n";
  for (const auto& c : cells) {
    std::vector<Vec2> pts;
    for (const std::uint32_t k : c.nodes) pts.push_back(P(r.nodes[k].ply));
    o += "<polygon class=\"cell\" points=\"" + points_attr(pts) + "\" fill=\"" +
         cell_fill(c.shear, top) + "\"/>\n";
  }
  o += "</g>\n";

  // Mapped links in bold (the paper's bold segments).
  {
    std::string g;
    for (const DrapeLink& l : r.links())
      g += "M" + pt(P(r.nodes[l.a].ply)) + "L" + pt(P(r.nodes[l.b].ply));
    const double w = std::clamp(0.12 * d, 0.8 * u, 2.5 * u);
    o += "<path id=\"links\" d=\"" + g + "\" stroke=\"#1a1a1a\" stroke-width=\"" + px(w) +
         "\" stroke-linecap=\"round\" fill=\"none\"/>\n";
  }
  auto loops_of = [&](const std::vector<OutlineLoop>& ls) {
    std::vector<std::vector<Vec2>> out;
    for (const auto& l : ls) {
      std::vector<Vec2> q;
      for (const Vec2& p : l.points) q.push_back(P(p));
      out.push_back(std::move(q));
    }
    return out;
  };
  if (ctx.flat) {
    o += "<path id=\"staircase\" d=\"" + loops_path(loops_of(ctx.flat->staircase)) +
         "\" stroke=\"#000000\" stroke-width=\"" + px(2.6 * u) +
         "\" fill=\"none\" stroke-linejoin=\"round\"/>\n";
    o += "<path id=\"outline\" d=\"" + loops_path(loops_of(ctx.flat->outline)) +
         "\" stroke=\"#e8112d\" stroke-width=\"" + px(1.8 * u) +
         "\" fill=\"none\" fill-rule=\"evenodd\" stroke-linejoin=\"round\"/>\n";
  }
  o += "<g id=\"shear-warn\" fill=\"none\" stroke=\"#ff00cc\" stroke-width=\"" + px(1.6 * u) +
       "\">\n";
  for (const auto& c : cells) {
    if (!(c.shear > warn)) continue;
    std::vector<Vec2> pts;
    for (const std::uint32_t k : c.nodes) pts.push_back(P(r.nodes[k].ply));
    o += "<polygon class=\"shear-warn\" points=\"" + points_attr(pts) + "\"/>\n";
  }
  o += "</g>\n";

  const double node_r = std::clamp(0.1 * d, 0.6 * u, 2.4 * u);
  o += "<g id=\"nodes\">\n";
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    const Vec2 q = P(n.ply);
    o += "<circle class=\"node\" cx=\"" + px(q.x()) + "\" cy=\"" + px(q.y()) + "\" r=\"" +
         px(node_r) + "\"/>\n";
  }
  o += "</g>\n<g id=\"base-path\">\n";
  const double path_r = std::clamp(0.22 * d, 1.8 * u, 4.0 * u);
  for (const std::uint32_t k : r.base_path) {
    const Vec2 q = P(r.nodes[k].ply);
    o += "<circle class=\"path-node\" cx=\"" + px(q.x()) + "\" cy=\"" + px(q.y()) + "\" r=\"" +
         px(path_r) + "\"/>\n";
  }
  o += "</g>\n<g id=\"start\">\n";
  const Vec2 s = P(spec.start);
  for (std::size_t k = 0; k < spec.sweeps.size(); ++k) {
    const Vec2 tip = P(spec.start + arrow_len * spec.sweeps[k].normalized());
    o += at_px(s, u, arrow(Vec2::Zero(), (tip - s) / u, "#1f5fd6", 2.4));
    o += at_px(tip, u,
               text(6, -4, "sweep " + std::to_string(k + 1), "sub halo", " fill=\"#1f5fd6\""));
  }
  o += at_px(s, u,
             "<circle cx=\"0\" cy=\"0\" r=\"6\" fill=\"#ffffff\" stroke=\"#1f5fd6\" "
             "stroke-width=\"2.4\"/>\n" +
                 text(8, 16, "P", "title halo", " fill=\"#1f5fd6\"") +
                 text(19, 20, "s", "sub halo", " fill=\"#1f5fd6\""));
  o += "</g>\n";

  // The scale bar: a round length in millimetres, to check the print is 1:1.
  {
    const double len = scale_bar_length(kScaleBarRel * f.width);
    const Vec2 a(f.left, f.top + f.height + 0.5 * f.bottom);
    const double tick = 6.0 * u;
    o += "<g id=\"scale-bar\" data-length-mm=\"" + fixed_text(len, 6) + "\">\n";
    o += "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(a.x() + len) +
         "\" y2=\"" + px(a.y()) + "\" stroke=\"#000000\" stroke-width=\"" + px(1.6 * u) + "\"/>\n";
    for (const double x : {a.x(), a.x() + len})
      o += "<line x1=\"" + px(x) + "\" y1=\"" + px(a.y() - tick) + "\" x2=\"" + px(x) + "\" y2=\"" +
           px(a.y() + tick) + "\" stroke=\"#000000\" stroke-width=\"" + px(1.2 * u) + "\"/>\n";
    o += at_px(Vec2(a.x() + len, a.y()), u, text(8, 4, fixed_text(len, 6) + " mm", "small"));
    o += "</g>\n";
  }

  const double lx = f.left + f.width + kMargin * u;
  double legend_end = 0.0;
  std::string lg = legend(0, 10, scale, warn,
                          {{"<rect x=\"{X}\" y=\"{Y}\" width=\"24\" height=\"12\" fill=\"none\" "
                            "stroke=\"#ff00cc\" stroke-width=\"1.6\"/>",
                            "shear > " + fixed_text(warn * kRadToDeg, 1) + "\u00b0"},
                           {sym_line("#1a1a1a", 2.0), "mapped threads"},
                           {sym_line("#000000", 2.6), "mapped cells' edge"},
                           {sym_line("#e8112d", 1.8), "exact outline"},
                           {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"3\" fill=\"#000\"/>", "base path"},
                           {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"5\" fill=\"#fff\" "
                            "stroke=\"#1f5fd6\" stroke-width=\"2\"/>",
                            "start P\u209b, sweeps"},
                           {sym_line("#dddddd", 1.0), "ply threads"}},
                          &legend_end);
  // Ply axes.
  const double ax = 20, ay = legend_end + 70;
  lg += arrow({ax, ay}, {ax + 40, ay}, "#444", 1.4);
  lg += arrow({ax, ay}, {ax, ay - 40}, "#444", 1.4);
  lg += text(ax + 44, ay + 4, "x weft", "small");
  lg += text(ax - 8, ay - 46, "y warp (0\u00b0)", "small");
  o += at_px(Vec2(lx, f.top), u, lg);
  o += "</svg>\n";
  return o;
}

// ---------------------------------------------------------------------------------------
// Depth-sorted primitives (drape.svg, shear.svg)

struct Prim {
  double depth;  // larger = nearer the viewer
  std::string svg;
};

std::string draw_sorted(std::vector<Prim>& prims) {
  std::stable_sort(prims.begin(), prims.end(),
                   [](const Prim& a, const Prim& b) { return a.depth < b.depth; });
  std::string o;
  for (const Prim& p : prims) o += p.svg;
  return o;
}

// ---------------------------------------------------------------------------------------
// drape.svg

struct Camera {
  Vec3 right, up, towards;  // towards the viewer
  static Camera from(const Vec3& view) {
    Camera c;
    c.towards = view.norm() > 0 ? Vec3(view.normalized()) : Vec3(1, 1, 1).normalized();
    Vec3 world_up = Vec3::UnitZ();
    if (world_up.cross(c.towards).norm() < kViewAlongZ) world_up = Vec3::UnitY();
    c.right = world_up.cross(c.towards).normalized();
    c.up = c.towards.cross(c.right);
    return c;
  }
  Vec2 project(const Vec3& p) const { return {p.dot(right), p.dot(up)}; }
  double depth(const Vec3& p) const { return p.dot(towards); }
};

std::string drape_svg(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const MoldSurface& surface = ctx.surface;
  const Camera cam = Camera::from(ctx.options.view);
  const ShearScale scale = shear_scale(r);
  const double top = scale.top;
  const double warn = ctx.options.warn_shear;
  const double d = std::min(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp);

  // The free boundary in 3D (the kernel's: seams of closed faces, collapsed pole edges and
  // the edges a shell's faces share are no boundary): each segment split into pieces.
  constexpr int kBoundaryPieces = 48;
  std::vector<std::pair<Vec3, Vec3>> boundary;
  for (const auto& loop : surface.boundary()) {
    const std::size_t n = loop.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      if (loop.kinds[k] != BoundaryLoop::kEdge) continue;
      const SurfaceLocation& a = loop.points[k];
      const SurfaceLocation& b = loop.points[(k + 1) % n];
      const int pieces = n > 64 ? 1 : kBoundaryPieces;
      Vec3 prev = surface.eval1(a).p;
      for (int m = 1; m <= pieces; ++m) {
        const Vec3 q =
            surface.eval1(a.with_uv(a.uv + (b.uv - a.uv) * (static_cast<double>(m) / pieces))).p;
        boundary.emplace_back(prev, q);
        prev = q;
      }
    }
  }

  Box2 box;
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) box.add(cam.project(n.point));
  for (const auto& [a, b] : boundary) {
    box.add(cam.project(a));
    box.add(cam.project(b));
  }
  const double ext = box.empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  Box2 padded = box;
  padded.add(box.lo - Vec2::Constant(0.03 * ext));
  padded.add(box.hi + Vec2::Constant(0.03 * ext));
  Frame f = Frame::fit(padded);
  const Vec3 view_dir = ctx.options.view;
  const TitleBlock tb =
      title_block("3D fitting (orthographic, view (" + fixed_text(view_dir.x(), 3) + ", " +
                      fixed_text(view_dir.y(), 3) + ", " + fixed_text(view_dir.z(), 3) + "))",
                  source_line(ctx) + "; " + std::to_string(r.metrics.nodes.mapped) +
                      " mapped nodes, " + shear_summary(ctx),
                  f.canvas_width() - 2 * kMargin);
  f.top = tb.height + kMargin * 0.5;
  auto P = [&](const Vec3& p) { return f.map(cam.project(p)); };
  const double bias = 0.5 * d;  // segments and nodes are drawn over the cells they border

  std::vector<Prim> prims;
  for (const auto& c : detail::mapped_cells(r)) {
    std::vector<Vec2> pts;
    Vec3 centre = Vec3::Zero(), normal = Vec3::Zero();
    for (std::size_t k = 0; k < c.nodes.size(); ++k) {
      const Vec3& p = r.nodes[c.nodes[k]].point;
      const Vec3& q = r.nodes[c.nodes[(k + 1) % c.nodes.size()]].point;
      pts.push_back(P(p));
      centre += p;
      normal += p.cross(q);  // Newell's normal
    }
    centre /= static_cast<double>(c.nodes.size());
    const double facing = normal.norm() > 0 ? std::abs(normal.normalized().dot(cam.towards)) : 1.0;
    const detail::Rgb base =
        c.shear < 0 ? detail::no_shear_colour() : detail::shear_colour(c.shear / top);
    const std::string fill = base.shaded(0.55 + 0.45 * facing).hex();
    prims.push_back({cam.depth(centre), "<polygon class=\"cell\" points=\"" + points_attr(pts) +
                                            "\" fill=\"" + fill + "\" stroke=\"" + fill +
                                            "\" stroke-width=\"0.3\"/>\n"});
  }
  auto segment = [&](const Vec3& a, const Vec3& b, const std::string& style) {
    const Vec2 p = P(a), q = P(b);
    return Prim{cam.depth(0.5 * (a + b)) + bias,
                "<line x1=\"" + px(p.x()) + "\" y1=\"" + px(p.y()) + "\" x2=\"" + px(q.x()) +
                    "\" y2=\"" + px(q.y()) + "\" " + style + "/>\n"};
  };
  const std::string thread_style = "stroke=\"#262626\" stroke-width=\"0.7\"";
  const std::string path_style = "stroke=\"#1f5fd6\" stroke-width=\"2.2\"";
  for (const DrapeLink& l : r.links())
    prims.push_back(segment(r.nodes[l.a].point, r.nodes[l.b].point,
                            l.kind == LinkKind::kBase ? path_style : thread_style));
  // The base path's own thread links are drawn as the path too.
  for (std::size_t k = 1; k < r.base_path.size(); ++k)
    prims.push_back(
        segment(r.nodes[r.base_path[k - 1]].point, r.nodes[r.base_path[k]].point, path_style));
  for (const auto& [a, b] : boundary)
    prims.push_back(
        segment(a, b, "stroke=\"#000000\" stroke-width=\"1.6\" stroke-linecap=\"round\""));
  const double node_r = std::clamp(0.06 * d * f.scale, 0.5, 2.0);
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    const Vec2 q = P(n.point);
    prims.push_back({cam.depth(n.point) + 1.2 * bias, "<circle class=\"node\" cx=\"" + px(q.x()) +
                                                          "\" cy=\"" + px(q.y()) + "\" r=\"" +
                                                          px(node_r) + "\"/>\n"});
  }
  for (const std::uint32_t k : r.base_path) {
    const Vec2 q = P(r.nodes[k].point);
    prims.push_back({cam.depth(r.nodes[k].point) + 1.3 * bias,
                     "<circle class=\"path-node\" cx=\"" + px(q.x()) + "\" cy=\"" + px(q.y()) +
                         "\" r=\"" + px(std::max(1.6, 2 * node_r)) + "\" fill=\"#1f5fd6\"/>\n"});
  }

  std::string o = svg_open(f.canvas_width(), f.canvas_height(), "plyfit 3D fitting");
  o += tb.svg;
  o += "<g id=\"scene\">\n" + draw_sorted(prims) + "</g>\n";
  // Start point.
  {
    const Vec2 s = P(r.start_point);
    o += "<circle cx=\"" + px(s.x()) + "\" cy=\"" + px(s.y()) +
         "\" r=\"5\" fill=\"#ffffff\" stroke=\"#1f5fd6\" stroke-width=\"2.2\"/>\n";
    o += text(s.x() + 8, s.y() - 8, "P", "title halo", " fill=\"#1f5fd6\"");
    o += text(s.x() + 19, s.y() - 4, "s", "sub halo", " fill=\"#1f5fd6\"");
  }
  const double lx = f.left + f.width + kMargin;
  double legend_end = 0.0;
  o += legend(lx, f.top + 10, scale, warn,
              {{sym_line("#262626", 1.0), "threads"},
               {sym_line("#1f5fd6", 2.2), "base path"},
               {sym_line("#000000", 1.6), "face boundary"},
               {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"5\" fill=\"#fff\" stroke=\"#1f5fd6\" "
                "stroke-width=\"2\"/>",
                "start P\u209b"}},
              &legend_end);
  // Axis triad.
  const Vec2 origin(lx + 50, legend_end + 70);
  for (const auto& [axis, name] :
       {std::pair{Vec3::UnitX(), "X"}, {Vec3::UnitY(), "Y"}, {Vec3::UnitZ(), "Z"}}) {
    const Vec2 q = cam.project(axis);
    const Vec2 tip = origin + 36.0 * Vec2(q.x(), -q.y());
    if ((tip - origin).norm() > 4) o += arrow(origin, tip, "#444", 1.4);
    o += text(tip.x() + 3 * (q.x() >= 0 ? 1 : -3), tip.y() + (q.y() >= 0 ? -3 : 12), name, "small");
  }
  o += "</svg>\n";
  return o;
}

// ---------------------------------------------------------------------------------------
// shear.svg

constexpr double kObliqueAngle = 40.0;  // degrees: the receding y axis on the page
constexpr double kObliqueScale = 0.75;  // the receding y axis is foreshortened to this
constexpr double kHeightRel = 0.45;     // height of pi relative to the plane development's size

std::string shear_svg(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const ShearScale scale = shear_scale(r);
  const double top = scale.top;
  const double warn = ctx.options.warn_shear;

  Box2 plane;
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) plane.add(n.ply);
  if (ctx.flat)
    for (const auto& l : ctx.flat->outline)
      for (const Vec2& q : l.points) plane.add(q);
  if (plane.empty()) plane.add(Vec2::Zero());
  const double ext = std::max({plane.size().x(), plane.size().y(), ctx.problem.ply.d_weft});
  const double hscale = kHeightRel * ext / kPi;  // mm of height per radian
  const double ca = kObliqueScale * std::cos(kObliqueAngle / kRadToDeg);
  const double sa = kObliqueScale * std::sin(kObliqueAngle / kRadToDeg);
  // (x, y, gamma) -> page (y up); projector direction q = (ca, -1, sa) (x, y, height).
  auto proj = [&](const Vec2& p, double gamma) {
    return Vec2(p.x() + ca * p.y(), hscale * gamma + sa * p.y());
  };
  auto depth = [&](const Vec2& p, double gamma) {
    return ca * p.x() - p.y() + sa * hscale * gamma;
  };

  Box2 box;
  for (const double g : {0.0, kPi})
    for (const Vec2& c :
         {plane.lo, plane.hi, Vec2(plane.lo.x(), plane.hi.y()), Vec2(plane.hi.x(), plane.lo.y())})
      box.add(proj(c, g));
  Box2 padded = box;
  padded.add(box.lo - Vec2::Constant(0.05 * ext));
  padded.add(box.hi + Vec2::Constant(0.05 * ext));
  Frame f = Frame::fit(padded);
  const TitleBlock tb = title_block(
      "Thread-angle distribution (height \u03b3 from 0\u00b0 to 180\u00b0 over the plane "
      "development)",
      source_line(ctx) + "; " + shear_summary(ctx), f.canvas_width() - 2 * kMargin);
  f.top = tb.height + kMargin * 0.5;
  auto P = [&](const Vec2& p, double gamma) { return f.map(proj(p, gamma)); };

  std::string o = svg_open(f.canvas_width(), f.canvas_height(), "plyfit thread-angle distribution");
  o += tb.svg;

  // Under everything: the plane development on the floor, the frame, the pi/2 reference.
  o += "<g id=\"floor\">\n";
  if (ctx.flat) {
    std::vector<std::vector<Vec2>> loops;
    for (const auto& l : ctx.flat->outline) {
      std::vector<Vec2> q;
      for (const Vec2& p : l.points) q.push_back(P(p, 0.0));
      loops.push_back(std::move(q));
    }
    o += "<path d=\"" + loops_path(loops) +
         "\" fill=\"#ececec\" fill-rule=\"evenodd\" stroke=\"#e8112d\" stroke-width=\"1.2\"/>\n";
  }
  const std::vector<Vec2> corners = {
      plane.lo, {plane.hi.x(), plane.lo.y()}, plane.hi, {plane.lo.x(), plane.hi.y()}};
  for (const double g : {0.0, kPi / 2}) {
    std::vector<Vec2> q;
    for (const Vec2& c : corners) q.push_back(P(c, g));
    o += "<polygon points=\"" + points_attr(q) +
         "\" fill=\"none\" stroke=\"#999\" stroke-width=\"0.8\"" +
         (g > 0 ? " stroke-dasharray=\"5,4\"" : "") + "/>\n";
  }
  for (const Vec2& c : corners) {
    const Vec2 a = P(c, 0.0), b = P(c, kPi / 2);
    o += "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(b.x()) + "\" y2=\"" +
         px(b.y()) + "\" stroke=\"#bbb\" stroke-width=\"0.8\" stroke-dasharray=\"2,3\"/>\n";
  }
  // The vertical axis at the back-left corner, 0 .. pi.
  const Vec2 axis_foot(plane.lo.x(), plane.hi.y());
  {
    const Vec2 a = P(axis_foot, 0.0), b = P(axis_foot, kPi);
    o += "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(b.x()) + "\" y2=\"" +
         px(b.y()) + "\" stroke=\"#333\" stroke-width=\"1.2\"/>\n";
    const char* names[] = {"0\u00b0", "45\u00b0", "90\u00b0", "135\u00b0", "180\u00b0"};
    for (int k = 0; k <= 4; ++k) {
      const Vec2 t = P(axis_foot, kPi * k / 4.0);
      o += "<line x1=\"" + px(t.x() - 6) + "\" y1=\"" + px(t.y()) + "\" x2=\"" + px(t.x()) +
           "\" y2=\"" + px(t.y()) + "\" stroke=\"#333\" stroke-width=\"1.2\"/>\n";
      o += text(t.x() - 10, t.y() + 4, names[k], "sub", " text-anchor=\"end\"");
    }
    o += text(b.x() + 6, b.y() - 6, "\u03b3", "title");
  }
  o += "</g>\n";

  // The height field: cells of regular nodes with a thread angle (a quad, or the triangle of
  // three corners), coloured by shear.
  std::set<std::pair<std::int32_t, std::int32_t>> cells;  // (j, i)
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only() || !n.has(DrapeNode::kHasAngle)) continue;
    for (int a = -1; a <= 0; ++a)
      for (int b = -1; b <= 0; ++b) cells.insert({n.id.j + b, n.id.i + a});
  }
  std::vector<Prim> prims;
  for (const auto& [j, i] : cells) {
    std::vector<const DrapeNode*> ring;
    for (const auto& [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
      const DrapeNode* n = r.find(NodeId::regular(i + a, j + b));
      if (n && n->mapped() && n->has(DrapeNode::kHasAngle)) ring.push_back(n);
    }
    if (ring.size() < 3) continue;
    std::vector<Vec2> pts;
    double shear = 0.0, dsum = 0.0;
    for (const DrapeNode* n : ring) {
      pts.push_back(P(n->ply, n->thread_angle));
      shear = std::max(shear, detail::node_shear(*n));
      dsum += depth(n->ply, n->thread_angle);
    }
    const std::string fill = detail::shear_colour(shear / top).hex();
    prims.push_back(
        {dsum / static_cast<double>(ring.size()),
         "<polygon class=\"cell\" points=\"" + points_attr(pts) + "\" fill=\"" + fill +
             "\" stroke=\"#1a1a1a\" stroke-width=\"0.35\" stroke-linejoin=\"round\"/>\n"});
  }
  const double d = std::min(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp);
  const double node_r = std::clamp(0.06 * d * f.scale, 0.5, 1.6);
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only() || !n.has(DrapeNode::kHasAngle)) continue;
    const Vec2 q = P(n.ply, n.thread_angle);
    prims.push_back({depth(n.ply, n.thread_angle) + 0.5 * d,
                     "<circle class=\"node\" cx=\"" + px(q.x()) + "\" cy=\"" + px(q.y()) +
                         "\" r=\"" + px(node_r) + "\"/>\n"});
  }
  o += "<g id=\"field\">\n" + draw_sorted(prims) + "</g>\n";

  const double lx = f.left + f.width + kMargin;
  o += legend(lx, f.top + 10, scale, warn,
              {{"<rect x=\"{X}\" y=\"{Y}\" width=\"24\" height=\"12\" fill=\"#ececec\" "
                "stroke=\"#e8112d\" stroke-width=\"1.2\"/>",
                "plane development"},
               {sym_line("#999999", 0.8, "5,4"), "\u03b3 = 90\u00b0 (no shear)"}});
  o += "</svg>\n";
  return o;
}

Status write_svgs(const ExportContext& ctx, const std::string& outdir) {
  const std::filesystem::path dir(outdir);
  if (auto s = write_file_atomic((dir / "flat.svg").string(), flat_svg(ctx)); !s) return s;
  if (auto s = write_file_atomic((dir / "drape.svg").string(), drape_svg(ctx)); !s) return s;
  return write_file_atomic((dir / "shear.svg").string(), shear_svg(ctx));
}

}  // namespace

Exporter make_svg_exporter() {
  return {"svg",
          {"flat.svg", "drape.svg", "shear.svg"},
          "flat.svg, drape.svg, shear.svg: plane development, 3D fitting, thread-angle field",
          write_svgs};
}

}  // namespace plyfit::exporters
