#pragma once
// Helpers shared by the writers: locale-independent number text, the mapped cells of the net
// with their shear, and the shear colour scale of the pictures.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

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

using plyfit::kPi;
using plyfit::kRadToDeg;

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

/// True when p lies inside the outline (even-odd over all loops, so holes are outside).
bool inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& p);

/// Distance from p to the nearest edge of the loops (infinity without loops).
double outline_distance(const std::vector<OutlineLoop>& loops, const Vec2& p);

/// A point well inside the outline: the centre of a largest inscribed circle and its radius.
struct InteriorPoint {
  Vec2 point = Vec2::Zero();
  double radius = 0.0;  ///< distance from `point` to the outline
  bool found = false;   ///< false without loops of positive area
};

/// A pole of inaccessibility of the outline (a point inside it as far from its edges as can
/// be): a grid of about kGridCells square cells along the outline's long side (at most
/// kMaxInteriorProbes), then the kClimbSeeds best grid points each climbed uphill on the
/// distance to the edges (eight directions, the step halved when none is better) until the
/// step is below precision / 4. The result is a local maximum within `precision`; on outlines
/// whose best grid point lies in the reach of the global maximum, the largest inscribed circle.
InteriorPoint interior_point(const std::vector<OutlineLoop>& loops, double precision);
/// Grid cells along the outline's long side, the cap on grid points (each costs one pass over
/// the edges), the grid points climbed from, and the climb's step cap.
constexpr int kGridCells = 32;
constexpr int kMaxInteriorProbes = 4096;
constexpr int kClimbSeeds = 8;
constexpr int kMaxClimbSteps = 400;

/// True when the box [lo, hi] lies inside the outline: its centre inside and no edge of the
/// loops meeting it.
bool box_inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& lo, const Vec2& hi);

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

/// The mold as labels show it: a file's name without its folder, or "builtin:..." as given.
std::string mold_label(const std::string& mold);
/// The faces draped, for labels: "face 3", "faces 3, 4, 7", or "18 faces" for many (an empty
/// list is the default face 0).
std::string faces_label(const std::vector<int>& faces);

/// Unicode code points of UTF-8 text; invalid bytes become U+FFFD.
std::u32string utf8_decode(const std::string& s);
/// UTF-8 text of code points.
std::string utf8_encode(const std::u32string& s);

/// XML-escapes text for SVG content and attributes (invalid UTF-8 and control characters are
/// replaced).
std::string xml_escape(const std::string& s);

}  // namespace plyfit::exporters::detail
