#pragma once
/// \file What a mold file holds, as listed before any face is converted.

#include <plyfit/kernel/types.hpp>

#include <string>
#include <vector>

namespace plyfit {

/// One face of a mold, described without converting its surface.
struct FaceInfo {
  int index = 0;                   ///< stable index (see the importers' documentation)
  std::string name;                ///< name or label from the file, may be empty
  std::string kind;                ///< original surface kind: bspline, bezier, plane, cylinder, ...
  int degree_u = 0, degree_v = 0;  ///< degrees (0 when the kind has none, e.g. a plane)
  int poles_u = 0, poles_v = 0;    ///< pole counts (0 when the kind has none)
  bool rational = false;
  bool trimmed = false;   ///< bounded by trim loops other than its natural boundary
  int holes = 0;          ///< inner loops
  bool reversed = false;  ///< the face's orientation reverses its surface normal
  double area = 0.0;      ///< area, mm^2 (0 when not measured)
  /// False for a face whose area could not be measured (an invalid face: its boundary does not
  /// bound a region of its surface that an integration within its work cap can measure).
  bool area_measured = true;
  BBox3 bbox;  ///< bounding box, mm
};

/// A mold file's content: its faces and where they come from.
struct Mold {
  std::string source;  ///< file path, or "builtin:NAME..." for a built-in mold
  std::string format;  ///< importer key (step, iges) or "builtin"
  std::string schema;  ///< file schema / flavour (e.g. AUTOMOTIVE_DESIGN, IGES 5.3)
  std::string unit;    ///< the file's length unit; geometry is converted to millimetres
  std::vector<FaceInfo> faces;
  std::vector<std::string> warnings;  ///< reader warnings, summarised (never printed raw)
};

}  // namespace plyfit
