#pragma once
// The readers of the OpenCASCADE module: each format is one file defining one read_*()
// function (the file read into a shape, with its schema, unit, warnings and entity names),
// listed once in module_entry.cpp (and once, with its extensions, in the registry:
// registry.cpp). Everything after the read (face walk, listing, conversion, curves) is shared.

#include "mold_file.hpp"

#include <string>

namespace plyfit::importers {

/// Reads a STEP file (step_reader.cpp).
Result<occt::ReadOutput> read_step(const std::string& path, occt::Deadline& deadline);
/// Reads an IGES file (iges_reader.cpp).
Result<occt::ReadOutput> read_iges(const std::string& path, occt::Deadline& deadline);

}  // namespace plyfit::importers
