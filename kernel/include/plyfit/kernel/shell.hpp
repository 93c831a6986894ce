#pragma once
/// \file Shells: several faces of a mold sewn along shared edges, draped as one surface.

#include <plyfit/kernel/face.hpp>

#include <cstdint>
#include <vector>

namespace plyfit {

/// Plain data of a shell, as importers (after sewing) and built-in molds produce it.
///
/// Every face that has a shared edge carries explicit trim loops (a natural boundary too, as
/// the loop of its domain's border) whose segments name the shared edge they lie on
/// (TrimLoop::edges). A shared edge is used by exactly two faces; the two uses run along the
/// same 3D curve (within `tolerance`), usually in opposite directions. Edges that bound one
/// face only are free (TrimLoop::kFreeEdge): the drape stops there. The seam of a face that
/// closes on itself (FaceData::closed_u / closed_v) is not a shared edge.
struct ShellData {
  std::vector<FaceData> faces;
  /// Number of shared edges: the edge indices in the loops run from 0 to edge_count - 1.
  std::int32_t edge_count = 0;
  /// Index of each face in its mold file, for reports (empty: 0, 1, ...).
  std::vector<int> source_faces;
  /// The sewing tolerance (model units): the largest gap between the two sides of a shared
  /// edge that was closed.
  double tolerance = 0.0;
};

}  // namespace plyfit
