#pragma once
// INI text as scene files and the materials table write it: "# comments", [section] lines and
// "key = value" lines, whitespace trimmed. One reader for both; each checks its own keys.

#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::cli {

/// A line of INI text that says something: a [section] or a key = value.
struct IniLine {
  int line = 0;             ///< 1-based line number
  bool is_section = false;  ///< a [section] line (its name in `section`)
  std::string section;      ///< the section it is in (empty before the first)
  std::string key, value;   ///< a key = value line's
};

/// Reads INI text; a line that is neither a section nor a key = value is an error whose place
/// (Error::where) is "SOURCE:LINE".
Result<std::vector<IniLine>> read_ini(const std::string& text, const std::string& source);

/// "SOURCE:LINE", the place of an error in an INI file.
std::string ini_place(const std::string& source, int line);

}  // namespace plyfit::cli
