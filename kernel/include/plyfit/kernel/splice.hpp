#pragma once
/// \file Splices: a flat pattern wider than the roll split into pieces along fibre-aligned
/// seams. The roll runs along the warp (ply +y); a pattern's width is its extent across the
/// warp (ply x). Seams are lines x = s in ply coordinates: warp threads on the part
/// (docs/splices.md; docs/decisions/splices.md says how the seams are placed).

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit {

/// Options of splice_pattern().
struct SpliceOptions {
  double roll_width = 0.0;  ///< W (model units): no piece is wider across the warp
  /// o >= 0: the piece left of a seam (lower x) extends o past it over its neighbour; 0 is
  /// a butt joint. At most W - d_weft (each piece brings at least a cell of new cloth).
  double overlap = 0.0;
  std::string ply_name = "ply";  ///< pieces are named ply_name + A, B, C...
  /// Seams of other plies (3D polylines on the part) this ply's seams keep at least `stagger`
  /// from, when the roll leaves room for it (SplicePlan::stagger_met says whether it did).
  std::vector<std::vector<Vec3>> avoid;
  double stagger = 0.0;
  /// Shear along a candidate seam is compared in steps of this (radians): seams whose shear
  /// differs by less count as equal, and the rightmost of equal ones is taken.
  double shear_step = 0.5 * kDegToRad;
  /// Candidate seam positions are spaced at most this fraction of d_weft apart.
  double candidate_step_rel = 0.25;
};

/// A seam: the warp line x = `x` of the ply, where two pieces meet.
struct Seam {
  double x = 0.0;  ///< ply coordinate across the warp
  /// The seam on the part: the warp thread at x interpolated between the draped threads
  /// round it, one polyline per stretch of the line inside the pattern (start and end on its
  /// outline).
  std::vector<std::vector<Vec3>> polylines;
  double length = 0.0;           ///< length of the line inside the pattern, ply units
  double length3d = 0.0;         ///< length of the polylines on the part
  double shear_max = 0.0;        ///< largest shear of the cells it crosses (radians)
  double shear_mean = 0.0;       ///< mean shear of those cells' nodes (radians)
  double stagger_distance = -1;  ///< distance on the part to the nearest avoided seam; -1: none
};

/// A piece of the ply: the pattern between two seams (and an overlap strip).
struct SplicePiece {
  std::string name;                 ///< ply name + letter
  std::vector<OutlineLoop> loops;   ///< outer loops CCW, holes CW; 2D and on the mold
  double area = 0.0;                ///< ply units squared
  double x_min = 0.0, x_max = 0.0;  ///< extent across the warp
  double width() const { return x_max - x_min; }
};

/// How a pattern was split. One piece (the pattern itself) and no seam when it fits the roll.
struct SplicePlan {
  double roll_width = 0.0, overlap = 0.0, stagger = 0.0;
  double pattern_width = 0.0;  ///< the cut outline's extent across the warp
  std::vector<Seam> seams;     ///< left to right
  std::vector<SplicePiece> pieces;
  bool stagger_met = true;  ///< every seam keeps `stagger` from the avoided ones
  bool split() const { return pieces.size() > 1; }
};

/// Checks the options against a ply of weft link d_weft: finite values, a roll at least two
/// cells wide, 0 <= overlap <= roll width - d_weft, stagger >= 0. Errors blame "roll-width",
/// "splice-overlap" or "splice-stagger".
Status check_splice_options(const SpliceOptions& options, double d_weft);

/// The letter(s) of piece k: A..Z, then AA, AB...
std::string piece_letter(std::size_t k);

/// Splits the cut outline of `flat` (a drape `result`'s) into the fewest pieces no wider than
/// the roll; among the seam positions that do it, the seams cross the least-sheared cells
/// (the largest shear first, then the mean). Errors blame "roll-width", "splice-overlap" or
/// "splice-stagger".
Result<SplicePlan> splice_pattern(const FlatPattern& flat, const DrapeResult& result,
                                  const SpliceOptions& options);

/// The smallest distance between two sets of 3D polylines (vertices to segments, both ways).
double polyline_distance(const std::vector<std::vector<Vec3>>& a,
                         const std::vector<std::vector<Vec3>>& b);

}  // namespace plyfit
