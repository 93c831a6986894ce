#pragma once
// The pictures of svg_exporter.cpp, each a whole SVG file.

#include <plyfit/exporters/exporters.hpp>

#include <string>

namespace plyfit::exporters::svg {

/// flat.svg: the plane development, 1:1 in millimetres (flat_svg.cpp).
std::string flat_svg(const ExportContext& ctx);
/// drape.svg: the 3D fitting in an orthographic view (drape_svg.cpp).
std::string drape_svg(const ExportContext& ctx);
/// shear.svg: the thread-angle distribution as a height field (shear_svg.cpp).
std::string shear_svg(const ExportContext& ctx);
/// view.svg: a small static 3D view for the ply book (view_svg.cpp).
std::string view_svg(const ExportContext& ctx);

}  // namespace plyfit::exporters::svg
