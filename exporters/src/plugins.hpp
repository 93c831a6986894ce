#pragma once
// Writer plugins: each format is one file defining one make_*_exporter() function, listed
// once in registry.cpp.

#include <plyfit/exporters/exporters.hpp>

namespace plyfit::exporters {

/// report.json (json_exporter.cpp).
Exporter make_json_exporter();
/// flat.dxf (dxf_exporter.cpp).
Exporter make_dxf_exporter();
/// net.step (step_exporter.cpp).
Exporter make_step_exporter();
/// flat.svg, drape.svg, shear.svg (svg_exporter.cpp).
Exporter make_svg_exporter();
/// net.vtk (vtk_exporter.cpp).
Exporter make_vtk_exporter();

}  // namespace plyfit::exporters
