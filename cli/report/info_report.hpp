#pragma once
// What plyfit info prints: a mold file's faces as a table or JSON, and one face's start (a
// point near its middle, its normal, drape flags from there) as text or JSON.

#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/optimize.hpp>

#include <iosfwd>
#include <string>

namespace plyfit::cli {

/// The faces of a mold file, one line each, then a summary and the warnings.
void print_listing(const Mold& m, std::ostream& os);
/// The same as JSON text (plyfit info --json).
std::string listing_json(const Mold& m);

/// A face's start (plyfit info --face N), as text or (json) JSON.
void print_face_start(const std::string& path, int index, const FaceInfo& info, const FaceStart& s,
                      bool json, std::ostream& os);

}  // namespace plyfit::cli
