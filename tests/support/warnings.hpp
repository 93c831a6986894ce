#pragma once
// Finding a run's warnings by their codes in tests.

#include <plyfit/kernel/result.hpp>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

namespace plyfit::support {

/// The warnings of `warnings` with `code`, in order.
inline std::vector<Warning> with_code(const std::vector<Warning>& warnings, WarningCode code) {
  std::vector<Warning> out;
  for (const Warning& w : warnings)
    if (w.code == code) out.push_back(w);
  return out;
}

/// The warnings of `warnings` with one of `codes`, in order.
inline std::vector<Warning> with_codes(const std::vector<Warning>& warnings,
                                       std::initializer_list<WarningCode> codes) {
  std::vector<Warning> out;
  for (const Warning& w : warnings)
    for (const WarningCode c : codes)
      if (w.code == c) out.push_back(w);
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

/// Value k of a warning as text; "" when it has none.
inline std::string text(const Warning& w, std::size_t k) {
  if (k < w.values.size())
    if (const auto* s = std::get_if<std::string>(&w.values[k])) return *s;
  return {};
}

/// The values of a warning as numbers, in order (NaN for a text).
inline std::vector<double> numbers(const Warning& w) {
  std::vector<double> out;
  for (std::size_t k = 0; k < w.values.size(); ++k) out.push_back(value(w, k));
  return out;
}

}  // namespace plyfit::support
