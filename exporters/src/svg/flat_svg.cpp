// flat.svg: the plane development in ply coordinates, drawn in millimetres (1 user unit =
// 1 mm, printable 1:1); its annotation keeps the size it has in the pixel pictures.
#include <plyfit/kernel/flat_pattern.hpp>

#include "render/text.hpp"
#include "svg/draw.hpp"
#include "svg/pictures.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::svg {

namespace {

using detail::kRadToDeg;
using render::fixed_text;

// One CSS pixel is 1/96 inch: the user units (mm) per px of annotation.
constexpr double kMmPerPx = 25.4 / 96.0;
constexpr int kMaxGridLines = 400;     // thread grid lines per direction drawn
constexpr double kMinGridPitch = 3.0;  // px: a denser grid is left out
// The scale bar under the drawing: at most this fraction of the drawing's width, and its room
// (px) below the drawing.
constexpr double kScaleBarRel = 0.5, kScaleBarRoom = 46.0;

// The picture's layout: the frame (1:1), the sweep arrows' length and the thread spacing.
struct Layout {
  Frame frame;
  TitleBlock title;
  double arrow_len = 0.0;
  double d = 0.0;  // the smaller thread spacing, user units
};

Layout layout(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  Layout l;
  Box2 box;
  if (ctx.flat) box.add(ctx.flat->outline);
  box.add_mapped(r);
  box.add(spec.start);
  const double ext = box.empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  l.arrow_len = 0.15 * std::max(ext, spec.d_weft);
  for (const Vec2& w : spec.sweeps) box.add(spec.start + l.arrow_len * w.normalized());
  // Room for labels of the start and arrows; 1:1, one user unit per millimetre of the ply.
  l.frame = Frame::fit(padded(box, 0.04 * ext), 1.0, kMmPerPx);
  l.frame.bottom = kScaleBarRoom * kMmPerPx;
  l.title = title_over(l.frame, "Plane development (ply coordinates, mm; 1:1 at 100 %)",
                       source_line(ctx) + "; " + std::to_string(r.metrics.nodes.mapped) +
                           " mapped nodes, outline area " +
                           fixed_text(ctx.flat ? ctx.flat->area : 0.0, 2) + " mm\u00b2, " +
                           shear_summary(ctx));
  l.d = std::min(spec.d_weft, spec.d_warp);
  return l;
}

// The thread grid of the ply over the frame, unless too dense or too many lines.
std::string thread_grid(const PlySpec& spec, const Layout& l) {
  const Frame& f = l.frame;
  const Box2 view{f.lo, f.hi};
  const double gx0 = std::ceil(view.lo.x() / spec.d_weft),
               gx1 = std::floor(view.hi.x() / spec.d_weft);
  const double gy0 = std::ceil(view.lo.y() / spec.d_warp),
               gy1 = std::floor(view.hi.y() / spec.d_warp);
  if (!(l.d >= kMinGridPitch * kMmPerPx && gx1 - gx0 < kMaxGridLines && gy1 - gy0 < kMaxGridLines))
    return "";
  std::string g;
  for (double i = gx0; i <= gx1; ++i) {
    const double x = i * spec.d_weft;
    add_segment(g, f.map({x, view.lo.y()}), f.map({x, view.hi.y()}));
  }
  for (double j = gy0; j <= gy1; ++j) {
    const double y = j * spec.d_warp;
    add_segment(g, f.map({view.lo.x(), y}), f.map({view.hi.x(), y}));
  }
  return "<path id=\"grid\" d=\"" + g + "\" stroke=\"#dddddd\" stroke-width=\"" +
         px(0.6 * kMmPerPx) + "\" fill=\"none\"/>\n";
}

std::vector<Vec2> mapped(const Frame& f, std::vector<Vec2> pts) {
  for (Vec2& p : pts) p = f.map(p);
  return pts;
}

// The mapped cells coloured by shear, the mapped links in bold (the paper's bold segments).
std::string cells_and_links(const ExportContext& ctx, const std::vector<detail::NetCell>& cells,
                            const render::ShearScale& scale, const Layout& l) {
  const DrapeResult& r = ctx.result;
  std::string o = "<g id=\"cells\" stroke=\"none\">\n";
  for (const auto& c : cells)
    o += polygon(mapped(l.frame, detail::cell_ply_points(r, c)), "cell",
                 " fill=\"" + scale.colour(c.shear).hex() + "\"");
  o += "</g>\n";
  std::string g;
  for (const DrapeLink& k : r.links())
    add_segment(g, l.frame.map(r.nodes[k.a].ply), l.frame.map(r.nodes[k.b].ply));
  const double w = std::clamp(0.12 * l.d, 0.8 * kMmPerPx, 2.5 * kMmPerPx);
  return o + "<path id=\"links\" d=\"" + g + "\" stroke=\"#1a1a1a\" stroke-width=\"" + px(w) +
         "\" stroke-linecap=\"round\" fill=\"none\"/>\n";
}

// The staircase outline of the mapped cells and the exact outline.
std::string outlines(const FlatPattern& flat, const Frame& f) {
  auto loops_of = [&](const std::vector<OutlineLoop>& ls) {
    std::vector<std::vector<Vec2>> out;
    for (const auto& l : ls) out.push_back(mapped(f, l.points));
    return out;
  };
  return "<path id=\"staircase\" d=\"" + loops_path(loops_of(flat.staircase)) +
         "\" stroke=\"#000000\" stroke-width=\"" + px(2.6 * kMmPerPx) +
         "\" fill=\"none\" stroke-linejoin=\"round\"/>\n" + "<path id=\"outline\" d=\"" +
         loops_path(loops_of(flat.outline)) + "\" stroke=\"#e8112d\" stroke-width=\"" +
         px(1.8 * kMmPerPx) +
         "\" fill=\"none\" fill-rule=\"evenodd\" stroke-linejoin=\"round\"/>\n";
}

// The cells whose shear exceeds the warning angle.
std::string shear_warnings(const ExportContext& ctx, const std::vector<detail::NetCell>& cells,
                           const Frame& f) {
  std::string o = "<g id=\"shear-warn\" fill=\"none\" stroke=\"#ff00cc\" stroke-width=\"" +
                  px(1.6 * kMmPerPx) + "\">\n";
  for (const auto& c : cells)
    if (c.shear > ctx.options.warn_shear)
      o += polygon(mapped(f, detail::cell_ply_points(ctx.result, c)), "shear-warn", "");
  return o + "</g>\n";
}

// The mapped regular nodes and the base path's nodes.
std::string nodes(const DrapeResult& r, const Layout& l) {
  const double node_r = std::clamp(0.1 * l.d, 0.6 * kMmPerPx, 2.4 * kMmPerPx);
  std::string o = "<g id=\"nodes\">\n";
  for (const DrapeNode& n : r.nodes)
    if (n.mapped() && !n.id.is_path_only()) o += circle(l.frame.map(n.ply), node_r, "node");
  o += "</g>\n<g id=\"base-path\">\n";
  const double path_r = std::clamp(0.22 * l.d, 1.8 * kMmPerPx, 4.0 * kMmPerPx);
  for (const std::uint32_t k : r.base_path)
    o += circle(l.frame.map(r.nodes[k].ply), path_r, "path-node");
  return o + "</g>\n";
}

// The start point P_s and the sweep arrows.
std::string start_and_sweeps(const PlySpec& spec, const Layout& l) {
  std::string o = "<g id=\"start\">\n";
  const Vec2 s = l.frame.map(spec.start);
  for (std::size_t k = 0; k < spec.sweeps.size(); ++k) {
    const Vec2 tip = l.frame.map(spec.start + l.arrow_len * spec.sweeps[k].normalized());
    o += at_px(s, kMmPerPx, arrow(Vec2::Zero(), (tip - s) / kMmPerPx, "#1f5fd6", 2.4));
    o += at_px(tip, kMmPerPx,
               text(6, -4, "sweep " + std::to_string(k + 1), "sub halo", " fill=\"#1f5fd6\""));
  }
  o += at_px(s, kMmPerPx,
             "<circle cx=\"0\" cy=\"0\" r=\"6\" fill=\"#ffffff\" stroke=\"#1f5fd6\" "
             "stroke-width=\"2.4\"/>\n" +
                 text(8, 16, "P", "title halo", " fill=\"#1f5fd6\"") +
                 text(19, 20, "s", "sub halo", " fill=\"#1f5fd6\""));
  return o + "</g>\n";
}

// A round length for the scale bar: 1, 2 or 5 times a power of ten, at most `max_len`.
double scale_bar_length(double max_len) {
  if (!(max_len > 0)) return 0.0;
  const double p = std::pow(10.0, std::floor(std::log10(max_len)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= max_len) return m * p;
  return p;
}

// The scale bar: a round length in millimetres, to check the print is 1:1.
std::string scale_bar(const Frame& f) {
  const double len = scale_bar_length(kScaleBarRel * f.width);
  const Vec2 a(f.left, f.top + f.height + 0.5 * f.bottom);
  const double tick = 6.0 * kMmPerPx;
  std::string o = "<g id=\"scale-bar\" data-length-mm=\"" + fixed_text(len, 6) + "\">\n";
  o += line(a, {a.x() + len, a.y()},
            "stroke=\"#000000\" stroke-width=\"" + px(1.6 * kMmPerPx) + "\"");
  for (const double x : {a.x(), a.x() + len})
    o += line({x, a.y() - tick}, {x, a.y() + tick},
              "stroke=\"#000000\" stroke-width=\"" + px(1.2 * kMmPerPx) + "\"");
  o += at_px(Vec2(a.x() + len, a.y()), kMmPerPx, text(8, 4, fixed_text(len, 6) + " mm", "small"));
  return o + "</g>\n";
}

// The legend and the ply axes, in px beside the drawing.
std::string flat_legend(const render::ShearScale& scale, double warn, const Frame& f) {
  double legend_end = 0.0;
  std::string lg = legend(0, 10, scale, warn,
                          {{"<rect x=\"{X}\" y=\"{Y}\" width=\"24\" height=\"12\" fill=\"none\" "
                            "stroke=\"#ff00cc\" stroke-width=\"1.6\"/>",
                            "shear > " + render::degrees_text(warn * kRadToDeg, 1)},
                           {sym_line("#1a1a1a", 2.0), "mapped threads"},
                           {sym_line("#000000", 2.6), "mapped cells' edge"},
                           {sym_line("#e8112d", 1.8), "exact outline"},
                           {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"3\" fill=\"#000\"/>", "base path"},
                           {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"5\" fill=\"#fff\" "
                            "stroke=\"#1f5fd6\" stroke-width=\"2\"/>",
                            "start P\u209b, sweeps"},
                           {sym_line("#dddddd", 1.0), "ply threads"}},
                          &legend_end);
  const double ax = 20, ay = legend_end + 70;
  lg += arrow({ax, ay}, {ax + 40, ay}, "#444", 1.4);
  lg += arrow({ax, ay}, {ax, ay - 40}, "#444", 1.4);
  lg += text(ax + 44, ay + 4, "x weft", "small");
  lg += text(ax - 8, ay - 46, "y warp (0\u00b0)", "small");
  return at_px(Vec2(f.left + f.width + kMargin * kMmPerPx, f.top), kMmPerPx, lg);
}

}  // namespace

std::string flat_svg(const ExportContext& ctx) {
  const auto cells = detail::mapped_cells(ctx.result);
  const render::ShearScale scale = render::shear_scale(ctx.result);
  const Layout l = layout(ctx);
  const Frame& f = l.frame;
  std::string o = svg_open(f.canvas_width(), f.canvas_height(), "plyfit plane development", true);
  o += at_px(Vec2::Zero(), kMmPerPx, l.title.svg);
  o += thread_grid(ctx.problem.ply, l);
  o += cells_and_links(ctx, cells, scale, l);
  if (ctx.flat) o += outlines(*ctx.flat, f);
  o += shear_warnings(ctx, cells, f);
  o += nodes(ctx.result, l);
  o += start_and_sweeps(ctx.problem.ply, l);
  o += scale_bar(f);
  o += flat_legend(scale, ctx.options.warn_shear, f);
  o += "</svg>\n";
  return o;
}

}  // namespace plyfit::exporters::svg
