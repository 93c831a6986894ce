#pragma once
/// \file The flat pattern: the region of the 2D ply that lands on the face, as outline loops
/// in ply coordinates.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/mold.hpp>

#include <algorithm>
#include <optional>
#include <vector>

namespace plyfit {

/// A closed outline loop in ply coordinates (the first point is not repeated).
struct OutlineLoop {
  std::vector<Vec2> points;
  /// The same points on the mold (the 3D ply boundary, e.g. for laser projection): every
  /// outline point is a node, a boundary crossing or a boundary vertex, each on the surface.
  /// Points of the staircase have their nodes' positions (zero for a corner never placed).
  std::vector<Vec3> points3d;
  bool hole = false;  ///< holes run clockwise, outer loops counter-clockwise
  double area = 0.0;  ///< enclosed area (positive)
  double perimeter = 0.0;
};

/// Outlines of the ply region on the face.
struct FlatPattern {
  /// Exact outline: where a thread segment or cell crosses the face boundary the crossing
  /// is found on the surface and carried back to ply coordinates by the cell's own
  /// interpolation.
  std::vector<OutlineLoop> outline;
  /// The coarser boundary of the mapped cells (the paper's "bold segments").
  std::vector<OutlineLoop> staircase;
  double area = 0.0;       ///< outline area, holes subtracted
  double perimeter = 0.0;  ///< outline length, holes included
  /// Cut outline: the exact outline without the features narrower than min_width (slivers
  /// of cloth cut off, notches and slits closed, loops narrower than it dropped;
  /// outline_cleanup.hpp). What a cutter cuts; equal to `outline` when min_width is 0.
  std::vector<OutlineLoop> cut;
  double cut_area = 0.0;          ///< cut outline area, holes subtracted
  double cut_perimeter = 0.0;     ///< cut outline length, holes included
  double min_width = 0.0;         ///< the minimum width w the cut outline was made with
  double cut_removed_area = 0.0;  ///< area of cloth cut away (slivers, narrow loops)
  double cut_added_area = 0.0;    ///< area of gaps closed (notches, slits, narrow holes)
  int slivers = 0;                ///< narrow features removed (loops dropped included)
  /// Cloth laid twice, left out of the cut outline before the narrow features are removed:
  /// the cells (or cell parts) of a piece with a node on the cloth of a larger piece, where
  /// the cloth came round onto itself (a closed face or shell) past the drape's overlap
  /// test, and the pieces the seam cuts off (beyond it). The cut area is the exact one less
  /// laid_twice_area and cut_removed_area, plus cut_added_area.
  int cells_laid_twice = 0;
  double laid_twice_area = 0.0;
};

/// Options of the flat pattern (the crossings are exact to rounding and the boundary is
/// followed through every vertex of the face's boundary polylines).
struct FlatPatternOptions {
  /// Minimum width of cloth and of gaps in the cut outline (model units); 0 makes the cut
  /// outline the exact one; empty: half the net spacing (the larger of d_weft, d_warp).
  std::optional<double> min_width;
  /// The minimum width used for a ply of `spec`: min_width, or its default.
  double width_for(const PlySpec& spec) const {
    return min_width.value_or(0.5 * std::max(spec.d_weft, spec.d_warp));
  }
};

/// Computes the flat pattern of a drape on `surface`.
FlatPattern flat_pattern(const MoldSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options = {});

}  // namespace plyfit
