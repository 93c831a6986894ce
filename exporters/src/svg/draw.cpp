#include "svg/draw.hpp"

#include "render/text.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::svg {

using render::fixed_text;
using render::xml_escape;

namespace {

// The title block (px): baselines of the first title line and the first subtitle line below
// the last title line, line pitches, the depth below the last line.
constexpr double kTitleBaseline = 28.0, kSubBelowTitle = 19.0, kTitlePitch = 21.0, kSubPitch = 16.0,
                 kTitleDepth = 9.0;
// Decimals px() writes: the default, and at most (a double's digits below the point).
constexpr int kDefaultDecimals = 2, kMaxDecimals = 12;
thread_local int written_decimals = kDefaultDecimals;

// The start label's subscript: its offset (px) from the "P" and its baseline's drop.
constexpr double kSubscriptX = 11.0, kSubscriptDrop = 4.0;
// The legend's colour bar (px) and its gradient's stops.
constexpr double kBarWidth = 22.0, kBarHeight = 220.0;
constexpr int kGradientStops = 16;

// Lines of `s` of at most `width` px at font size `em` (px).
std::vector<std::string> wrap(const std::string& s, double width, double em) {
  return render::wrap_words(
      s, static_cast<std::size_t>(std::max(10.0, std::floor(width / (kCharEm * em)))));
}

// The colour bar with its top at y0: the gradient, the ticks of the scale, the warning level.
std::string colour_bar(double x, double y0, const render::ShearScale& scale, double warn) {
  const double top = scale.top;
  std::string o = "<defs><linearGradient id=\"shear-scale\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n";
  for (int k = 0; k <= kGradientStops; ++k) {
    const double t = static_cast<double>(k) / kGradientStops;
    o += "<stop offset=\"" + fixed_text(t, 4) + "\" stop-color=\"" + render::shear_colour(t).hex() +
         "\"/>\n";
  }
  o += "</linearGradient></defs>\n";
  o += "<rect x=\"" + px(x) + "\" y=\"" + px(y0) + "\" width=\"" + px(kBarWidth) + "\" height=\"" +
       px(kBarHeight) + "\" fill=\"url(#shear-scale)\" stroke=\"#333\" stroke-width=\"0.8\"/>\n";
  const double top_deg = top * detail::kRadToDeg;
  const int ticks = static_cast<int>(std::lround(top_deg / scale.step_deg));
  for (int k = 0; k <= ticks; ++k) {
    const double v = scale.step_deg * k;
    const double yy = y0 + kBarHeight * (1.0 - v / top_deg);
    o += line({x + kBarWidth, yy}, {x + kBarWidth + 5, yy}, "stroke=\"#333\"");
    o += text(x + kBarWidth + 8, yy + 4, render::degrees_text(v, 0), "small");
  }
  if (warn <= top) {
    const double yy = y0 + kBarHeight * (1.0 - warn / top);
    o += line({x - 4, yy}, {x + kBarWidth + 4, yy}, "stroke=\"#e8112d\" stroke-width=\"2\"");
    o += text(x + kBarWidth + 46, yy + 4, "warn", "small", " fill=\"#e8112d\"");
  }
  return o;
}

}  // namespace

Vec2 text_size(const std::string& s, double em) {
  return {kCharEm * em * static_cast<double>(render::utf8_length(s)),
          (kAscentEm + kDescentEm) * em};
}

const Vec2 kStartLabelSize(kSubscriptX + kCharEm * kSubEm,
                           kAscentEm* kTitleEm + kSubscriptDrop + kDescentEm * kSubEm);

std::string start_label(const Vec2& top_left, const std::string& colour) {
  const double baseline = top_left.y() + kAscentEm * kTitleEm;
  const std::string fill = " fill=\"" + colour + "\"";
  return text(top_left.x(), baseline, "P", "title halo", fill) +
         text(top_left.x() + kSubscriptX, baseline + kSubscriptDrop, "s", "sub halo", fill);
}

std::string px(double v) {
  return fixed_text(v, written_decimals);
}

WrittenDecimals::WrittenDecimals(double resolution) : saved_(written_decimals) {
  if (resolution > 0 && std::isfinite(resolution))
    written_decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(resolution))),
                                  kDefaultDecimals, kMaxDecimals);
}

WrittenDecimals::~WrittenDecimals() {
  written_decimals = saved_;
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

void add_segment(std::string& d, const Vec2& a, const Vec2& b) {
  d += 'M';
  d += pt(a);
  d += 'L';
  d += pt(b);
}

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

std::string text(double x, double y, const std::string& s, const std::string& cls,
                 const std::string& extra) {
  return "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" class=\"" + cls + "\"" + extra + ">" +
         xml_escape(s) + "</text>\n";
}

std::string line(const Vec2& a, const Vec2& b, const std::string& style) {
  return "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(b.x()) + "\" y2=\"" +
         px(b.y()) + "\" " + style + "/>\n";
}

std::string circle(const Vec2& c, double r, const std::string& cls, const std::string& extra) {
  const std::string class_attr = cls.empty() ? "" : " class=\"" + cls + "\"";
  return "<circle" + class_attr + " cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" +
         px(r) + "\"" + extra + "/>\n";
}

std::string polygon(const std::vector<Vec2>& pts, const std::string& cls,
                    const std::string& extra) {
  const std::string class_attr = cls.empty() ? "" : " class=\"" + cls + "\"";
  return "<polygon" + class_attr + " points=\"" + points_attr(pts) + "\"" + extra + "/>\n";
}

std::string arrow(const Vec2& a, const Vec2& b, const std::string& colour, double width) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0)) return "";
  const Vec2 u = d / len, n(-u.y(), u.x());
  const double head = std::min(12.0, 0.35 * len);
  const Vec2 base = b - head * u;
  return line(a, base, "stroke=\"" + colour + "\" stroke-width=\"" + px(width) + "\"") +
         polygon({b, base + 0.4 * head * n, base - 0.4 * head * n}, "", " fill=\"" + colour + "\"");
}

std::string at_px(const Vec2& p, double unit, const std::string& svg) {
  return "<g transform=\"translate(" + px(p.x()) + " " + px(p.y()) + ") scale(" +
         fixed_text(unit, 6) + ")\">\n" + svg + "</g>\n";
}

std::string svg_open(double w, double h, const std::string& title, bool mm) {
  const std::string u = mm ? "mm" : "";
  std::string o;
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(w) + u +
       "\" height=\"" + px(h) + u + "\" viewBox=\"0 0 " + px(w) + " " + px(h) + "\">\n";
  o += "<title>" + xml_escape(title) + "</title>\n";
  o += "<style>\n"
       "text{font-family:DejaVu Sans,Verdana,Arial,sans-serif;fill:#222}\n"
       ".title{font-size:" +
       fixed_text(kTitleEm, 0) + "px;font-weight:bold}.sub{font-size:" + fixed_text(kSubEm, 0) +
       "px}.small{font-size:" + fixed_text(kSmallEm, 0) +
       "px}\n"
       ".node{fill:#1a1a1a}.path-node{fill:#000}\n"
       ".halo{paint-order:stroke;stroke:#ffffff;stroke-width:3px;stroke-linejoin:round}\n"
       "</style>\n";
  o +=
      "<rect x=\"0\" y=\"0\" width=\"" + px(w) + "\" height=\"" + px(h) + "\" fill=\"#ffffff\"/>\n";
  return o;
}

Frame Frame::fit(Box2 box, double fixed_scale, double unit) {
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

Box2 padded(const Box2& box, double margin) {
  Box2 out = box;
  out.add(box.lo - Vec2::Constant(margin));
  out.add(box.hi + Vec2::Constant(margin));
  return out;
}

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

TitleBlock title_over(Frame& f, const std::string& title, const std::string& sub) {
  double longest = 0.0;  // px: a word is never cut
  for (const auto& [s, em] : {std::pair{title, kTitleEm}, {sub, kSubEm}})
    for (const auto& w : render::wrap_words(s, 1))
      longest = std::max(longest, text_size(w, em).x());
  const double room = f.canvas_width() / f.unit - 2 * kMargin;
  if (longest > room) f.min_width = f.width + (longest - room) * f.unit;
  const TitleBlock tb = title_block(title, sub, f.canvas_width() / f.unit - 2 * kMargin);
  f.top = tb.height * f.unit + kMargin * f.unit * 0.5;
  return tb;
}

std::string source_line(const ExportContext& ctx) {
  return ctx.run.ply_name + " (" + render::material_label(ctx) + ") on " +
         render::mold_label(ctx.run.mold) + ", " + render::faces_label(ctx.run.faces);
}

std::string shear_summary(const ExportContext& ctx) {
  const DrapeMetrics& m = ctx.result.metrics;
  return "max shear " + render::degrees_text(m.shear_max * detail::kRadToDeg, 2) + ", \u03b3 " +
         render::degrees_text(m.gamma_min * detail::kRadToDeg, 2) + " \u2026 " +
         render::degrees_text(m.gamma_max * detail::kRadToDeg, 2);
}

std::string sym_line(const std::string& colour, double w, const std::string& dash) {
  return "<line x1=\"{X}\" y1=\"{YM}\" x2=\"{X2}\" y2=\"{YM}\" stroke=\"" + colour +
         "\" stroke-width=\"" + px(w) + "\"" +
         (dash.empty() ? "" : " stroke-dasharray=\"" + dash + "\"") + "/>";
}

std::string legend(double x, double y, const render::ShearScale& scale, double warn,
                   const std::vector<LegendEntry>& entries, double* end_y) {
  std::string o = "<g id=\"legend\">\n";
  o += text(x, y, "shear |90\u00b0 \u2212 \u03b3|", "sub");
  const double y0 = y + 14.0;
  o += colour_bar(x, y0, scale, warn);
  double yy = y0 + kBarHeight + 26.0;
  o += "<rect x=\"" + px(x) + "\" y=\"" + px(yy - 9) + "\" width=\"14\" height=\"10\" fill=\"" +
       render::no_shear_colour().hex() + "\"/>\n";
  o += text(x + 20, yy, "no thread angle", "small");
  for (const auto& [symbol, label] : entries) {
    yy += 18.0;
    std::string s = symbol;
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

std::string draw_sorted(std::vector<Prim>& prims) {
  std::stable_sort(prims.begin(), prims.end(),
                   [](const Prim& a, const Prim& b) { return a.depth < b.depth; });
  std::string o;
  for (const Prim& p : prims) o += p.svg;
  return o;
}

}  // namespace plyfit::exporters::svg
