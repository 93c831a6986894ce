#pragma once
// Text the writers put into their files: locale-independent numbers, UTF-8, XML escaping, word
// wrapping, and the labels naming a run's mold, faces and material.

#include <plyfit/exporters/exporters.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace plyfit::exporters::render {

/// Shortest decimal text (fixed notation, no exponent) that reads back as exactly `x`.
std::string exact_text(double x);
/// `x` in fixed notation with `decimals` decimals, trailing zeros removed ("-0" becomes "0").
std::string fixed_text(double x, int decimals);
/// An angle in degrees as fixed_text() followed by the degree sign (U+00B0).
std::string degrees_text(double deg, int decimals);

/// Unicode code points of UTF-8 text; invalid bytes become U+FFFD.
std::u32string utf8_decode(const std::string& s);
/// UTF-8 text of code points.
std::string utf8_encode(const std::u32string& s);
/// Characters (code points) of UTF-8 text.
std::size_t utf8_length(const std::string& s);

/// XML-escapes text for SVG content and attributes (invalid UTF-8 and control characters are
/// replaced).
std::string xml_escape(const std::string& s);

/// Greedy word wrap of `s` (words separated by spaces) into lines of at most `max_chars`
/// characters; a word longer than a line gets a line of its own, never cut.
std::vector<std::string> wrap_words(const std::string& s, std::size_t max_chars);

/// The mold as labels show it: a file's name without its folder, or "builtin:..." as given.
std::string mold_label(const std::string& mold);
/// The faces draped, for labels: "face 3", "faces 3, 4, 7", or "18 faces" for many (an empty
/// list is the default face 0).
std::string faces_label(const std::vector<int>& faces);
/// The material as the pictures and the report name it: its label, else its name.
std::string material_label(const ExportContext& ctx);

}  // namespace plyfit::exporters::render
