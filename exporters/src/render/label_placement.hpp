#pragma once
// Where labels go: a block of text inside the outline of a flat pattern, centred on the point
// farthest from its edges and as large as fits.

#include <plyfit/kernel/flat_pattern.hpp>

#include <vector>

namespace plyfit::exporters::render {

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

/// A block of labels whose size is proportional to its text height h: `width` x `height` per
/// unit of h.
struct BlockShape {
  double width = 0.0, height = 0.0;
  double width_at(double h) const { return h * width; }
  double height_at(double h) const { return h * height; }
};

/// The text height and the block's top-left corner.
struct BlockPlace {
  double h = 0.0;
  Vec2 top_left = Vec2::Zero();
};

/// The largest block up to text height `max_h` centred on the outline's pole of inaccessibility
/// (interior_point() to kPolePrecisionRel of `extent`, the pattern's size) that lies inside the
/// outline. Without an outline (nothing mapped): at height max_h, its top 2 max_h below
/// `fallback`.
BlockPlace place_block(const std::vector<OutlineLoop>& loops, const BlockShape& shape,
                       double extent, double max_h, const Vec2& fallback);
constexpr double kPolePrecisionRel = 1e-3;
/// Bisection steps for the largest block that fits.
constexpr int kFitSteps = 40;

}  // namespace plyfit::exporters::render
