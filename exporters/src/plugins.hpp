#pragma once
// Writer plugins: each format is one file defining one make_*_exporter() function, listed
// once in registry.cpp.

#include <plyfit/exporters/exporters.hpp>

namespace plyfit::exporters {

Exporter make_json_exporter();

}  // namespace plyfit::exporters
