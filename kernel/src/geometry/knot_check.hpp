#pragma once
// Validation shared by NURBS curves and surfaces.

#include <plyfit/kernel/result.hpp>

#include "geometry/bspline_basis.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace plyfit::detail {

/// Checks a flat knot vector for `count` poles of `degree`; `what` names the direction ("u",
/// "v" or "curve"), the first value of every error.
inline Status check_knots(const std::vector<double>& knots, int count, int degree,
                          const std::string& what) {
  if (degree < 1 || degree > kMaxDegree)
    return Error{
        ErrorCode::kDegreeRange, {}, {what, std::int64_t{degree}, std::int64_t{kMaxDegree}}};
  if (count < degree + 1)
    return Error{
        ErrorCode::kTooFewPoles, {}, {what, std::int64_t{degree} + 1, std::int64_t{count}}};
  const std::size_t expected = static_cast<std::size_t>(count) + degree + 1;
  if (knots.size() != expected)
    return Error{
        ErrorCode::kKnotCount,
        {},
        {what, static_cast<std::int64_t>(knots.size()), static_cast<std::int64_t>(expected)}};
  int mult = 1;
  for (std::size_t i = 0; i < knots.size(); ++i) {
    const auto at = static_cast<std::int64_t>(i);
    if (!std::isfinite(knots[i])) return Error{ErrorCode::kKnotNotFinite, {}, {what, at}};
    if (i == 0) continue;
    if (knots[i] < knots[i - 1]) return Error{ErrorCode::kKnotsDecrease, {}, {what, at}};
    mult = (knots[i] == knots[i - 1]) ? mult + 1 : 1;
    if (mult > degree + 1) return Error{ErrorCode::kKnotMultiplicity, {}, {what, at}};
  }
  if (!(knots[degree] < knots[count])) return Error{ErrorCode::kEmptyDomain, {}, {what}};
  return ok_status();
}

}  // namespace plyfit::detail
