#pragma once
// The importers, one file per format, and the forwarding to the OpenCASCADE module they share.

#include <plyfit/importers/importers.hpp>

#include <string>
#include <vector>

namespace plyfit::importers {

/// An importer whose reader (`key`) is in the OpenCASCADE module, loaded on the first open.
Importer occt_importer(std::string key, std::vector<std::string> extensions,
                       std::string description);

/// STEP (step_importer.cpp).
Importer step_importer();
/// IGES (iges_importer.cpp).
Importer iges_importer();

}  // namespace plyfit::importers
