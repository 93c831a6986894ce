#pragma once
// The readers of the OpenCASCADE module: each format is one file defining one open_*()
// function, listed once in occt_module_entry.cpp (and once, with its extensions, in the
// registry: registry.cpp).

#include <plyfit/importers/importers.hpp>

#include <memory>
#include <string>
#include <vector>

namespace plyfit::importers {

/// Opens a STEP file (step_importer.cpp).
Result<std::unique_ptr<MoldFile>> open_step(const std::string& path, const ImportOptions& options);
/// Opens an IGES file (iges_importer.cpp).
Result<std::unique_ptr<MoldFile>> open_iges(const std::string& path, const ImportOptions& options);
/// Reads the curves of a STEP file (step_importer.cpp).
Result<std::vector<FileCurve>> curves_step(const std::string& path, const ImportOptions& options);
/// Reads the curves of an IGES file (iges_importer.cpp).
Result<std::vector<FileCurve>> curves_iges(const std::string& path, const ImportOptions& options);

}  // namespace plyfit::importers
