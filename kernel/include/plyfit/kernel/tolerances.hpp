#pragma once
/// \file The one place where plyfit's tolerances live.
///
/// Every field is named after what it compares and is relative to a scale given by the
/// problem: the spacing `d` of the ply, the size of the face, or the width of a parameter
/// range. Algorithms multiply these by their scale; none uses a bare epsilon.

#include <plyfit/kernel/types.hpp>

namespace plyfit {

/// Tolerances for geometry, solvers and the drape. All are dimensionless ratios unless the
/// name says otherwise.
struct Tolerances {
  /// Newton stop, eq. (9): |F1| + |F2| < newton_residual_rel * d, where both F are lengths.
  double newton_residual_rel = 1e-14;
  /// Floor of the Newton stop: residuals are not asked to go below roundoff_rel times the
  /// magnitude of the coordinates involved and of the face (a few ulps of |F| computed from
  /// them: the surface is evaluated to a few ulps of its control net's size).
  double roundoff_rel = 2e-15;
  /// Thread angles (radians) closer than fold_angle to 0 or pi are cloth folded flat onto
  /// itself, not a drape: a node whose angle would pass them stops at the shear limit even
  /// without a lock angle (eq. 12 with gamma_min = fold_angle). Below it the net can collapse
  /// onto a curve (weft and warp neighbours at one point) that satisfies every link and
  /// never leaves the face, and the two-sphere problem degenerates (its Jacobian's condition
  /// grows as 1 / sin gamma). One degree: far past any woven fabric's locking angle.
  double fold_angle = 1.0 * kDegToRad;
  /// Iteration cap of every Newton solve.
  int newton_max_iterations = 40;
  /// Cap on step halvings in a line search.
  int line_search_max_halvings = 30;
  /// A point is degenerate (pole) when |Su x Sv| < degenerate_rel * |Su|max * |Sv|max, the
  /// maxima taken as the surface's characteristic parametric speeds.
  double degenerate_rel = 1e-8;
  /// Parameter values closer than param_rel * (domain width) are the same.
  double param_rel = 1e-12;
  /// Two ply points closer than ply_merge_rel * d are the same node (e.g. an auxiliary point
  /// that falls on a thread crossing).
  double ply_merge_rel = 1e-9;
  /// Consecutive vertices of a flat-pattern outline closer than outline_merge_rel * d are
  /// one. Where a face corner lies within a hair of a cell edge, the edge's crossings and the
  /// corner carried in by the cell's map come out in an order rounding decides, and a bowtie
  /// of 1e-7 d was seen; the outline is accurate to O(d^2) anyway, so nothing real is lost.
  double outline_merge_rel = 1e-6;
  /// Trim polylines deviate from the exact trim curve by at most trim_chord_rel * face size.
  double trim_chord_rel = 1e-5;
  /// During Newton, an iterate may leave the face's parameter domain by at most this many
  /// parameter-space step lengths before the solve stops with "left the face".
  double extension_steps = 2.0;
  /// A rational surface extended past its domain is undefined where its weight falls below
  /// extension_min_weight_rel times its smallest control weight.
  double extension_min_weight_rel = 1e-3;
  /// A sweep direction must make at least this angle (radians) with the base path: in 2D, and
  /// in 3D its component across the path in the tangent plane at the start must be at least
  /// sin(sweep_min_angle) of its length (so neither along the path nor along the normal). The
  /// sweep only picks a side of the path (the scan's order is the same for every direction
  /// into one side); within a degree of the path that side is a matter of the last digits
  /// given, and no drape worth making is specified that way. One degree.
  double sweep_min_angle = 1.0 * kDegToRad;
  /// A rosette (a ply's 0° direction) must keep at least this sine of its angle with the
  /// surface normal at the seed: nearer the normal, its projection onto the tangent plane (the
  /// 0° direction) turns with the last digits of the normal.
  double rosette_min_sin = 1e-3;
  /// A 3D start farther than start_far_rel times the surface's size (bounding-box diagonal)
  /// from the surface is projected onto it but makes the drape partial with a warning: the
  /// drape starts far from where it was asked to (a wrong unit, face or frame). The paper's
  /// own starts off the surface lie within a fifth of it (Table 1 (b): 5.9 mm, 0.17 of the
  /// octant's size; Table 3 (c): 2.2 mm, 0.06 of the surface of revolution's).
  double start_far_rel = 0.5;
  /// Ply boundaries (boundary.hpp), relative to the mold's size (its bounding-box diagonal):
  /// curves whose ends lie within boundary_gap_rel of each other are chained (CAD curves meet
  /// to their modelling tolerance, far below; a larger gap is a missing curve); every boundary
  /// point must lie within boundary_on_mold_rel of the mold (a boundary drawn on the mold in
  /// CAD does, to its tolerance; farther is a wrong curve, unit or frame); loops are divided
  /// into segments of at most boundary_step_rel before they are mapped to the faces' (u, v),
  /// where a segment is straight (0.1 mm on a 100 mm mold: the chord of a 20 mm radius off by
  /// 6e-5 mm).
  double boundary_gap_rel = 1e-3;
  double boundary_on_mold_rel = 1e-3;
  double boundary_step_rel = 1e-3;
  /// Curves read from a STEP or IGES file (a boundary, a seed curve) are polylines that deviate
  /// from the exact curve by at most curve_chord_rel times the curves' size (their
  /// bounding-box diagonal): a circle of radius r to 1e-5 r encloses its area to about 1e-5.
  double curve_chord_rel = 1e-5;
  /// A seed curve from a file (SeedCurve::kCurve) must lie within seed_curve_rel of the
  /// surface's size (bounding-box diagonal) of the surface, and pass that near the start.
  double seed_curve_rel = 1e-3;
};

}  // namespace plyfit
