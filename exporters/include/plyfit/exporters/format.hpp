#pragma once
/// \file printf-style formatting into a string: the one formatter of the tables and texts the
/// CLI prints and of plyfit-bench's figures (both link this module).

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

namespace plyfit::exporters {

/// `spec` with `args` put in, as std::snprintf would print it.
template <typename... Args>
std::string format(const char* spec, Args... args) {
  const int n = std::snprintf(nullptr, 0, spec, args...);
  std::string s(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(s.data(), s.size(), spec, args...);
  s.resize(static_cast<std::size_t>(std::max(n, 0)));
  return s;
}

}  // namespace plyfit::exporters
