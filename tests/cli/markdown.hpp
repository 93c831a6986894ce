#pragma once
// Reading the README and the manual (docs/*.md) in tests: files of the source tree, the rows of
// their tables, their headings as GitHub makes anchors of them, their links.

#include "cli/cli_util.hpp"

#include <cctype>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace plyfit::test {

/// A file of the source tree, by its path from the root ("" when it is missing).
inline std::string source_file(const std::string& rel) {
  return slurp(std::string(PLYFIT_SOURCE_DIR) + "/" + rel);
}

/// The lines of `md` outside fenced code blocks.
inline std::vector<std::string> prose_lines(const std::string& md) {
  std::vector<std::string> out;
  std::istringstream in(md);
  std::string line;
  bool fenced = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      fenced = !fenced;
      continue;
    }
    if (!fenced) out.push_back(line);
  }
  return out;
}

inline std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

/// The cells of every table row of `md` (header rows included, separator rows not); a `\|`
/// inside a cell is part of it.
inline std::vector<std::vector<std::string>> table_rows(const std::string& md) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& line : prose_lines(md)) {
    if (line.rfind("| ", 0) != 0 && line.rfind("|`", 0) != 0) continue;
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '|' && line[i - 1] != '\\') {
        cells.push_back(trimmed(cell));
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    rows.push_back(cells);
  }
  return rows;
}

/// The first table row of `md` whose first cell is `first` exactly.
inline std::optional<std::vector<std::string>> table_row(const std::string& md,
                                                         const std::string& first) {
  for (auto& r : table_rows(md))
    if (!r.empty() && r[0] == first) return r;
  return std::nullopt;
}

/// The first table row of `md` whose first cell holds `token`.
inline std::optional<std::vector<std::string>> table_row_holding(const std::string& md,
                                                                 const std::string& token) {
  for (auto& r : table_rows(md))
    if (!r.empty() && r[0].find(token) != std::string::npos) return r;
  return std::nullopt;
}

/// The anchor GitHub gives a heading's text: lower case, punctuation dropped but '-' and '_',
/// spaces made '-'; bytes of non-ASCII characters kept.
inline std::string heading_slug(const std::string& text) {
  std::string slug;
  for (const unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c >= 0x80)
      slug += static_cast<char>(std::tolower(c));
    else if (c == ' ')
      slug += '-';
  }
  return slug;
}

/// The headings of `md` (outside code blocks): their texts, without the leading #s.
inline std::vector<std::string> headings(const std::string& md) {
  std::vector<std::string> out;
  for (const auto& line : prose_lines(md)) {
    const auto hashes = line.find_first_not_of('#');
    if (hashes == 0 || hashes == std::string::npos || line[hashes] != ' ') continue;
    out.push_back(trimmed(line.substr(hashes)));
  }
  return out;
}

/// The anchors of `md`'s headings, a repeated one with -1, -2, ... as GitHub numbers them.
inline std::vector<std::string> anchors(const std::string& md) {
  std::vector<std::string> out;
  std::map<std::string, int> seen;
  for (const auto& h : headings(md)) {
    const std::string slug = heading_slug(h);
    const int n = seen[slug]++;
    out.push_back(n == 0 ? slug : slug + "-" + std::to_string(n));
  }
  return out;
}

/// The targets of `md`'s links and images (outside code blocks and code spans).
inline std::vector<std::string> link_targets(const std::string& md) {
  std::vector<std::string> out;
  const std::regex code_span("`[^`]*`"), link(R"(\]\(([^)\s]+)\))");
  for (const auto& line : prose_lines(md)) {
    const std::string text = std::regex_replace(line, code_span, "``");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link);
         it != std::sregex_iterator(); ++it)
      out.push_back((*it)[1]);
  }
  return out;
}

/// The part of `md` from the heading line `heading` (e.g. "## Keys") to the next heading of the
/// same or a higher level, code blocks included; empty when there is no such heading.
inline std::string md_section(const std::string& md, const std::string& heading) {
  const std::size_t level = heading.find(' ');
  std::istringstream in(md);
  std::string line, out;
  bool fenced = false, inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    const auto hashes = line.find_first_not_of('#');
    const bool is_heading =
        !fenced && hashes != 0 && hashes != std::string::npos && line[hashes] == ' ';
    if (inside && is_heading && hashes <= level) break;
    if (!inside && is_heading && line == heading) inside = true;
    if (inside) out += line + "\n";
  }
  return out;
}

}  // namespace plyfit::test
