#pragma once
// Kernel NURBS data as OpenCASCADE geometry: the one conversion used by the STEP writer, the
// sample mold writer, plyfit-bench and the tests that compare with OpenCASCADE. Private to
// the modules that link OpenCASCADE (no OpenCASCADE type in a public header).

#include <plyfit/kernel/nurbs.hpp>

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>

#include <vector>

namespace plyfit::occt {

/// A flat knot vector as OpenCASCADE's distinct knots and multiplicities (1-based arrays).
struct KnotsMults {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
};
KnotsMults compress_knots(const std::vector<double>& flat);

/// The same surface as an OpenCASCADE B-spline (rational iff weights are given).
Handle(Geom_BSplineSurface) to_occt(const NurbsSurfaceData& d);
/// The same 3D curve.
Handle(Geom_BSplineCurve) to_occt(const NurbsCurveData3& d);
/// The same 2D curve.
Handle(Geom2d_BSplineCurve) to_occt(const NurbsCurveData2& d);

}  // namespace plyfit::occt
