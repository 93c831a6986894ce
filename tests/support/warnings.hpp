#pragma once
// Finding a run's warnings by their codes in tests.

#include <plyfit/kernel/result.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace plyfit::support {

/// The warnings of `warnings` with `code`, in order.
inline std::vector<Warning> with_code(const std::vector<Warning>& warnings, WarningCode code) {
  std::vector<Warning> out;
  for (const Warning& w : warnings)
    if (w.code == code) out.push_back(w);
  return out;
}

/// Value k of a warning as a number (a count or a measure); NaN when it has none.
inline double value(const Warning& w, std::size_t k) {
  if (k < w.values.size()) {
    if (const auto* x = std::get_if<double>(&w.values[k])) return *x;
    if (const auto* i = std::get_if<std::int64_t>(&w.values[k])) return static_cast<double>(*i);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace plyfit::support
