// flat.svg: the plane development in ply coordinates, drawn in millimetres (1 user unit =
// 1 mm, printable 1:1); its annotation is sized to the drawing (render/drawing_scale.hpp): as
// in the pixel pictures relative to the drawing, never smaller than on paper, and the net's
// strokes thinner than its cells.
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/splice.hpp>

#include "net_util.hpp"
#include "render/label_placement.hpp"
#include "render/text.hpp"
#include "svg/draw.hpp"
#include "svg/pictures.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::svg {

namespace {

using detail::kRadToDeg;
using render::fixed_text;

// Coordinates are written to this fraction of the thinnest stroke.
constexpr double kResolutionRel = 0.1;
constexpr int kMaxGridLines = 400;     // thread grid lines per direction drawn
constexpr double kMinGridPitch = 3.0;  // px: a denser grid is left out
// The scale bar under the drawing: at most this fraction of the drawing's width, and its room
// (px) below the drawing.
constexpr double kScaleBarRel = 0.5, kScaleBarRoom = 46.0;
// The sweep arrows: kArrowRel of the drawing long, at least kMinArrowPx px; the start marker's
// radius and stroke and the arrows' stroke (px); the steps (px) by which a label moves away
// from its preferred place when something is there, and how wide (relative to the drawing) a
// label must be to be kept off the drawing.
constexpr double kArrowRel = 0.15, kMinArrowPx = 36.0, kMarkerPx = 6.0, kMarkerStrokePx = 2.4,
                 kArrowStrokePx = 2.4, kLabelGapPx = 6.0, kLabelOverPartRel = 0.5;
const Vec2 kSweepLabelAt(6.0, -4.0), kStartLabelAt(8.0, 16.0);  // baselines, px

// A label: its text (empty for the start's label, P with a subscript s) and its box in ply
// coordinates (y up).
struct Label {
  std::string text;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
};

// The picture's layout: the frame (1:1), the annotation's scale, the sweep arrows' length, the
// labels of the sweeps and the start (the last), and the thread spacing.
struct Layout {
  Frame frame;
  TitleBlock title;
  render::DrawingScale scale;
  double arrow_len = 0.0;
  std::vector<Label> labels;
  double d = 0.0;  // the smaller thread spacing, user units
};

double path_mark_radius(const render::DrawingScale& sc) {
  return sc.sized(0.22, 1.8, 4.0, render::kPathMarkMaxRel);
}

// What the labels keep clear of: the base path and its marks, the start marker, the arrows.
render::Obstacles label_obstacles(const ExportContext& ctx, const Layout& l) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  render::Obstacles o;
  for (std::size_t k = 0; k < r.base_path.size(); ++k) {
    const Vec2& p = r.nodes[r.base_path[k]].ply;
    o.discs.emplace_back(p, path_mark_radius(l.scale));
    if (k > 0) o.segments.emplace_back(r.nodes[r.base_path[k - 1]].ply, p);
  }
  o.discs.emplace_back(spec.start, l.scale.mark_unit * (kMarkerPx + kMarkerStrokePx));
  for (const Vec2& w : spec.sweeps)
    o.segments.emplace_back(spec.start, spec.start + l.arrow_len * w.normalized());
  return o;
}

// The sweep labels at the arrows' tips and the start's label, each where nothing else is; a
// label wider than kLabelOverPartRel of the drawing `part` goes off it if there is room nearby.
std::vector<Label> place_labels(const ExportContext& ctx, const Layout& l, const Box2& part) {
  const PlySpec& spec = ctx.problem.ply;
  const double u = l.scale.unit;
  render::Obstacles obstacles = label_obstacles(ctx, l);
  render::Obstacles drawing;
  drawing.boxes.emplace_back(part.lo, part.hi);
  std::vector<Label> labels;
  // A label of `size_px` whose top-left corner is preferably `at_px` from the anchor (x right,
  // y down, px).
  auto place = [&](const std::string& text, const Vec2& anchor, const Vec2& towards,
                   const Vec2& size_px, const Vec2& at_px) {
    const Vec2 size = u * size_px;
    const Vec2 preferred = anchor + u * Vec2(at_px.x(), -at_px.y() - size_px.y());
    const bool large = size.x() > kLabelOverPartRel * std::max(part.size().x(), part.size().y());
    const Vec2 lo = render::place_label(anchor, size, preferred, towards, u * kLabelGapPx,
                                        obstacles, large ? &drawing : nullptr);
    obstacles.boxes.emplace_back(lo, lo + size);
    labels.push_back({text, lo, lo + size});
  };
  const Vec2 ascent(0.0, kAscentEm * kSubEm);
  for (std::size_t k = 0; k < spec.sweeps.size(); ++k) {
    const std::string text = "sweep " + std::to_string(k + 1);
    const Vec2 w = spec.sweeps[k].normalized();
    place(text, spec.start + l.arrow_len * w, w, text_size(text, kSubEm), kSweepLabelAt - ascent);
  }
  place("", spec.start, Vec2(1.0, -1.0).normalized(), kStartLabelSize,
        kStartLabelAt - Vec2(0.0, kAscentEm * kTitleEm));
  return labels;
}

Layout layout(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  Layout l;
  Box2 box;
  if (ctx.flat) box.add(ctx.flat->outline);
  box.add_mapped(r);
  box.add(spec.start);
  const double ext = box.empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  l.d = std::min(spec.d_weft, spec.d_warp);
  l.scale = render::drawing_scale(ext, l.d);
  l.arrow_len = std::max(kArrowRel * std::max(ext, spec.d_weft), l.scale.mark_unit * kMinArrowPx);
  const Box2 part = box;
  for (const Vec2& w : spec.sweeps) box.add(spec.start + l.arrow_len * w.normalized());
  l.labels = place_labels(ctx, l, part);
  // Room for the labels; 1:1, one user unit per millimetre of the ply.
  box = padded(box, 0.04 * ext);
  for (const Label& lb : l.labels) {
    box.add(lb.lo);
    box.add(lb.hi);
  }
  l.frame = Frame::fit(box, 1.0, l.scale.unit);
  l.frame.bottom = kScaleBarRoom * l.scale.unit;
  l.title = title_over(l.frame, "Plane development (ply coordinates, mm; 1:1 at 100 %)",
                       source_line(ctx) + "; " + std::to_string(r.metrics.nodes.mapped) +
                           " mapped nodes, outline area " +
                           fixed_text(ctx.flat ? ctx.flat->area : 0.0, 2) + " mm\u00b2, " +
                           shear_summary(ctx));
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
  if (!(l.d >= l.scale.px(kMinGridPitch) && gx1 - gx0 < kMaxGridLines && gy1 - gy0 < kMaxGridLines))
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
         px(l.scale.net_stroke(0.6)) + "\" fill=\"none\"/>\n";
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
  const double w = l.scale.sized(0.12, 0.8, 2.5, render::kNetStrokeMaxRel);
  return o + "<path id=\"links\" d=\"" + g + "\" stroke=\"#1a1a1a\" stroke-width=\"" + px(w) +
         "\" stroke-linecap=\"round\" fill=\"none\"/>\n";
}

// The staircase outline of the mapped cells and the exact outline.
std::string outlines(const FlatPattern& flat, const Layout& l) {
  const Frame& f = l.frame;
  auto loops_of = [&](const std::vector<OutlineLoop>& ls) {
    std::vector<std::vector<Vec2>> out;
    for (const auto& loop : ls) out.push_back(mapped(f, loop.points));
    return out;
  };
  return "<path id=\"staircase\" d=\"" + loops_path(loops_of(flat.staircase)) +
         "\" stroke=\"#000000\" stroke-width=\"" + px(l.scale.edge_stroke(2.6)) +
         "\" fill=\"none\" stroke-linejoin=\"round\"/>\n" + "<path id=\"outline\" d=\"" +
         loops_path(loops_of(flat.outline)) + "\" stroke=\"#e8112d\" stroke-width=\"" +
         px(l.scale.edge_stroke(1.8)) +
         "\" fill=\"none\" fill-rule=\"evenodd\" stroke-linejoin=\"round\"/>\n";
}

// Each dart's two cut lines (open paths), where each side's cloth ends.
std::string dart_lines(const DrapeResult& r, const Layout& l) {
  if (r.darts.empty()) return "";
  std::string path;
  for (const DartResult& d : r.darts) {
    for (const auto* cut : {&d.line_left, &d.line_right}) {
      const std::vector<Vec2> pts = mapped(l.frame, *cut);
      for (std::size_t k = 1; k < pts.size(); ++k) add_segment(path, pts[k - 1], pts[k]);
    }
  }
  return "<path id=\"darts\" d=\"" + path + "\" stroke=\"#8800aa\" stroke-width=\"" +
         px(l.scale.edge_stroke(1.8)) + "\" fill=\"none\" stroke-linejoin=\"round\"/>\n";
}

// The pieces' outline colours, in turn (pieces next to each other differ), and the seams'.
const char* const kPieceColours[] = {"#1f5fd6", "#e07b00", "#008a5e", "#8a5a00"};
const char* const kSeamColour = "#cc00cc";

// A pattern split for the roll: each piece's loops as an outline of its own (class "piece",
// data-name its name), and the seams where pieces meet, dashed (id "seams"): the warp lines
// x = s clipped to the cut outline, as flat.dxf's SEAMS.
std::string pieces_and_seams(const ExportContext& ctx, const Layout& l) {
  if (!ctx.splices || !ctx.splices->split() || !ctx.flat) return "";
  const Frame& f = l.frame;
  const double w = l.scale.edge_stroke(1.4);
  std::string o =
      "<g id=\"pieces\" fill=\"none\" stroke-width=\"" + px(w) + "\" stroke-linejoin=\"round\">\n";
  std::size_t k = 0;
  for (const SplicePiece& p : ctx.splices->pieces) {
    std::vector<std::vector<Vec2>> loops;
    for (const auto& loop : p.loops) loops.push_back(mapped(f, loop.points));
    const char* colour = kPieceColours[k++ % std::size(kPieceColours)];
    o += "<path class=\"piece\" data-name=\"" + render::xml_escape(p.name) + "\" d=\"" +
         loops_path(loops) + "\" stroke=\"" + colour + "\" fill-rule=\"evenodd\"/>\n";
  }
  o += "</g>\n";
  std::string seams;
  for (const Seam& s : ctx.splices->seams)
    for (const auto& [a, b] : detail::clip_line(ctx.flat->cut, 0, s.x))
      add_segment(seams, f.map({s.x, a}), f.map({s.x, b}));
  return o + "<path id=\"seams\" d=\"" + seams + "\" stroke=\"" + kSeamColour +
         "\" stroke-width=\"" + px(w) + "\" stroke-dasharray=\"" + px(6 * w) + " " + px(4 * w) +
         "\" fill=\"none\"/>\n";
}

// The cells whose shear exceeds the warning angle.
std::string shear_warnings(const ExportContext& ctx, const std::vector<detail::NetCell>& cells,
                           const Layout& l) {
  const Frame& f = l.frame;
  std::string o = "<g id=\"shear-warn\" fill=\"none\" stroke=\"#ff00cc\" stroke-width=\"" +
                  px(l.scale.edge_stroke(1.6)) + "\">\n";
  for (const auto& c : cells)
    if (c.shear > ctx.options.warn_shear)
      o += polygon(mapped(f, detail::cell_ply_points(ctx.result, c)), "shear-warn", "");
  return o + "</g>\n";
}

// The mapped regular nodes and the base path's nodes.
std::string nodes(const DrapeResult& r, const Layout& l) {
  const double node_r = l.scale.sized(0.1, 0.6, 2.4, render::kNodeMarkMaxRel);
  std::string o = "<g id=\"nodes\">\n";
  for (const DrapeNode& n : r.nodes)
    if (n.mapped() && !n.id.is_path_only()) o += circle(l.frame.map(n.ply), node_r, "node");
  o += "</g>\n<g id=\"base-path\">\n";
  const double path_r = path_mark_radius(l.scale);
  for (const std::uint32_t k : r.base_path)
    o += circle(l.frame.map(r.nodes[k].ply), path_r, "path-node");
  return o + "</g>\n";
}

// The start point P_s and the sweep arrows, and their labels where the layout placed them.
std::string start_and_sweeps(const PlySpec& spec, const Layout& l) {
  const double u = l.scale.unit, mu = l.scale.mark_unit;
  const std::string blue = "#1f5fd6";
  std::string o = "<g id=\"start\">\n";
  const Vec2 s = l.frame.map(spec.start);
  for (std::size_t k = 0; k < spec.sweeps.size(); ++k) {
    const Vec2 tip = l.frame.map(spec.start + l.arrow_len * spec.sweeps[k].normalized());
    o += at_px(s, mu, arrow(Vec2::Zero(), (tip - s) / mu, blue, kArrowStrokePx));
  }
  o += at_px(s, mu,
             circle(Vec2::Zero(), kMarkerPx, "",
                    " id=\"origin\" fill=\"#ffffff\" stroke=\"" + blue + "\" stroke-width=\"" +
                        px(kMarkerStrokePx) + "\"") +
                 "\n");
  for (const Label& lb : l.labels) {
    const Vec2 top_left = l.frame.map({lb.lo.x(), lb.hi.y()});
    o += "<g class=\"label\">\n";
    o += lb.text.empty()
             ? at_px(top_left, u, start_label(Vec2::Zero(), blue))
             : at_px(top_left, u,
                     text(0, kAscentEm * kSubEm, lb.text, "sub halo", " fill=\"" + blue + "\""));
    o += "</g>\n";
  }
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
  const double tick = 6.0 * f.unit;
  std::string o = "<g id=\"scale-bar\" data-length-mm=\"" + fixed_text(len, 6) + "\">\n";
  o +=
      line(a, {a.x() + len, a.y()}, "stroke=\"#000000\" stroke-width=\"" + px(1.6 * f.unit) + "\"");
  for (const double x : {a.x(), a.x() + len})
    o += line({x, a.y() - tick}, {x, a.y() + tick},
              "stroke=\"#000000\" stroke-width=\"" + px(1.2 * f.unit) + "\"");
  o += at_px(Vec2(a.x() + len, a.y()), f.unit, text(8, 4, fixed_text(len, 6) + " mm", "small"));
  return o + "</g>\n";
}

// The legend and the ply axes, in px beside the drawing; the darts' cut lines and the pieces
// and seams when there are some.
std::string flat_legend(const ExportContext& ctx, const render::ShearScale& scale, double warn,
                        const Frame& f) {
  double legend_end = 0.0;
  std::vector<LegendEntry> entries = {
      {"<rect x=\"{X}\" y=\"{Y}\" width=\"24\" height=\"12\" fill=\"none\" "
       "stroke=\"#ff00cc\" stroke-width=\"1.6\"/>",
       "shear > " + render::degrees_text(warn * kRadToDeg, 1)},
      {sym_line("#1a1a1a", 2.0), "mapped threads"},
      {sym_line("#000000", 2.6), "mapped cells' edge"},
      {sym_line("#e8112d", 1.8), "exact outline"}};
  if (!ctx.result.darts.empty()) entries.push_back({sym_line("#8800aa", 1.8), "dart cut lines"});
  if (ctx.splices && ctx.splices->split() && ctx.flat) {
    entries.push_back({sym_line(kPieceColours[0], 1.4), "pieces (one colour each)"});
    entries.push_back({sym_line(kSeamColour, 1.4, "6 4"), "seams"});
  }
  entries.push_back({"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"3\" fill=\"#000\"/>", "base path"});
  entries.push_back(
      {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"5\" fill=\"#fff\" "
       "stroke=\"#1f5fd6\" stroke-width=\"2\"/>",
       "start P\u209b, sweeps"});
  entries.push_back({sym_line("#dddddd", 1.0), "ply threads"});
  std::string lg = legend(0, 10, scale, warn, entries, &legend_end);
  const double ax = 20, ay = legend_end + 70;
  lg += arrow({ax, ay}, {ax + 40, ay}, "#444", 1.4);
  lg += arrow({ax, ay}, {ax, ay - 40}, "#444", 1.4);
  lg += text(ax + 44, ay + 4, "x weft", "small");
  lg += text(ax - 8, ay - 46, "y warp (0\u00b0)", "small");
  return at_px(Vec2(f.left + f.width + kMargin * f.unit, f.top), f.unit, lg);
}

}  // namespace

std::string flat_svg(const ExportContext& ctx) {
  const auto cells = detail::mapped_cells(ctx.result);
  const render::ShearScale scale = render::shear_scale(ctx.result);
  const Layout l = layout(ctx);
  const Frame& f = l.frame;
  const WrittenDecimals decimals(kResolutionRel * l.scale.net_stroke(0.6));
  std::string o = svg_open(f.canvas_width(), f.canvas_height(), "plyfit plane development", true);
  o += at_px(Vec2::Zero(), f.unit, l.title.svg);
  o += thread_grid(ctx.problem.ply, l);
  o += cells_and_links(ctx, cells, scale, l);
  if (ctx.flat) o += outlines(*ctx.flat, l);
  o += shear_warnings(ctx, cells, l);
  o += pieces_and_seams(ctx, l);
  o += dart_lines(ctx.result, l);
  o += nodes(ctx.result, l);
  o += start_and_sweeps(ctx.problem.ply, l);
  o += scale_bar(f);
  o += flat_legend(ctx, scale, ctx.options.warn_shear, f);
  o += "</svg>\n";
  return o;
}

}  // namespace plyfit::exporters::svg
