#pragma once
// Importer plugins: each format is one file defining one make_*_importer() function, listed
// once in registry.cpp.

#include <plyfit/importers/importers.hpp>

namespace plyfit::importers {

Importer make_step_importer();
Importer make_iges_importer();

}  // namespace plyfit::importers
