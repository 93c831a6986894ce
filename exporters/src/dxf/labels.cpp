#include "dxf/labels.hpp"

#include "render/text.hpp"

#include <algorithm>

namespace plyfit::exporters::dxf {

namespace {
// The label block, in units of the text height h: line pitch, the widest a character of the
// Standard style's font is drawn (AutoCAD's txt and LibreCAD's fonts draw capitals and digits
// narrower than this, so the block estimate is generous), the grain arrow's column ("WARP"
// rotated, the shaft, a gap before the text) and the depth below the last baseline.
constexpr double kLinePitch = 1.6;
constexpr double kCharWidth = 1.0;
constexpr double kArrowColumn = 3.0;
constexpr double kDescent = 0.4;
}  // namespace

render::BlockShape label_shape(const std::vector<std::string>& lines) {
  // Characters as the file writes them (one byte each, a \U+XXXX escape seven): a reader that
  // shows the escape, or measures it so (ezdxf), still finds the line inside the outline.
  std::size_t chars = 0;
  for (const auto& l : lines) chars = std::max(chars, dxf_text(l).size());
  return {kArrowColumn + kCharWidth * static_cast<double>(chars),
          1.0 + kLinePitch * static_cast<double>(lines.size() - 1) + kDescent};
}

void add_labels(Writer& e, const std::vector<std::string>& lines, const render::BlockShape& shape,
                const render::BlockPlace& place, const char* grain_layer, const char* label_layer) {
  const double h = place.h;
  const Vec2 top_left = place.top_left;
  const double block_h = shape.height_at(h);
  const Vec2 foot = top_left + Vec2(2.0 * h, -block_h);
  const Vec2 tip = top_left + Vec2(2.0 * h, 0.0);
  const double head = std::min(1.2 * h, 0.3 * block_h), head_half = 0.45 * h;
  e.line(grain_layer, foot, tip);
  e.line(grain_layer, tip, tip + Vec2(head_half, -head));
  e.line(grain_layer, tip, tip + Vec2(-head_half, -head));
  e.text(grain_layer, foot + Vec2(-0.4 * h, 0.1 * block_h), h, "WARP", 90.0);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const Vec2 at =
        top_left + Vec2(kArrowColumn * h, -h * (1.0 + kLinePitch * static_cast<double>(k)));
    e.text(label_layer, at, h, lines[k]);
  }
}

}  // namespace plyfit::exporters::dxf
