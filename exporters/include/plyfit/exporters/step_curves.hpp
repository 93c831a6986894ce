#pragma once
/// \file A small native writer of STEP files (ISO 10303-21, AP214) holding named sets of 3D
/// B-spline curves: each set is one product (PRODUCT name = the set's name) whose shape is a
/// geometrically bounded wireframe of its curves, in millimetres. net.step is written with it
/// (sets `weft`, `warp`, `base_path`); OpenCASCADE (XDE, with names) and DRAW read it back.
/// No OpenCASCADE is involved, so writing net.step does not load it.

#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::exporters {

/// One named group of curves: one product of the STEP file.
struct StepCurveSet {
  std::string name;                     ///< product name (e.g. "weft"); any text
  std::vector<NurbsCurveData3> curves;  ///< non-rational B-splines (degree 1 or more)
};

/// The header of a STEP file. The defaults give reproducible bytes.
struct StepFileInfo {
  std::string file_name;                          ///< FILE_NAME name (e.g. "net.step")
  std::string description;                        ///< FILE_DESCRIPTION text
  std::string timestamp = "2000-01-01T00:00:00";  ///< fixed, so that equal inputs give equal bytes
  std::string author = "plyfit";
  std::string organisation = "plyfit";
};

/// A set of polylines through `lines` (degree-1 B-splines with chord-length parameters); a
/// closed polyline ends where it starts (its first point is repeated at the end). Lines of
/// fewer than two points, or with two consecutive points equal, are an error (the kernel's,
/// with the set's name as its `where`).
Result<StepCurveSet> polyline_set(std::string name, const std::vector<std::vector<Vec3>>& lines,
                                  bool closed);

/// The STEP file's text: sets without curves are left out; reals are written in the shortest
/// form that reads back bit for bit. Errors (their `where` names the set): kCurveRational,
/// kCurveInvalid (a curve the kernel refuses, a non-finite pole among them; its error is the
/// cause).
Result<std::string> step_curves_text(const std::vector<StepCurveSet>& sets,
                                     const StepFileInfo& info);

/// Writes step_curves_text() to `path` atomically (temporary file + rename); errors name `path`
/// as their input.
Status write_step_curves(const std::string& path, const std::vector<StepCurveSet>& sets,
                         const StepFileInfo& info);

}  // namespace plyfit::exporters
