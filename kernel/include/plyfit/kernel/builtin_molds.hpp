#pragma once
/// \file Built-in molds: exact analytic faces by name, so that a drape needs no file, and
/// built-in shells: several such faces sewn along shared edges.
/// All have the outward (convex-side) normal; lengths in millimetres, angles in degrees.

#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>

#include <map>
#include <string>
#include <vector>

namespace plyfit {

/// One parameter of a built-in mold.
struct BuiltinParam {
  std::string key;
  double value;  ///< default
  std::string meaning;
};

/// A built-in mold's description (for help texts and the README).
struct BuiltinInfo {
  std::string name;
  std::string placement;  ///< where it sits and which way its normal points
  std::vector<BuiltinParam> params;
};

/// Every built-in mold.
const std::vector<BuiltinInfo>& builtin_molds();

/// A built-in face with its trim loops also as exact curves (what a mold file stores).
struct BuiltinFace {
  /// The face; its loops are polylines through points of exact_loops whose chords lie within
  /// tol.trim_chord_rel * (face size) of the exact curves on the surface (3D).
  FaceData face;
  /// The trim loops as exact NURBS curves in (u, v), end to end in each loop, in the order of
  /// face.loops (empty for an untrimmed face). The first loop is the outer one: a real trim,
  /// or the border of the domain when natural_outer (a face with holes only).
  std::vector<std::vector<NurbsCurveData2>> exact_loops;
  /// True when the outer loop is the domain's border (as a mold file bounds a face by its
  /// surface's natural boundary, with seams and collapsed edges).
  bool natural_outer = true;
};

/// The face of built-in mold `name` with `params` overriding the defaults, with its exact
/// trims. Errors name an unknown mold, an unknown key or an invalid value (a hole or trim that
/// does not fit inside the face too).
Result<BuiltinFace> builtin_face(const std::string& name,
                                 const std::map<std::string, double>& params,
                                 const Tolerances& tol = {});

/// The face of built-in mold `name` (builtin_face().face).
Result<FaceData> builtin_mold(const std::string& name, const std::map<std::string, double>& params);

/// Parses "NAME[:key=value,...]" (the part after "builtin:") into name and parameters.
Result<std::pair<std::string, std::map<std::string, double>>> parse_builtin_spec(
    const std::string& spec);

// ---- shells ----

/// Every built-in shell.
const std::vector<BuiltinInfo>& builtin_shells();
/// True when `name` is a built-in shell.
bool is_builtin_shell(const std::string& name);
/// The shell of built-in `name` with `params` overriding the defaults. Errors name an unknown
/// shell, an unknown key or an invalid value.
Result<ShellData> builtin_shell(const std::string& name,
                                const std::map<std::string, double>& params);

}  // namespace plyfit
