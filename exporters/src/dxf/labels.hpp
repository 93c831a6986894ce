#pragma once
// The label block of a DXF drawing: text lines beside a grain arrow (the warp, +y), as
// flat.dxf and the laminate's cut.dxf draw them.

#include "dxf/writer.hpp"
#include "render/label_placement.hpp"

#include <string>
#include <vector>

namespace plyfit::exporters::dxf {

/// The block's size per unit of text height: the arrow's column and the longest line wide,
/// the lines high.
render::BlockShape label_shape(const std::vector<std::string>& lines);

/// The grain arrow up the block's left column (the head at the top, "WARP" along the shaft) on
/// `grain_layer`, and the lines beside it on `label_layer`.
void add_labels(Writer& e, const std::vector<std::string>& lines, const render::BlockShape& shape,
                const render::BlockPlace& place, const char* grain_layer, const char* label_layer);

}  // namespace plyfit::exporters::dxf
