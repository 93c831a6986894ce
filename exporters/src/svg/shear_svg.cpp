// shear.svg: the thread-angle distribution as a height field over the plane development (paper
// Fig. 15): height = gamma from 0 to pi, drawn in an oblique parallel projection (x and height
// true, the ply's y axis receding at kObliqueAngle, foreshortened to kObliqueScale) with depth
// sorting.
#include <plyfit/kernel/flat_pattern.hpp>

#include "svg/draw.hpp"
#include "svg/pictures.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace plyfit::exporters::svg {

namespace {

using detail::kPi;
using detail::kRadToDeg;

constexpr double kObliqueAngle = 40.0;  // degrees: the receding y axis on the page
constexpr double kObliqueScale = 0.75;  // the receding y axis is foreshortened to this
constexpr double kHeightRel = 0.45;     // height of pi relative to the plane development's size
constexpr double kCellEdgePx = 0.35;    // the cells' edges (px)

// The oblique projection of (x, y, gamma) onto the page (y up), with its depth along the
// projector (ca, -1, sa), and the frame it is drawn in.
struct Oblique {
  double hscale = 1.0;  // mm of height per radian
  double ca = 0.0, sa = 0.0;
  Frame frame;
  Vec2 project(const Vec2& p, double gamma) const {
    return Vec2(p.x() + ca * p.y(), hscale * gamma + sa * p.y());
  }
  double depth(const Vec2& p, double gamma) const {
    return ca * p.x() - p.y() + sa * hscale * gamma;
  }
  Vec2 map(const Vec2& p, double gamma) const { return frame.map(project(p, gamma)); }
};

// The plane development's box: the mapped nodes and the exact outline.
Box2 plane_box(const ExportContext& ctx) {
  Box2 plane;
  plane.add_mapped(ctx.result);
  if (ctx.flat) plane.add(ctx.flat->outline);
  if (plane.empty()) plane.add(Vec2::Zero());
  return plane;
}

// The projection scaled to the plane, and its frame around the box from 0 to pi high.
Oblique oblique_view(const ExportContext& ctx, const Box2& plane) {
  const double ext = std::max({plane.size().x(), plane.size().y(), ctx.problem.ply.d_weft});
  Oblique v;
  v.hscale = kHeightRel * ext / kPi;
  v.ca = kObliqueScale * std::cos(kObliqueAngle / kRadToDeg);
  v.sa = kObliqueScale * std::sin(kObliqueAngle / kRadToDeg);
  Box2 box;
  for (const double g : {0.0, kPi})
    for (const Vec2& c :
         {plane.lo, plane.hi, Vec2(plane.lo.x(), plane.hi.y()), Vec2(plane.hi.x(), plane.lo.y())})
      box.add(v.project(c, g));
  v.frame = Frame::fit(padded(box, 0.05 * ext));
  return v;
}

// The vertical axis at the back-left corner of the plane, 0 .. pi, with its ticks.
std::string gamma_axis(const Box2& plane, const Oblique& v) {
  const Vec2 axis_foot(plane.lo.x(), plane.hi.y());
  const Vec2 a = v.map(axis_foot, 0.0), b = v.map(axis_foot, kPi);
  std::string o = line(a, b, "stroke=\"#333\" stroke-width=\"1.2\"");
  const char* names[] = {"0\u00b0", "45\u00b0", "90\u00b0", "135\u00b0", "180\u00b0"};
  for (int k = 0; k <= 4; ++k) {
    const Vec2 t = v.map(axis_foot, kPi * k / 4.0);
    o += line({t.x() - 6, t.y()}, t, "stroke=\"#333\" stroke-width=\"1.2\"");
    o += text(t.x() - 10, t.y() + 4, names[k], "sub", " text-anchor=\"end\"");
  }
  return o + text(b.x() + 6, b.y() - 6, "\u03b3", "title");
}

// Under everything: the plane development on the floor, the frame at 0 and pi/2, the axis.
std::string floor_layer(const ExportContext& ctx, const Box2& plane, const Oblique& v) {
  std::string o = "<g id=\"floor\">\n";
  if (ctx.flat) {
    std::vector<std::vector<Vec2>> loops;
    for (const auto& l : ctx.flat->outline) {
      std::vector<Vec2> q;
      for (const Vec2& p : l.points) q.push_back(v.map(p, 0.0));
      loops.push_back(std::move(q));
    }
    o += "<path d=\"" + loops_path(loops) +
         "\" fill=\"#ececec\" fill-rule=\"evenodd\" stroke=\"#e8112d\" stroke-width=\"1.2\"/>\n";
  }
  const std::vector<Vec2> corners = {
      plane.lo, {plane.hi.x(), plane.lo.y()}, plane.hi, {plane.lo.x(), plane.hi.y()}};
  for (const double g : {0.0, kPi / 2}) {
    std::vector<Vec2> q;
    for (const Vec2& c : corners) q.push_back(v.map(c, g));
    o += polygon(q, "",
                 std::string(" fill=\"none\" stroke=\"#999\" stroke-width=\"0.8\"") +
                     (g > 0 ? " stroke-dasharray=\"5,4\"" : ""));
  }
  for (const Vec2& c : corners)
    o += line(v.map(c, 0.0), v.map(c, kPi / 2),
              "stroke=\"#bbb\" stroke-width=\"0.8\" stroke-dasharray=\"2,3\"");
  return o + gamma_axis(plane, v) + "</g>\n";
}

bool with_angle(const DrapeNode& n) {
  return n.mapped() && !n.id.is_path_only() && n.has(DrapeNode::kHasAngle);
}

// The height field: cells of regular nodes with a thread angle (a quad, or the triangle of
// three corners), coloured by shear, and the nodes over them.
std::vector<Prim> height_field(const ExportContext& ctx, const render::ShearScale& scale,
                               const Oblique& v) {
  const DrapeResult& r = ctx.result;
  std::set<std::pair<std::int32_t, std::int32_t>> cells;  // (j, i)
  for (const DrapeNode& n : r.nodes)
    if (with_angle(n))
      for (int a = -1; a <= 0; ++a)
        for (int b = -1; b <= 0; ++b) cells.insert({n.id.j + b, n.id.i + a});
  // The cells' edges (the threads) and the node marks within the cell (px on the page).
  const double d = std::min(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp);
  const render::DrawingScale sc = render::drawing_scale(kPlotSize, d * v.frame.scale, 1.0);
  const std::string edge = px(sc.net_stroke(kCellEdgePx));
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
      pts.push_back(v.map(n->ply, n->thread_angle));
      shear = std::max(shear, detail::node_shear(*n));
      dsum += v.depth(n->ply, n->thread_angle);
    }
    prims.push_back(
        {dsum / static_cast<double>(ring.size()),
         polygon(pts, "cell",
                 " fill=\"" + scale.colour(shear).hex() + "\" stroke=\"#1a1a1a\" stroke-width=\"" +
                     edge + "\" stroke-linejoin=\"round\"")});
  }
  const double node_r = sc.sized(0.06, 0.5, 1.6, render::kNodeMarkMaxRel);
  for (const DrapeNode& n : r.nodes)
    if (with_angle(n))
      prims.push_back({v.depth(n.ply, n.thread_angle) + 0.5 * d,
                       circle(v.map(n.ply, n.thread_angle), node_r, "node")});
  return prims;
}

}  // namespace

std::string shear_svg(const ExportContext& ctx) {
  const render::ShearScale scale = render::shear_scale(ctx.result);
  const Box2 plane = plane_box(ctx);
  Oblique v = oblique_view(ctx, plane);
  const TitleBlock tb = title_over(
      v.frame,
      "Thread-angle distribution (height \u03b3 from 0\u00b0 to 180\u00b0 over the plane "
      "development)",
      source_line(ctx) + "; " + shear_summary(ctx));
  std::string o =
      svg_open(v.frame.canvas_width(), v.frame.canvas_height(), "plyfit thread-angle distribution");
  o += tb.svg;
  o += floor_layer(ctx, plane, v);
  std::vector<Prim> prims = height_field(ctx, scale, v);
  o += "<g id=\"field\">\n" + draw_sorted(prims) + "</g>\n";
  o += legend(v.frame.left + v.frame.width + kMargin, v.frame.top + 10, scale,
              ctx.options.warn_shear,
              {{"<rect x=\"{X}\" y=\"{Y}\" width=\"24\" height=\"12\" fill=\"#ececec\" "
                "stroke=\"#e8112d\" stroke-width=\"1.2\"/>",
                "plane development"},
               {sym_line("#999999", 0.8, "5,4"), "\u03b3 = 90\u00b0 (no shear)"}});
  o += "</svg>\n";
  return o;
}

}  // namespace plyfit::exporters::svg
