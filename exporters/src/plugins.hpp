#pragma once
// Writer plugins: each format is one file defining one make_*_exporter() function, listed
// once in registry.cpp.

#include <plyfit/exporters/exporters.hpp>

#include <functional>
#include <string>
#include <vector>

namespace plyfit::exporters {

/// One file a writer makes: its name in the output folder and how its bytes are made.
struct OutputFile {
  std::string name;
  std::function<Result<std::string>(const ExportContext&)> content;
};

/// A writer of `files`, in order: each file's bytes are made, then written atomically into the
/// output folder; the first failure stops it (its error names the file).
Exporter file_exporter(std::string key, std::string description, std::vector<OutputFile> files);

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
/// net.glb (glb_exporter.cpp).
Exporter make_glb_exporter();

}  // namespace plyfit::exporters
