#pragma once
/// \file The opening of a chart drawn as SVG (the CLI's optimize front, plyfit-bench's plots):
/// pixel units, sans-serif text, a white background.

#include <plyfit/exporters/format.hpp>

#include <string>

namespace plyfit::exporters {

/// The <svg> element of a chart `width` x `height` pixels and its white background; the
/// caller appends the drawing and "</svg>\n".
inline std::string svg_chart_open(double width, double height) {
  return format(
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
             "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"12\">\n",
             width, height, width, height) +
         format("<rect width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", width, height);
}

}  // namespace plyfit::exporters
