#pragma once
/// \file Ply boundaries: closed curves on the mold that bound a ply (drop-offs, local
/// reinforcements, cut-outs), as Fibersim and CATIA CPD define them.
///
/// The curves (3D polylines) are chained into closed loops, projected onto the mold and
/// optionally offset along the surface; the ply's region is the even-odd combination of the
/// loops (inner loops are cut-outs) on the mold. bound_mold() gives the mold restricted to that
/// region: each face's trims meet the region in the face's (u, v), so that the drape stops at
/// the boundary as at a trim, across the faces of a shell, and the flat pattern cuts it as it
/// cuts trims.

#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>

#include <string>
#include <vector>

namespace plyfit {

/// A curve of a ply boundary: a polyline in 3D (mm).
struct BoundaryCurve {
  std::vector<Vec3> points;
  std::string name;  ///< how errors name it (a curve's name, or "line N" of a CSV file)
  /// Closed by definition: its last point joins its first (a CSV block). Otherwise it is
  /// closed when its ends meet within Tolerances::boundary_gap_rel, or chained with others.
  bool closed = false;
};

/// A ply boundary: its curves and the offset of its region along the surface.
struct PlyBoundary {
  std::vector<BoundaryCurve> curves;
  /// mm along the surface: > 0 grows the region (a trim allowance), < 0 shrinks it.
  double offset = 0.0;
};

/// One closed loop of a boundary as it lies on the mold (after the offset).
struct PlyBoundaryLoop {
  std::vector<Vec3> points;  ///< on the mold; the last point joins the first
  double length = 0.0;       ///< mm
  std::vector<int> curves;   ///< the curves chained into it (indices into PlyBoundary::curves)
};

/// A mold restricted to a ply's region.
struct BoundedMold {
  MoldSurface surface;
  std::vector<PlyBoundaryLoop> loops;
  double area = 0.0;       ///< the region's area on the mold, mm^2
  std::vector<int> faces;  ///< per face of `surface`: its index in the mold given
};

/// The mold restricted to the region of `boundary` that holds `seed` (projected onto the mold).
/// Errors: no curve (kBoundaryEmpty), a curve of fewer than 2 points or a non-finite point
/// (kBoundaryCurvePoints, naming it), an open end farther than the gap tolerance from any other
/// (kBoundaryGap: the curve, the end, the gap and the tolerance), a point farther from the mold
/// than the tolerance (kBoundaryOffMold: the curve, its distance, the tolerance), a seed
/// outside the region (kBoundarySeedOutside). The errors blame "boundary".
Result<BoundedMold> bound_mold(const MoldSurface& mold, const PlyBoundary& boundary,
                               const Vec3& seed, const Tolerances& tol = {});

}  // namespace plyfit
