// view.svg: a small static 3D view of the draped ply, for the ply book to inline beside the
// ply's table row (no title, legend or text: the page has them). The net is seen from a fixed
// oblique direction: kViewTilt off the outward normal at the start, towards the bisector of
// the weft and the warp there, so that both thread directions are foreshortened alike. The
// mapped cells are coloured by shear in drape.svg's scale and shaded as there, in painter's
// order; their edges are the threads (thin, dark), with the base path and the face's free
// boundary. Above kViewMaxCells cells the thread grid's s x s blocks are drawn instead, each
// the convex hull (in ply coordinates) of its cells' corners with their largest shear: the
// edges are then every s-th thread, and the file stays small at any net size.
#include "svg/pictures.hpp"
#include "svg/scene3d.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace plyfit::exporters::svg {

namespace {

constexpr double kViewSize = 360.0;       // px: the longer side of the drawing
constexpr double kViewMarginUnit = 0.25;  // of the pictures' margin: 10 px
constexpr std::size_t kViewMaxCells = 1500;
constexpr double kViewTilt = 35.0 * kDegToRad;
constexpr int kViewBoundaryPieces = 8;
const std::string kEdgeStyle = "stroke=\"#262626\" stroke-width=\"0.3\" stroke-linejoin=\"round\"";
const std::string kPathStyle = "stroke=\"#1f5fd6\" stroke-width=\"1.2\"";
const std::string kBoundaryStyle =
    "stroke=\"#000000\" stroke-width=\"0.9\" stroke-linecap=\"round\"";

// Towards the viewer: kViewTilt from the outward normal at the start towards the bisector of
// the base path's tangent and its normal turn; the isometric (1, 1, 1) without a normal there.
Vec3 view_direction(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const SurfaceNormal sn = ctx.surface.normal(r.start_at);
  if (!sn.ok || !sn.n.allFinite() || !(sn.n.norm() > 0)) return Vec3(1, 1, 1);
  const Vec3 n = sn.n.normalized();
  const Vec3 t = r.base_tangent - r.base_tangent.dot(n) * n;
  if (!t.allFinite() || !(t.norm() > 0)) return n;
  const Vec3 side = (t.normalized() + n.cross(t.normalized())).normalized();
  return std::cos(kViewTilt) * n + std::sin(kViewTilt) * side;
}

std::int32_t floor_div(std::int32_t a, std::int32_t s) {
  return a >= 0 ? a / s : -((-a + s - 1) / s);
}

// The convex hull of `nodes` in ply coordinates, counter-clockwise, collinear points left out
// (Andrew's monotone chain; ties broken by node index: deterministic).
std::vector<std::uint32_t> ply_hull(const DrapeResult& r, std::vector<std::uint32_t> nodes) {
  auto ply = [&](std::uint32_t k) { return r.nodes[k].ply; };
  std::sort(nodes.begin(), nodes.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Vec2 p = ply(a), q = ply(b);
    return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : a < b;
  });
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  if (nodes.size() < 3) return nodes;
  auto turn = [&](std::uint32_t o, std::uint32_t a, std::uint32_t b) {
    const Vec2 u = ply(a) - ply(o), v = ply(b) - ply(o);
    return u.x() * v.y() - u.y() * v.x();
  };
  std::vector<std::uint32_t> hull(2 * nodes.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], nodes[i]) <= 0) --k;
    hull[k++] = nodes[i];
  }
  for (std::size_t i = nodes.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], nodes[i]) <= 0) --k;
    hull[k++] = nodes[i];
  }
  hull.resize(k - 1);
  return hull;
}

// The cells to draw: the mapped cells, or their s x s blocks of the thread grid (s the
// smallest that brings them to kViewMaxCells or fewer), in (j, i) order.
struct ViewCells {
  std::vector<detail::NetCell> cells;
  std::int32_t s = 1;
};
ViewCells view_cells(const DrapeResult& r) {
  std::vector<detail::NetCell> cells = detail::mapped_cells(r);
  if (cells.size() <= kViewMaxCells) return {std::move(cells), 1};
  const auto s = static_cast<std::int32_t>(
      std::ceil(std::sqrt(static_cast<double>(cells.size()) / kViewMaxCells)));
  std::map<std::pair<std::int32_t, std::int32_t>, detail::NetCell> blocks;
  for (const auto& c : cells) {
    detail::NetCell& b = blocks[{floor_div(c.j, s), floor_div(c.i, s)}];
    b.j = floor_div(c.j, s) * s;
    b.i = floor_div(c.i, s) * s;
    b.nodes.insert(b.nodes.end(), c.nodes.begin(), c.nodes.end());
    b.shear = std::max(b.shear, c.shear);
  }
  ViewCells out{{}, s};
  for (auto& [key, b] : blocks) {
    b.nodes = ply_hull(r, std::move(b.nodes));
    if (b.nodes.size() >= 3) out.cells.push_back(std::move(b));
  }
  return out;
}

// The frame of the projected mapped nodes and boundary, kViewSize on its longer side.
Frame view_frame(const DrapeResult& r, const std::vector<Segment3>& boundary, const Camera& cam) {
  const Box2 box = scene_box(r, boundary, cam);
  const double side = std::max(box.size().x(), box.size().y());
  return Frame::fit(box, side > 0 ? kViewSize / side : 1.0, kViewMarginUnit);
}

// The base path and the free boundary, over the cells they border (a depth bias of
// half the drawn cells' size `d`).
void add_lines(std::vector<Prim>& prims, const DrapeResult& r,
               const std::vector<Segment3>& boundary, double d, const View& v) {
  auto segment = [&](const Vec3& a, const Vec3& b, const std::string& style) {
    return Prim{v.cam.depth(0.5 * (a + b)) + 0.5 * d, line(v.map(a), v.map(b), style)};
  };
  for (std::size_t k = 1; k < r.base_path.size(); ++k)
    prims.push_back(
        segment(r.nodes[r.base_path[k - 1]].point, r.nodes[r.base_path[k]].point, kPathStyle));
  for (const auto& [a, b] : boundary) prims.push_back(segment(a, b, kBoundaryStyle));
}

}  // namespace

std::string view_svg(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const std::vector<Segment3> boundary = free_boundary(ctx.surface, kViewBoundaryPieces);
  View v{Camera::from(view_direction(ctx)), {}};
  v.frame = view_frame(r, boundary, v.cam);
  const ViewCells drawn = view_cells(r);
  std::vector<Prim> prims;
  add_cells(prims, r, drawn.cells, render::shear_scale(r), v, CellEdges::kGroupStroke);
  add_lines(prims, r, boundary, drawn.s * std::max(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp),
            v);
  const double w = 2 * v.frame.left + v.frame.width, h = 2 * v.frame.top + v.frame.height;
  std::string o = svg_open(
      w, h,
      "plyfit 3D view" + (ctx.run.ply_name.empty() ? std::string() : ": " + ctx.run.ply_name));
  // No id: the ply book inlines many of these in one page.
  o += "<g " + kEdgeStyle + ">\n" + draw_sorted(prims) + "</g>\n";
  o += "</svg>\n";
  return o;
}

}  // namespace plyfit::exporters::svg
