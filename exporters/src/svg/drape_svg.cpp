// drape.svg: the 3D fitting in an orthographic view along ExportOptions::view (towards the
// viewer; Z up on the page), painter's algorithm: every cell, segment and node sorted by depth.
#include <plyfit/kernel/mold.hpp>

#include "render/label_placement.hpp"
#include "render/text.hpp"
#include "svg/draw.hpp"
#include "svg/pictures.hpp"
#include "svg/scene3d.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::svg {

namespace {

using render::fixed_text;

// Each free boundary segment is drawn in this many pieces.
constexpr int kBoundaryPieces = 48;
// Strokes (px): threads, the base path, the face boundary; the start marker's radius and
// stroke, a label's gap from what it avoids.
constexpr double kThreadPx = 0.7, kPathPx = 2.2, kMarkerPx = 5.0, kMarkerStrokePx = 2.2,
                 kLabelGapPx = 6.0;
const std::string kBoundaryStyle =
    "stroke=\"#000000\" stroke-width=\"1.6\" stroke-linecap=\"round\"";
// The start label's preferred place: P's baseline from the start (px).
const Vec2 kStartLabelAt(8.0, -8.0);

std::string stroke_style(const std::string& colour, double width) {
  return "stroke=\"" + colour + "\" stroke-width=\"" + px(width) + "\"";
}

// The links, the base path and the free boundary as segments; the nodes over them. Segments
// and nodes are drawn over the cells they border (a depth bias of half the spacing `d`).
void add_net(std::vector<Prim>& prims, const DrapeResult& r, const std::vector<Segment3>& boundary,
             double d, const View& v) {
  const double bias = 0.5 * d;
  const render::DrawingScale sc = render::drawing_scale(kPlotSize, d * v.frame.scale, 1.0);
  const std::string thread_style = stroke_style("#262626", sc.net_stroke(kThreadPx));
  const std::string path_style = stroke_style("#1f5fd6", sc.net_stroke(kPathPx));
  auto segment = [&](const Vec3& a, const Vec3& b, const std::string& style) {
    return Prim{v.cam.depth(0.5 * (a + b)) + bias, line(v.map(a), v.map(b), style)};
  };
  for (const DrapeLink& l : r.links())
    prims.push_back(segment(r.nodes[l.a].point, r.nodes[l.b].point,
                            l.kind == LinkKind::kBase ? path_style : thread_style));
  // The base path's own thread links are drawn as the path too.
  for (std::size_t k = 1; k < r.base_path.size(); ++k)
    prims.push_back(
        segment(r.nodes[r.base_path[k - 1]].point, r.nodes[r.base_path[k]].point, path_style));
  for (const auto& [a, b] : boundary) prims.push_back(segment(a, b, kBoundaryStyle));
  const double node_r = sc.sized(0.06, 0.5, 2.0, render::kNodeMarkMaxRel);
  const double path_r = std::min(std::max(1.6, 2 * node_r), render::kPathMarkMaxRel * sc.cell);
  for (const DrapeNode& n : r.nodes)
    if (n.mapped() && !n.id.is_path_only())
      prims.push_back({v.cam.depth(n.point) + 1.2 * bias, circle(v.map(n.point), node_r, "node")});
  for (const std::uint32_t k : r.base_path)
    prims.push_back({v.cam.depth(r.nodes[k].point) + 1.3 * bias,
                     circle(v.map(r.nodes[k].point), path_r, "path-node", " fill=\"#1f5fd6\"")});
}

// The start point P_s over the scene, its label clear of the base path and the marker.
std::string start_marker(const DrapeResult& r, const View& v) {
  const Vec2 s = v.map(r.start_point);
  render::Obstacles avoid;
  for (std::size_t k = 1; k < r.base_path.size(); ++k)
    avoid.segments.emplace_back(v.map(r.nodes[r.base_path[k - 1]].point),
                                v.map(r.nodes[r.base_path[k]].point));
  avoid.discs.emplace_back(s, kMarkerPx + kMarkerStrokePx);
  const Vec2 preferred = s + kStartLabelAt - Vec2(0.0, kAscentEm * kTitleEm);
  const Vec2 at = render::place_label(s, kStartLabelSize, preferred, Vec2(1.0, -1.0).normalized(),
                                      kLabelGapPx, avoid);
  return circle(s, kMarkerPx, "",
                " id=\"origin\" fill=\"#ffffff\" " + stroke_style("#1f5fd6", kMarkerStrokePx)) +
         "<g class=\"label\">\n" + start_label(at, "#1f5fd6") + "</g>\n";
}

// The legend and, below it, the axis triad of the view.
std::string drape_legend(const render::ShearScale& scale, double warn, const View& v) {
  const double lx = v.frame.left + v.frame.width + kMargin;
  double legend_end = 0.0;
  std::string o =
      legend(lx, v.frame.top + 10, scale, warn,
             {{sym_line("#262626", 1.0), "threads"},
              {sym_line("#1f5fd6", 2.2), "base path"},
              {sym_line("#000000", 1.6), "face boundary"},
              {"<circle cx=\"{XM}\" cy=\"{YM}\" r=\"5\" fill=\"#fff\" stroke=\"#1f5fd6\" "
               "stroke-width=\"2\"/>",
               "start P\u209b"}},
             &legend_end);
  const Vec2 origin(lx + 50, legend_end + 70);
  for (const auto& [axis, name] :
       {std::pair{Vec3::UnitX(), "X"}, {Vec3::UnitY(), "Y"}, {Vec3::UnitZ(), "Z"}}) {
    const Vec2 q = v.cam.project(axis);
    const Vec2 tip = origin + 36.0 * Vec2(q.x(), -q.y());
    if ((tip - origin).norm() > 4) o += arrow(origin, tip, "#444", 1.4);
    o += text(tip.x() + 3 * (q.x() >= 0 ? 1 : -3), tip.y() + (q.y() >= 0 ? -3 : 12), name, "small");
  }
  return o;
}

}  // namespace

std::string drape_svg(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const render::ShearScale scale = render::shear_scale(r);
  const std::vector<Segment3> boundary = free_boundary(ctx.surface, kBoundaryPieces);
  View v{Camera::from(ctx.options.view), {}};
  v.frame = Frame::fit(scene_box(r, boundary, v.cam));
  const Vec3 view = ctx.options.view;
  const TitleBlock tb =
      title_over(v.frame,
                 "3D fitting (orthographic, view (" + fixed_text(view.x(), 3) + ", " +
                     fixed_text(view.y(), 3) + ", " + fixed_text(view.z(), 3) + "))",
                 source_line(ctx) + "; " + std::to_string(r.metrics.nodes.mapped) +
                     " mapped nodes, " + shear_summary(ctx));
  std::vector<Prim> prims;
  add_cells(prims, r, detail::mapped_cells(r), scale, v, CellEdges::kOwnColour);
  add_net(prims, r, boundary, std::min(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp), v);
  std::string o = svg_open(v.frame.canvas_width(), v.frame.canvas_height(), "plyfit 3D fitting");
  o += tb.svg;
  o += "<g id=\"scene\">\n" + draw_sorted(prims) + "</g>\n";
  o += start_marker(r, v);
  o += drape_legend(scale, ctx.options.warn_shear, v);
  o += "</svg>\n";
  return o;
}

}  // namespace plyfit::exporters::svg
