#pragma once
// Number and column formatting shared by the tables plyfit prints.

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

namespace plyfit::cli {

/// `x` with `digits` decimals.
inline std::string fixed(double x, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << x;
  return os.str();
}

/// `s` padded with spaces to `width`.
inline std::string pad(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

/// printf-style formatting into a string.
template <typename... Args>
std::string format(const char* spec, Args... args) {
  const int n = std::snprintf(nullptr, 0, spec, args...);
  std::string s(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(s.data(), s.size(), spec, args...);
  s.resize(static_cast<std::size_t>(std::max(n, 0)));
  return s;
}

}  // namespace plyfit::cli
