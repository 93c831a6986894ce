#pragma once
// How large a drawing's annotation and strokes are, in the drawing's own units (millimetres):
// text, legends, scale bars, markers and arrows grow with the drawing so that they read the
// same on a 1 mm part and on a 20 m one, never smaller than their size on paper; the strokes of
// the net stay thinner than its cells. Every picture (flat.svg, drape.svg, shear.svg, flat.dxf
// and any cut drawing) sizes its annotation here.

#include <algorithm>

namespace plyfit::exporters::render {

/// Annotation is designed in "px" and drawn as if the drawing's larger side were kViewPx px
/// across (the pixel pictures' plot size); one px is never less than kMinUnitMm on paper (a CSS
/// px, 1/96 inch), the annotation's size when the drawing is printed 1:1.
constexpr double kViewPx = 760.0;
constexpr double kMinUnitMm = 25.4 / 96.0;
/// Marks drawn on the drawing itself (the start marker, the sweep arrows) are sized as if the
/// drawing were at least kMinMarkViewPx px across, so that on a part smaller than that on
/// paper they do not hide it.
constexpr double kMinMarkViewPx = 100.0;
/// Strokes of the net (threads, the thread grid) are at most kNetStrokeMaxRel of a cell, lines
/// along the cells' edges (the staircase, the outline, shear-warning frames) kEdgeStrokeMaxRel,
/// node marks at most kNodeMarkMaxRel of a cell in radius (the base path's kPathMarkMaxRel).
constexpr double kNetStrokeMaxRel = 0.2;
constexpr double kEdgeStrokeMaxRel = 0.5;
constexpr double kNodeMarkMaxRel = 0.2;
constexpr double kPathMarkMaxRel = 0.5;
/// Text height of a drawing's labels (flat.dxf's label block, a cut drawing's ply labels) as a
/// fraction of the drawing's extent: at most kLabelTextRel; the origin marker's radius is
/// kMarkerRel of it.
constexpr double kLabelTextRel = 1.0 / 40.0;
constexpr double kMarkerRel = 1.0 / 80.0;

/// The sizes of one drawing: `unit` drawing units per px of annotation, `mark_unit` per px of
/// the marks on the drawing, `cell` the net's smaller thread spacing (drawing units).
struct DrawingScale {
  double unit = kMinUnitMm;
  double mark_unit = kMinUnitMm;
  double cell = 1.0;
  /// An annotation length of `v` px.
  double px(double v) const { return v * unit; }
  /// A stroke of the net: `want_px` px, at most kNetStrokeMaxRel of a cell.
  double net_stroke(double want_px) const {
    return std::min(want_px * unit, kNetStrokeMaxRel * cell);
  }
  /// A line along the cells' edges: `want_px` px, at most kEdgeStrokeMaxRel of a cell.
  double edge_stroke(double want_px) const {
    return std::min(want_px * unit, kEdgeStrokeMaxRel * cell);
  }
  /// A size (a stroke, a mark's radius): `rel` of a cell within [lo_px, hi_px] px, at most
  /// `max_rel` of a cell.
  double sized(double rel, double lo_px, double hi_px, double max_rel) const {
    return std::min(std::clamp(rel * cell, lo_px * unit, hi_px * unit), max_rel * cell);
  }
};

/// The scale of a drawing of larger side `extent` and cell `cell` (drawing units) whose unit is
/// `min_unit` drawing units per px or more (kMinUnitMm for a drawing in mm printed 1:1).
inline DrawingScale drawing_scale(double extent, double cell, double min_unit = kMinUnitMm) {
  const double unit = extent > 0 ? std::max(min_unit, extent / kViewPx) : min_unit;
  const double mark_unit = extent > 0 ? std::min(unit, extent / kMinMarkViewPx) : unit;
  return {unit, mark_unit, cell > 0 ? cell : extent};
}

/// The text height of a drawing's labels: kLabelTextRel of its extent, at least `min_h`.
inline double label_text_height(double extent, double min_h = 0.0) {
  return std::max(kLabelTextRel * extent, min_h);
}

}  // namespace plyfit::exporters::render
