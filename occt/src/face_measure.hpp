#pragma once
// The area and bounding box of an OpenCASCADE face, computed by plyfit on the face's exact
// geometry (its surface and the pcurves of its edges), without converting the face.
//
// Area: Green's theorem in the (u, v) plane, A = |sum over the boundary of the integral of
// G(u, v) dv|, with G(u, v) the integral of |S_u x S_v| along u from a fixed u of the loop. The
// boundary integral is adaptive Gauss-Kronrod (7/15 points, QUADPACK's error estimate) over
// pieces split where the pcurve crosses a knot line, so each piece is smooth; the inner
// integral is Gauss-Legendre over the surface's knot spans, with an order and subdivision
// chosen per face by comparing rules on rows across the face. The estimated error is at most
// the requested fraction of the area when `converged`. OpenCASCADE's own adaptive
// integration (BRepGProp::SurfaceProperties with a tolerance) is far slower at equal accuracy
// and, on the shared test files, misses its requested tolerance by orders of magnitude.
//
// Private to the OpenCASCADE module (OpenCASCADE types in the interface): the library
// plyfit_occt_measure, linked by the module and by the tests and benchmarks that call it.

#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/types.hpp>

#include <Geom_BSplineSurface.hxx>

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace plyfit::importers::occt {

/// What measure_face() found.
struct FaceMeasure {
  double area = 0.0;       ///< mm^2
  double error = 0.0;      ///< estimated absolute error of `area`, mm^2
  bool converged = false;  ///< error <= the requested fraction of the area
  /// Bounding box of points on the face: its boundary (kBoxEdgeSamples points per edge) and a
  /// grid of kBoxGrid x kBoxGrid points over its (u, v) box that lie inside its boundary. It
  /// depends on the geometry alone (not on the accuracy asked of the area). Empty unless asked
  /// for.
  BBox3 bbox;
  long evaluations = 0;  ///< surface evaluations made
  /// False when the face could not be measured: the integration ran out of its work cap
  /// (kMaxMeasureEvaluations) or gave no finite value, as on an invalid face (a boundary that
  /// does not bound a region of its surface); `area` and `error` are 0 then and `failure` says
  /// why.
  bool measured = true;
  std::string failure;
  /// The kernel's surface the face was measured on (built with the default Tolerances, from
  /// nurbs_data() of the face's non-periodic B-spline or Bezier surface), else null: the face's
  /// conversion takes it rather than building it again.
  std::shared_ptr<const NurbsSurface> surface = {};
};

/// Work cap of one measure_face(): surface evaluations, kMaxMeasureEvaluations and
/// kMeasureEvaluationsPerPatch for each Bezier patch of a B-spline surface. The faces of the
/// shared CAD files need at most 1.9e5 at 1e-9 relative, a few hundred per patch; an invalid face
/// can make the adaptive rules ask for ever more.
constexpr long kMaxMeasureEvaluations = 2'000'000;
constexpr long kMeasureEvaluationsPerPatch = 2'000;

/// Grid points per direction of the interior samples of the bounding box.
constexpr int kBoxGrid = 32;
/// Boundary points per edge sampled for the bounding box (at least one per smooth interval of
/// its pcurve).
constexpr int kBoxEdgeSamples = 64;

/// Measures `face` to the relative accuracy `rel_tol` (estimated), with its bounding box when
/// `with_box`. `transposed` integrates along v and around the boundary in u instead (the same
/// area by another path of quadratures: tests and benchmarks compare the two). Falls back to
/// OpenCASCADE's integration (BRepGProp) for a face that has no boundary with pcurves; then
/// `converged` is false and `bbox` comes from OpenCASCADE's BRepBndLib::AddOptimal. Ends within
/// its work cap of surface evaluations (FaceMeasure::measured says whether it measured).
FaceMeasure measure_face(const TopoDS_Face& face, double rel_tol, bool with_box,
                         bool transposed = false);

/// The warning of face `face` (made by the file's entity `entity`, or "") whose measure `m`
/// falls short of the relative accuracy `rel` it was asked for: kFaceAreaUnmeasured {face,
/// entity, why} when it was not measured, kFaceAreaShort {face, entity, rel, the relative error
/// reached when estimated}; none when it reached `rel`.
std::optional<Warning> area_warning(const FaceMeasure& m, double rel, int face,
                                    const std::string& entity);

/// The kernel's plain data of an OpenCASCADE B-spline surface (same parametrization).
NurbsSurfaceData nurbs_data(const Handle(Geom_BSplineSurface) & b);

/// The edges of a wire of `f` in order along it, with their orientation in the wire
/// (BRepTools_WireExplorer; the stored order when it cannot chain every edge).
std::vector<TopoDS_Edge> ordered_edges(const TopoDS_Wire& w, const TopoDS_Face& f);

}  // namespace plyfit::importers::occt
