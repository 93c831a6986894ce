#pragma once
// Number and column formatting shared by the tables plyfit prints.

#include <plyfit/exporters/format.hpp>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

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

/// Rows as columns padded to their widest cell (the last column unpadded).
inline void print_columns(const std::vector<std::vector<std::string>>& rows, std::ostream& os) {
  std::vector<std::size_t> w(rows.empty() ? 0 : rows[0].size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c + 1 < row.size() && c < w.size(); ++c)
      w[c] = std::max(w[c], row[c].size());
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += c + 1 < row.size() && c < w.size() ? pad(row[c], w[c] + 2) : row[c];
    os << line << "\n";
  }
}

/// printf-style formatting into a string (shared with plyfit-bench).
using exporters::format;

}  // namespace plyfit::cli
