#pragma once
/// \file The cut outline: a flat pattern's exact outline with the features narrower than a
/// minimum width removed. A pure 2-D polygon function: it knows nothing of the
/// drape.
///
/// What is narrow: a *tip*, a run of outline vertices joined by edges shorter than the width
/// w in all that turns back by more than kSliverTurnDeg (the spike of
/// tests/support/outline_checks.hpp with w for d / 2). From a tip the outline is followed
/// both ways while its two sides stay closer than w to each other; where the width reaches
/// w the feature is cut across by a chord of length w. A tip that turns left (the region on
/// its inside) is a sliver of cloth: cut off, its area removed; one that turns right is a
/// notch or slit: closed across its mouth, its area added. A loop whose whole extent is
/// narrower than w (the smallest width of its convex hull) is dropped. Nothing else of the
/// outline moves: every vertex not inside a narrow feature is kept as it is.

#include <plyfit/kernel/flat_pattern.hpp>

#include <vector>

namespace plyfit {

/// A run of vertices shorter than the minimum width that turns back by more than this
/// (degrees) is the tip of a narrow feature (the outline checks' kSpikeTurnDeg).
inline constexpr double kSliverTurnDeg = 170.0;

/// A chord is placed where the width reaches w (1 + kCutChordMargin), not w: a chord of
/// exactly w comes out an ulp or so short from its rounded end points, and a check of the
/// cut outline (a run shorter than w that turns back is a spike) would then count the chord
/// itself as part of a spike. The margin is far below any length that matters and far
/// above rounding.
inline constexpr double kCutChordMargin = 1e-9;

/// Options of outline_cleanup().
struct OutlineCleanupOptions {
  /// Minimum width w (model units) of cloth and of gaps in the cut outline; 0 turns the
  /// clean-up off (the cut outline is the exact one, point for point).
  double min_width = 0.0;
};

/// What outline_cleanup() did.
struct OutlineCleanupResult {
  std::vector<OutlineLoop> loops;  ///< the cut outline (outer loops CCW, holes CW)
  double removed_area = 0.0;       ///< area of the slivers and loops cut away
  double added_area = 0.0;         ///< area of the notches and hole loops closed
  int slivers = 0;                 ///< narrow features cut or closed, loops dropped included
  int loops_dropped = 0;           ///< loops dropped whole (narrower than w everywhere)
  /// Tips left as they were because no clean cut was found (the chord across would cross
  /// the outline elsewhere, or the tip's sides never part by w).
  int tips_left = 0;
};

/// Removes from `loops` (a flat pattern's outline: simple loops, region on the left of each)
/// every feature narrower than options.min_width. The chords' 3D points are interpolated
/// linearly along the edges they end on (within O(d^2) of the surface, like the outline).
OutlineCleanupResult outline_cleanup(const std::vector<OutlineLoop>& loops,
                                     const OutlineCleanupOptions& options);

}  // namespace plyfit
