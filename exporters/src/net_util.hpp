#pragma once
// Helpers shared by the writers: locale-independent number text, the mapped cells of the net
// with their shear, and the shear colour scale of the pictures.

#include <plyfit/kernel/drape.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace plyfit::exporters::detail {

/// A 2D box grown point by point (empty until the first point).
struct Box2 {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x() && lo.y() <= hi.y()); }
  Vec2 size() const { return hi - lo; }
};

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;

/// Shortest decimal text (fixed notation, no exponent) that reads back as exactly `x`.
std::string exact_text(double x);
/// `x` in fixed notation with `decimals` decimals, trailing zeros removed ("-0" becomes "0").
std::string fixed_text(double x, int decimals);

/// Shear of a node: |pi/2 - thread_angle| (radians), or a negative value if the node has no
/// thread angle.
double node_shear(const DrapeNode& n);

/// A mapped cell (or the mapped part of a cell the base path splits): a convex polygon of
/// node indices, counter-clockwise in ply coordinates, every node mapped.
struct NetCell {
  std::int32_t i = 0, j = 0;         ///< the cell: lower-left regular node (i, j)
  std::vector<std::uint32_t> nodes;  ///< indices into DrapeResult::nodes
  /// The cell's shear: the largest |pi/2 - gamma| over its corners that have a thread angle
  /// (radians); negative when none has one.
  double shear = -1.0;
};

/// Every mapped cell part (plyfit::mapped_cells: the parts the kernel counts in
/// DrapeMetrics::flat_area), with its shear. Sorted by (j, i): deterministic.
std::vector<NetCell> mapped_cells(const DrapeResult& r);

/// An RGB colour.
struct Rgb {
  double r = 0, g = 0, b = 0;  ///< 0..1
  /// "#rrggbb".
  std::string hex() const;
  /// This colour scaled towards black by `f` (1 = unchanged).
  Rgb shaded(double f) const;
};

/// The pictures' shear colour scale (viridis-like, dark blue at 0, yellow at the top):
/// t in [0, 1], clamped.
Rgb shear_colour(double t);

/// Colour of cells without a shear value.
inline Rgb no_shear_colour() {
  return {0.75, 0.75, 0.75};
}

/// Unicode code points of UTF-8 text; invalid bytes become U+FFFD.
std::u32string utf8_decode(const std::string& s);
/// UTF-8 text of code points.
std::string utf8_encode(const std::u32string& s);

/// XML-escapes text for SVG content and attributes (invalid UTF-8 and control characters are
/// replaced).
std::string xml_escape(const std::string& s);

}  // namespace plyfit::exporters::detail
