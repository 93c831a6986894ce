#pragma once
// The text functions of the error and warning codes: text_<name>(values) for each code of
// PLYFIT_ERROR_CODES and warning_<name>(values) for each of PLYFIT_WARNING_CODES, defined in
// the error_text_*.cpp / warning_text*.cpp files of this folder by the module that raises them.

#include <plyfit/kernel/result.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace plyfit::exporters::render {

/// A code's values as its text reads them (by position, as the raiser gave them). A missing or
/// mistyped value shows as -1, 0 or "?" (a bug, but never a crash while reporting a problem).
struct Values {
  const std::vector<MessageValue>& v;
  std::int64_t count(std::size_t k) const;
  double number(std::size_t k) const;
  std::string text(std::size_t k) const;
  /// count(k) in decimal.
  std::string n(std::size_t k) const { return std::to_string(count(k)); }
  /// number(k) to three significant digits (a measure in a sentence).
  std::string brief(std::size_t k) const;
  /// number(k) with std::to_string's six decimals (an input echoed as given).
  std::string fixed(std::size_t k) const { return std::to_string(number(k)); }
};

/// A code's sentence with its values in place: {nK} is count(K) in decimal, {tK} text(K),
/// {bK} brief(K), {fK} fixed(K), {qK} text(K) in single quotes (K one digit).
std::string fill(std::string_view sentence, const Values& x);

/// The text of an error and its causes carried as a warning's values from values[first] on:
/// for each, its code's name, its value count and its values ("could not be described:
/// OpenCASCADE failed (...)"); a name that is no code shows as itself.
std::string error_chain_text(const Values& x, std::size_t first);

/// Defines the text function `name` of a code whose text is one sentence with its values in
/// place (fill()); used as PLYFIT_SENTENCE(text_code, "sentence");
#define PLYFIT_SENTENCE(name, sentence) \
  std::string name(const Values& x) {   \
    return fill(sentence, x);           \
  }                                     \
  static_assert(true)

#define PLYFIT_DECLARE_TEXT(name, snake) std::string text_##snake(const Values& x);
PLYFIT_ERROR_CODES(PLYFIT_DECLARE_TEXT)
#undef PLYFIT_DECLARE_TEXT
#define PLYFIT_DECLARE_TEXT(name, snake) std::string warning_##snake(const Values& x);
PLYFIT_WARNING_CODES(PLYFIT_DECLARE_TEXT)
#undef PLYFIT_DECLARE_TEXT

}  // namespace plyfit::exporters::render
