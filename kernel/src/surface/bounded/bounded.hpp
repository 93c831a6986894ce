#pragma once
/// \file The steps of bound_mold(): boundary curves chained into loops on the mold, and each
/// face's trims met with the loops' region in its (u, v).

#include "surface/face.hpp"

#include <plyfit/kernel/boundary.hpp>

#include <functional>
#include <optional>
#include <vector>

namespace plyfit::detail {

/// A closed loop of a boundary: its points (the last joins the first) and, per point, the
/// curve it comes from.
struct MoldLoop {
  std::vector<Vec3> points;
  std::vector<int> curve;
};

/// The curves chained into closed loops: a closed curve is a loop; open curves are joined end
/// to end where their ends lie within `gap`. Errors as bound_mold()'s for the curves and gaps.
Result<std::vector<MoldLoop>> chain_curves(const PlyBoundary& boundary, double gap);

/// Every segment of the loop divided into equal ones no longer than `step`.
void densify(MoldLoop& loop, double step);

/// Every point of the loops replaced by its projection onto the mold; an error
/// (kBoundaryOffMold) names the curve of a point farther than `reach`.
Status project_loops(const MoldSurface& mold, const PlyBoundary& boundary,
                     std::vector<MoldLoop>& loops, double reach);

/// Every point moved by `offset` along the surface, across its loop, away from the region
/// (`inside(p, reach)` tells whether 3D point p lies on the mold within `reach` of the surface
/// and in the region), then projected onto the mold.
void offset_loops(const MoldSurface& mold, std::vector<MoldLoop>& loops, double offset,
                  const std::function<bool(const Vec3&, double)>& inside);

/// What the region does to one face.
struct FaceCut {
  enum Kind { kWhole, kNone, kPart } kind = kWhole;
  std::vector<TrimLoop> loops;  ///< for kPart: the face's new trims, tagged
  double area = 0.0;            ///< for kPart: their area on the face (boundary_area)
  bool winding = false;         ///< a loop winds round the face's closed direction
};

/// The face's trims met with the loops' region, in its (u, v): the loops projected onto the
/// face's surface (clamped to its domain, unwrapped across seams), combined even-odd, and
/// intersected with the face's own region. A segment of the result on one of the face's own
/// trim segments keeps its shared-edge tag; the others are free edges.
/// A loop winding round a closed direction bounds, with the others, the side of the face
/// towards the open direction's near edge (v0 or u0), or its far one when `far_side`.
FaceCut cut_face(const Face& face, const std::vector<MoldLoop>& loops, const Tolerances& tol,
                 bool far_side = false);

}  // namespace plyfit::detail
