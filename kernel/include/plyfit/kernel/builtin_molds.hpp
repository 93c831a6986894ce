#pragma once
/// \file Built-in molds: exact analytic faces by name, so that a drape needs no file.
/// All have the outward (convex-side) normal; lengths in millimetres, angles in degrees.

#include <plyfit/kernel/face.hpp>
#include <plyfit/kernel/result.hpp>

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

/// The face of built-in mold `name` with `params` overriding the defaults. Errors name an
/// unknown mold, an unknown key or an invalid value.
Result<FaceData> builtin_mold(const std::string& name, const std::map<std::string, double>& params);

/// Parses "NAME[:key=value,...]" (the part after "builtin:") into name and parameters.
Result<std::pair<std::string, std::map<std::string, double>>> parse_builtin_spec(
    const std::string& spec);

}  // namespace plyfit
