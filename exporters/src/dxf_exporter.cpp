// flat.dxf: the flat pattern as ASCII DXF R2000 (AC1015), millimetres ($INSUNITS 4), in ply
// coordinates, for a cutter or a nesting program. The contours to cut are on their own
// layers; everything else is marking (pen or ink) on layers of its own:
//   OUTLINE     closed LWPOLYLINEs: the outer loops of the cut outline, counter-clockwise
//               (FlatPattern::cut: the exact outline without slivers and notches narrower
//               than the minimum width; the exact outline is in report.json)
//   HOLES       closed LWPOLYLINEs: its inner loops (holes), clockwise
//   PIECE_<name> a flat pattern split for the roll (--roll-width): instead of OUTLINE and
//               HOLES, each piece's loops on a layer of its own, with its name and grain arrow
//   SEAMS       LINEs: the seams between the pieces (warp lines x = s clipped to the outline)
//   THREADS     LINEs: the warp (x = i d_weft) and weft (y = j d_warp) grid lines clipped to
//               the outline (even-odd over all loops); only when ExportOptions::dxf_threads
//               (otherwise the layer is not in the file at all)
//   BASEPATH    an open LWPOLYLINE through the mapped base-path nodes, in path order
//   ORIGIN      the start point (POINT and CIRCLE)
//   GRAIN       the grain arrow: the warp direction (+y, the fabric's 0 degree direction, along
//               the roll) as LINEs, with the TEXT "WARP" along it, inside the outline
//   SHEAR_WARN  closed LWPOLYLINEs around the mapped cells whose shear exceeds
//               ExportOptions::warn_shear (cell shear: the largest |90 deg - gamma| over the
//               cell's corners that have a thread angle)
//   DART        open LWPOLYLINEs: each dart's two cut lines (DartResult::line_left and
//               line_right, from the dart's first point to its tip); only with darts
//   LABELS      TEXT inside the outline: ply name, material, ply angle, spacing, outline
//               area, shear, and the mold's file name (never its folder) with the face
// The labels and the arrow form a block centred on the pole of inaccessibility of the outline
// less the base path and the origin marker (the centre of a largest circle inside the outline
// that neither meets, render/label_placement's place_block), as large as fits inside the
// outline clear of both (with a generous width per character) up to a text height of
// render::kLabelTextRel of the pattern (render/drawing_scale.hpp).
//
// Text: the file declares $DWGCODEPAGE ANSI_1252, the code page of R2000 text, and writes
// U+00A0..U+00FF (the degree sign U+00B0 among them) as their single cp1252 bytes, other
// non-ASCII characters as \U+XXXX; it writes no AutoCAD %% control code.
//
// The file carries every table and object AutoCAD requires of R2000 (dxf/document.hpp).
// Numbers are written in their shortest exact decimal form; nothing depends on the clock or on
// hash order, so equal inputs give equal bytes.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/splice.hpp>

#include "dxf/document.hpp"
#include "dxf/labels.hpp"
#include "net_util.hpp"
#include "plugins.hpp"
#include "render/drawing_scale.hpp"
#include "render/label_placement.hpp"
#include "render/text.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters {

namespace {

using detail::Box2;
using render::degrees_text;
using render::fixed_text;

// A pattern split for the roll: each piece's layer is this and its name; the seams' layer.
constexpr const char* kPiecePrefix = "PIECE_";
constexpr const char* kSeamsLayer = "SEAMS";
constexpr int kSeamsColour = 6;  // magenta

// What the drawing covers: the outline, the mapped nodes and the start, and its extent (at
// least one thread spacing).
struct Extents {
  Box2 box;
  double extent = 0.0;
};
Extents drawing_extents(const DrapeResult& r, const PlySpec& spec,
                        const std::vector<OutlineLoop>& loops) {
  Extents e;
  e.box.add(loops);
  e.box.add_mapped(r);
  e.box.add(spec.start);
  e.extent = std::max({e.box.hi.x() - e.box.lo.x(), e.box.hi.y() - e.box.lo.y(),
                       std::max(spec.d_weft, spec.d_warp)});
  return e;
}

// OUTLINE and HOLES: the cut outline's loops.
void add_outline(dxf::Writer& e, const std::vector<OutlineLoop>& loops) {
  for (const auto& l : loops) e.polyline(l.hole ? "HOLES" : "OUTLINE", l.points, true);
}

// THREADS: the grid lines (axis 0: warp threads x = i d_weft; axis 1: weft threads
// y = j d_warp) over the box, clipped to the outline.
void add_thread_grid(dxf::Writer& e, const std::vector<OutlineLoop>& loops, const PlySpec& spec,
                     const Box2& box) {
  for (const int axis : {0, 1}) {
    const double pitch = axis == 0 ? spec.d_weft : spec.d_warp;
    for (auto i = static_cast<long long>(std::ceil(box.lo[axis] / pitch));
         static_cast<double>(i) * pitch <= box.hi[axis]; ++i) {
      const double c = static_cast<double>(i) * pitch;
      for (const auto& [a, b] : detail::clip_line(loops, axis, c)) {
        const Vec2 from = axis == 0 ? Vec2(c, a) : Vec2(a, c);
        const Vec2 to = axis == 0 ? Vec2(c, b) : Vec2(b, c);
        e.line(dxf::kThreadsLayer, from, to);
      }
    }
  }
}

// The base path's ply points, in path order.
std::vector<Vec2> base_path_points(const DrapeResult& r) {
  std::vector<Vec2> path;
  for (const std::uint32_t k : r.base_path) path.push_back(r.nodes[k].ply);
  return path;
}

// BASEPATH, ORIGIN and SHEAR_WARN.
void add_markings(dxf::Writer& e, const ExportContext& ctx, const std::vector<Vec2>& path,
                  double marker) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  e.polyline("BASEPATH", path, false);
  e.dot("ORIGIN", spec.start);
  e.circle("ORIGIN", spec.start, marker);
  for (const auto& c : detail::mapped_cells(r))
    if (c.shear > ctx.options.warn_shear)
      e.polyline("SHEAR_WARN", detail::cell_ply_points(r, c), true);
}

// What the label block keeps clear of: the base path and the origin marker.
render::Obstacles marking_obstacles(const std::vector<Vec2>& path, const Vec2& start,
                                    double marker) {
  render::Obstacles o;
  for (std::size_t k = 1; k < path.size(); ++k) o.segments.emplace_back(path[k - 1], path[k]);
  o.discs.emplace_back(start, marker);
  return o;
}

// The label lines: ply, material, angles, spacing, area, shear and the mold.
std::vector<std::string> label_lines(const ExportContext& ctx) {
  const PlySpec& spec = ctx.problem.ply;
  const double shear_max_deg = ctx.result.metrics.shear_max * detail::kRadToDeg;
  const double lock_deg = ctx.run.lock_angle_deg;
  const std::string material =
      ctx.options.material_label.empty() || ctx.options.material_label == ctx.run.material
          ? ctx.run.material
          : ctx.options.material_label + " (" + ctx.run.material + ")";
  return {
      "PLY: " + ctx.run.ply_name,
      "MATERIAL: " + material,
      "PLY ANGLE: " + degrees_text(ctx.options.ply_angle_deg, 2),
      "SPACING: " + fixed_text(spec.d_weft, 6) + " x " + fixed_text(spec.d_warp, 6) +
          " mm (weft x warp link)",
      "AREA: " + fixed_text(ctx.flat ? ctx.flat->cut_area : 0.0, 3) + " mm\u00b2",
      "SHEAR: max " + degrees_text(shear_max_deg, 2) + ", warning " +
          degrees_text(ctx.options.warn_shear * detail::kRadToDeg, 2) + ", limit " +
          (lock_deg >= 90.0 ? std::string("none") : degrees_text(lock_deg, 2)),
      "MOLD: " + render::mold_label(ctx.run.mold) + " " + render::faces_label(ctx.run.faces),
  };
}

// The layers of a pattern split for the roll: flat.dxf's, SEAMS and one per piece.
std::vector<dxf::Layer> piece_layers(const SplicePlan& plan, bool threads, bool darts) {
  std::vector<dxf::Layer> layers;
  for (const auto& l : dxf::kLayers)
    if ((threads || std::string(l.name) != dxf::kThreadsLayer) &&
        (darts || std::string(l.name) != "DART"))
      layers.push_back({l.name, l.colour});
  layers.push_back({kSeamsLayer, kSeamsColour});
  for (const SplicePiece& p : plan.pieces) layers.push_back({kPiecePrefix + p.name, 7});
  return layers;
}

// Each piece on its own layer, labelled with its name beside its grain arrow, and the seams
// (the warp lines where pieces meet) on SEAMS.
void add_pieces(dxf::Writer& e, const SplicePlan& plan, const std::vector<OutlineLoop>& loops,
                double extent, const Vec2& lo) {
  for (const SplicePiece& p : plan.pieces) {
    const std::string layer = kPiecePrefix + p.name;
    for (const auto& l : p.loops) e.polyline(layer.c_str(), l.points, true);
    const std::vector<std::string> lines = {"PIECE: " + p.name};
    const render::BlockShape shape = dxf::label_shape(lines);
    const render::BlockPlace place =
        render::place_block(p.loops, shape, extent, render::label_text_height(extent), lo);
    dxf::add_labels(e, lines, shape, place, layer.c_str(), layer.c_str());
  }
  for (const Seam& s : plan.seams)
    for (const auto& [a, b] : detail::clip_line(loops, 0, s.x))
      e.line(kSeamsLayer, Vec2(s.x, a), Vec2(s.x, b));
}

std::string build_dxf(const ExportContext& ctx) {
  const std::vector<OutlineLoop> no_loops;
  const std::vector<OutlineLoop>& loops = ctx.flat ? ctx.flat->cut : no_loops;
  Extents ext = drawing_extents(ctx.result, ctx.problem.ply, loops);
  std::vector<dxf::Layer> layers;
  if (ctx.splices)
    layers = piece_layers(*ctx.splices, ctx.options.dxf_threads, !ctx.result.darts.empty());
  // The entities first: their handles set $HANDSEED.
  dxf::Writer e(layers.empty() ? static_cast<unsigned>(dxf::kFirstEntityHandle)
                               : dxf::first_entity_handle(layers));
  if (ctx.splices)
    add_pieces(e, *ctx.splices, loops, ext.extent, ext.box.lo);
  else
    add_outline(e, loops);
  if (ctx.options.dxf_threads && !loops.empty())
    add_thread_grid(e, loops, ctx.problem.ply, ext.box);
  const std::vector<Vec2> path = base_path_points(ctx.result);
  const double marker = render::kMarkerRel * ext.extent;
  add_markings(e, ctx, path, marker);
  for (const DartResult& dart : ctx.result.darts) {
    if (dart.line_left.size() >= 2) e.polyline("DART", dart.line_left, false);
    if (dart.line_right.size() >= 2) e.polyline("DART", dart.line_right, false);
  }
  const std::vector<std::string> lines = label_lines(ctx);
  const render::BlockShape shape = dxf::label_shape(lines);
  const render::BlockPlace place =
      render::place_block(loops, shape, ext.extent, render::label_text_height(ext.extent),
                          ext.box.lo, marking_obstacles(path, ctx.problem.ply.start, marker));
  dxf::add_labels(e, lines, shape, place, "GRAIN", "LABELS");
  ext.box.add(place.top_left);
  ext.box.add(place.top_left + Vec2(shape.width_at(place.h), -shape.height_at(place.h)));
  if (ext.box.empty()) ext.box.add(Vec2::Zero());
  return dxf::document(e, {ext.box.lo, ext.box.hi, place.h, ctx.options.dxf_threads,
                           !ctx.result.darts.empty(), layers});
}

}  // namespace

Exporter make_dxf_exporter() {
  return file_exporter(
      "dxf", "flat.dxf: flat pattern (outline, threads, base path, origin, shear warnings, labels)",
      {{"flat.dxf", build_dxf}});
}

}  // namespace plyfit::exporters
