#pragma once
// Curves from a file, for a ply's boundary and seed curve: a CSV of 3D points, one closed loop
// per block, or a STEP/IGES file's curves, with `FILE:NAMES|INDICES` picking some.

#include <plyfit/kernel/boundary.hpp>
#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::cli {

/// A curve file as given: its path and the curves picked (names or indices from 0; empty:
/// every curve).
struct CurveFileSpec {
  std::string path;
  std::vector<std::string> pick;
};

/// Splits `FILE[:NAMES|INDICES]` (comma list): the text after the last ':' picks curves
/// unless the whole text names an existing file.
CurveFileSpec parse_curve_spec(const std::string& text);

/// The text back (`--dump-scene`).
std::string to_string(const CurveFileSpec& spec);

/// True for a STEP or IGES file (by extension), whose curves the importers read.
bool is_cad_curve_file(const std::string& path);

/// The curves of the file, each named for errors ("FILE line N", the line of its first point;
/// "FILE curve N 'NAME'" for a STEP/IGES curve, picked by index or by its name in the file), the
/// picked ones in the order picked. A CSV block is a closed curve. Errors (blaming the file): it
/// cannot be opened (kCurveFileCannotOpen), a line is not a point (kCurveFileSyntax: its number
/// and text), an unknown type (kCurveFileFormat), a STEP/IGES file that does not read
/// (kCurveFileUnreadable, the reader's error as cause) or holds no curve (kCurveFileNoCurves),
/// a pick that names no curve (kCurveNotFound), no curve at all (kBoundaryEmpty).
Result<std::vector<BoundaryCurve>> read_curves(const CurveFileSpec& spec);

}  // namespace plyfit::cli
