#pragma once
// The SVG pictures' drawing: elements with coordinates written with two decimals, the frame
// that maps a drawing into the picture, the title block, the legend, depth-sorted primitives.

#include <plyfit/exporters/exporters.hpp>

#include "net_util.hpp"
#include "render/colour_scale.hpp"
#include "render/drawing_scale.hpp"

#include <string>
#include <utility>
#include <vector>

namespace plyfit::exporters::svg {

using detail::Box2;

constexpr double kPlotSize = render::kViewPx;  // px: the longer side of the drawing
constexpr double kMargin = 40.0;               // px around the drawing
constexpr double kLegendWidth = 190.0;
constexpr double kLegendHeight = 520.0;
/// Font sizes (px) of the text classes title, sub and small; a text's box is estimated with
/// characters kCharEm wide (DejaVu Sans/Verdana's widest average), kAscentEm above the
/// baseline and kDescentEm below.
constexpr double kTitleEm = 17.0, kSubEm = 12.0, kSmallEm = 11.0;
constexpr double kCharEm = 0.62, kAscentEm = 0.8, kDescentEm = 0.25;
/// The box (px) of `s` at font size `em`: width, height.
Vec2 text_size(const std::string& s, double em);
/// The start's label, "P" with a subscript "s", its box's top-left corner at `top_left` (px),
/// in `colour`; kStartLabelSize is its box (px).
std::string start_label(const Vec2& top_left, const std::string& colour);
extern const Vec2 kStartLabelSize;

/// A coordinate or length: two decimals, or as many as a WrittenDecimals in scope says.
std::string px(double v);
/// While it lives, px() writes enough decimals to resolve `resolution` (at least two): a
/// drawing of small cells in mm keeps them exact to the digits it needs (one per thread).
class WrittenDecimals {
 public:
  explicit WrittenDecimals(double resolution);
  ~WrittenDecimals();
  WrittenDecimals(const WrittenDecimals&) = delete;
  WrittenDecimals& operator=(const WrittenDecimals&) = delete;

 private:
  int saved_;
};
/// "x,y".
std::string pt(const Vec2& p);
/// Points for a polygon's points attribute.
std::string points_attr(const std::vector<Vec2>& pts);
/// Appends the segment a-b to path data `d` ("Mx,yLx,y").
void add_segment(std::string& d, const Vec2& a, const Vec2& b);
/// A closed path of loops (for fill-rule evenodd).
std::string loops_path(const std::vector<std::vector<Vec2>>& loops);

/// <text> of class `cls` at (x, y); `extra` attributes follow the class.
std::string text(double x, double y, const std::string& s, const std::string& cls,
                 const std::string& extra = "");
/// <line> from a to b with `style` attributes.
std::string line(const Vec2& a, const Vec2& b, const std::string& style);
/// <circle> of class `cls` (none when empty); `extra` attributes follow the radius.
std::string circle(const Vec2& c, double r, const std::string& cls, const std::string& extra = "");
/// <polygon> of class `cls` (none when empty); `extra` attributes follow the points.
std::string polygon(const std::vector<Vec2>& pts, const std::string& cls, const std::string& extra);
/// An arrow from a to b: a line and a filled head.
std::string arrow(const Vec2& a, const Vec2& b, const std::string& colour, double width);
/// Annotation drawn in px at a point of a picture whose user units are `unit` per px.
std::string at_px(const Vec2& p, double unit, const std::string& svg);

/// The svg element: `w` x `h` user units, in px (pixel pictures) or in mm (flat.svg, 1:1).
std::string svg_open(double w, double h, const std::string& title, bool mm = false);

/// Maps drawing coordinates (y up) to the picture's user units (y down). Pixel pictures fit
/// the box into kPlotSize; flat.svg draws it at 1 user unit per model unit (mm). Margins,
/// legend and title sizes are in user units (`unit` user units per pixel).
struct Frame {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Ones();
  double scale = 1.0;
  double unit = 1.0;  // user units per px of annotation
  double left = kMargin, top = kMargin;
  double width = 1.0, height = 1.0;  // plot area, user units
  double bottom = 0.0;               // room below the plot area (the scale bar)
  double min_width = 0.0;            // the plot area and the room beside it, at least

  static Frame fit(Box2 box, double fixed_scale = 0.0, double unit = 1.0);
  Vec2 map(const Vec2& p) const {
    return {left + (p.x() - lo.x()) * scale, top + (hi.y() - p.y()) * scale};
  }
  double canvas_width() const {
    return left + std::max(width, min_width) + (kMargin + kLegendWidth) * unit;
  }
  double canvas_height() const {
    return std::max(top + height + bottom + kMargin * unit, top + (kLegendHeight + kMargin) * unit);
  }
};
/// `box` grown by `margin` on every side.
Box2 padded(const Box2& box, double margin);

/// The title and the subtitle, wrapped to `width` px, in px coordinates from the top-left
/// corner of the picture; `height` is the room they take (px).
struct TitleBlock {
  std::string svg;
  double height = 0.0;
};
TitleBlock title_block(const std::string& title, const std::string& sub, double width);
/// The title block across the picture of `f`, whose plot area moves below it; the picture
/// widens to its longest word.
TitleBlock title_over(Frame& f, const std::string& title, const std::string& sub);

/// The subtitle's parts: the ply, material, mold and faces; the shear and thread angles.
std::string source_line(const ExportContext& ctx);
std::string shear_summary(const ExportContext& ctx);

/// A legend entry: a symbol drawn in a 24 x 12 box at ({X}, {Y}) ({XM}, {YM} its middle, {X2}
/// its right side), and its label.
using LegendEntry = std::pair<std::string, std::string>;
/// A line symbol for a legend entry.
std::string sym_line(const std::string& colour, double w, const std::string& dash = "");
/// The legend at (x, y): the shear colour bar from 0 to the scale's top, the warning level
/// `warn`, and the entries; `end_y` receives the last entry's baseline.
std::string legend(double x, double y, const render::ShearScale& scale, double warn,
                   const std::vector<LegendEntry>& entries, double* end_y = nullptr);

/// A primitive of a depth-sorted picture.
struct Prim {
  double depth;  // larger = nearer the viewer
  std::string svg;
};
/// The primitives far first (painter's algorithm; equal depths in their order).
std::string draw_sorted(std::vector<Prim>& prims);

}  // namespace plyfit::exporters::svg
