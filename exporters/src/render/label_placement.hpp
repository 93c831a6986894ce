#pragma once
// Where labels go: a block of text inside the outline of a flat pattern, centred on the point
// farthest from its edges and from what else is drawn, as large as fits; a small label next to
// its anchor where nothing else is.

#include <plyfit/kernel/flat_pattern.hpp>

#include <utility>
#include <vector>

namespace plyfit::exporters::render {

/// What a label keeps clear of: lines (paths, arrows), discs (markers) and boxes (labels
/// already placed), in the drawing's coordinates.
struct Obstacles {
  std::vector<std::pair<Vec2, Vec2>> segments;
  std::vector<std::pair<Vec2, double>> discs;  ///< centre, radius
  std::vector<std::pair<Vec2, Vec2>> boxes;    ///< lo, hi
  /// Distance from p to the nearest obstacle (infinity without any; negative inside a disc or
  /// a box).
  double distance(const Vec2& p) const;
  /// True when the box [lo, hi] meets an obstacle.
  bool meet(const Vec2& lo, const Vec2& hi) const;
};

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
/// With `obstacles`, the distance is the smaller of the distances to the edges and to them.
InteriorPoint interior_point(const std::vector<OutlineLoop>& loops, double precision,
                             const Obstacles& obstacles = {});
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

/// The largest block up to text height `max_h` that lies inside the outline and keeps
/// kObstacleGap text heights from every obstacle, centred on the pole of inaccessibility of the
/// outline less the obstacles (interior_point() to kPolePrecisionRel of `extent`, the pattern's
/// size) or on one of interior_point()'s grid points where a larger block fits (by at least
/// kBlockGainRel). Without an outline (nothing mapped): at height max_h, its top 2 max_h below
/// `fallback`.
BlockPlace place_block(const std::vector<OutlineLoop>& loops, const BlockShape& shape,
                       double extent, double max_h, const Vec2& fallback,
                       const Obstacles& obstacles = {});
constexpr double kObstacleGap = 0.5;
constexpr double kBlockGainRel = 0.01;
constexpr double kPolePrecisionRel = 1e-3;
/// Bisection steps for the largest block that fits.
constexpr int kFitSteps = 40;

/// A label box of `size` beside `anchor`, where it meets no obstacle: at `preferred` (its
/// lo corner) when that is free, else the first free of the boxes on the eight sides of the
/// anchor (the sides nearest the direction `towards` first) at kLabelRings distances of `gap`
/// steps; `preferred` when none is free. With `avoid_also` (what the label had better not
/// cover, such as the drawing), first the first place free of both, then of `obstacles` alone.
Vec2 place_label(const Vec2& anchor, const Vec2& size, const Vec2& preferred, const Vec2& towards,
                 double gap, const Obstacles& obstacles, const Obstacles* avoid_also = nullptr);
constexpr int kLabelRings = 8;

}  // namespace plyfit::exporters::render
