// Private to the kernel (kernel/src/molds/): what the built-in molds and shells share: their
// parameters (defaults overridden by the given ones, and the checks of their values, each error
// naming the parameter and the built-in) and a face bounded by its natural boundary.
#pragma once

#include <plyfit/kernel/builtin_molds.hpp>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace plyfit::detail {

/// The parameter values of one built-in: its defaults, then the given ones.
class BuiltinParams {
 public:
  /// The built-in `name` of `list` and its values; `what` names the kind ("mold", "shell") in
  /// errors: an unknown built-in, an unknown key or a value that is not finite.
  static Result<BuiltinParams> resolve(const std::vector<BuiltinInfo>& list,
                                       const std::string& what, const std::string& name,
                                       const std::map<std::string, double>& given);

  const std::string& name() const { return name_; }
  /// The value of parameter k (one of the built-in's).
  double operator[](const char* k) const { return values_.at(k); }
  /// The value as an angle in radians (the parameters give degrees).
  double radians(const char* k) const;

  /// Each of `keys` is > 0.
  Status positive(std::initializer_list<const char*> keys) const;
  /// Parameter k is an angle in (0, 360] degrees.
  Status angle(const char* k) const;
  /// Parameter k lies in [lo, hi].
  Status within(const char* k, double lo, double hi) const;
  /// Parameter k is an integer in [lo, hi].
  Status integer(const char* k, int lo, int hi) const;

 private:
  std::string name_;
  std::map<std::string, double> values_;
};

/// deg in radians, as deg * pi / 180 (the built-ins' faces keep these bits).
inline double radians(double deg) {
  return deg * kPi / 180.0;
}

/// The descriptions of a list of built-ins (MoldEntry or ShellEntry), in its order.
template <class Entry>
std::vector<BuiltinInfo> infos_of(const std::vector<Entry>& entries) {
  std::vector<BuiltinInfo> out;
  for (const Entry& e : entries) out.push_back(e.info);
  return out;
}

/// The corners of the surface's parameter domain, counter-clockwise in (u, v) from (u0, v0).
std::array<Vec2, 4> domain_corners(const NurbsSurfaceData& surface);

/// A built-in mold: its description and parameters, and how its face (and exact trims) are
/// made from the parameter values (the face's name is set already).
struct MoldEntry {
  BuiltinInfo info;
  Status (*make)(const BuiltinParams& v, const Tolerances& tol, BuiltinFace& b);
};

/// Fills b.face.loops from b.exact_loops: polylines whose chords' surface images lie within
/// tol.trim_chord_rel of the trimmed face's size of the exact curves' (trims.cpp).
Status sample_trims(BuiltinFace& b, const Tolerances& tol);

/// The closed polygon through `corners` as degree-1 curves.
std::vector<NurbsCurveData2> polygon_curves(const std::vector<Vec2>& corners);

}  // namespace plyfit::detail
