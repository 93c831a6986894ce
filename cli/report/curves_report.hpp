#pragma once
// What plyfit info FILE --curves prints: the curves of a STEP or IGES file (for ply boundaries
// and seed curves), each with its index, name, kind, length, closed flag and end points.

#include <plyfit/importers/importers.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace plyfit::cli {

/// The curves as a table, or (json) as JSON.
void print_curves(const std::string& path, const std::vector<importers::FileCurve>& curves,
                  bool json, std::ostream& os);

}  // namespace plyfit::cli
