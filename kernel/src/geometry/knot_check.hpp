#pragma once
// Validation shared by NURBS curves and surfaces.

#include <plyfit/kernel/result.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace plyfit::detail {

/// Checks a flat knot vector for `count` poles of `degree`; `what` names the direction
/// ("u", "v" or "curve") in the message.
inline Status check_knots(const std::vector<double>& knots, int count, int degree,
                          const std::string& what) {
  if (degree < 1 || degree > 25)
    return Error{"degree in " + what + " is " + std::to_string(degree) + ", must be 1..25"};
  if (count < degree + 1)
    return Error{"need at least degree + 1 = " + std::to_string(degree + 1) + " poles in " + what +
                 ", got " + std::to_string(count)};
  const size_t expected = static_cast<size_t>(count) + degree + 1;
  if (knots.size() != expected)
    return Error{"knot count in " + what + " is " + std::to_string(knots.size()) +
                 ", must be poles + degree + 1 = " + std::to_string(expected)};
  int mult = 1;
  for (size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i]))
      return Error{"knot " + std::to_string(i) + " in " + what + " is not finite"};
    if (i == 0) continue;
    if (knots[i] < knots[i - 1])
      return Error{"knots in " + what + " decrease at index " + std::to_string(i)};
    mult = (knots[i] == knots[i - 1]) ? mult + 1 : 1;
    if (mult > degree + 1)
      return Error{"knot multiplicity in " + what + " exceeds degree + 1 at index " +
                   std::to_string(i)};
  }
  if (!(knots[degree] < knots[count])) return Error{"empty parameter domain in " + what};
  return ok_status();
}

}  // namespace plyfit::detail
