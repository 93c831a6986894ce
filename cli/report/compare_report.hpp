#pragma once
// What plyfit compare prints: the figures of the paper's Tables 2 and 4 per scene, the best
// scene per criterion marked, as a text table, Markdown or CSV.

#include <plyfit/kernel/result.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace plyfit::cli {

/// How a column is marked.
enum class Mark {
  kSmaller,  ///< the smallest figure among the compared scenes
  kLarger,   ///< the largest
  kCovers,   ///< every scene that covers the face (the outline coverage rule): the compared ones
  kNone,     ///< shown only
};

/// One column of the table.
struct Criterion {
  std::string key;     ///< CSV column and `best` entry
  std::string header;  ///< table header
  Mark mark;
  bool count;  ///< an integer count (exact ties)
  int digits;  ///< decimals shown
};

const std::vector<Criterion>& criteria();

/// Index of the column `key` in criteria().
std::size_t column(const std::string& key);

/// One compared scene.
struct Row {
  std::string name, path;
  bool ok = false;                ///< draped (status ok or partial)
  bool partial = false;           ///< draped, status partial
  std::string error, error_code;  ///< why it failed (text and code)
  std::vector<Warning> warnings;
  std::vector<double> values;  ///< one per criterion
  std::vector<bool> best;
  bool compared = false;  ///< status ok and covers the face: its figures compete for best
};

/// Marks each row's best figures among the compared scenes (the rule: kRule in the .cpp, printed
/// under the table).
void mark_best(std::vector<Row>& rows);

/// The table as aligned text, Markdown or CSV (full precision), with the notes (scenes that
/// failed, are partial or cover less) and the rule.
void print_compare_text(const std::vector<Row>& rows, std::ostream& os);
void print_compare_markdown(const std::vector<Row>& rows, std::ostream& os);
void print_compare_csv(const std::vector<Row>& rows, std::ostream& os);

}  // namespace plyfit::cli
