#pragma once
// Checks of a file's faces as OpenCASCADE's reader made them (in millimetres, units converted),
// before anything is computed on them: every coordinate, pole, weight, knot, radius, offset,
// trim curve, edge range, vertex, placement and tolerance finite, and every coordinate, length
// and parameter at most kMaxModelCoordinate in magnitude. The text checks (file_checks.hpp)
// catch a bad number where the file states it; these catch what the reading made of the numbers
// (a unit factor or a transformation applied to them, an entity the text checks do not know).
//
// Private to the OpenCASCADE module.

#include <plyfit/kernel/result.hpp>

#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <XSControl_Reader.hxx>

#include <string>

namespace plyfit::importers::occt {

/// Largest coordinate, length or parameter of a face's geometry (mm): no mold is 100 km large,
/// and a value that large leaves no digits for the geometry.
constexpr double kMaxModelCoordinate = 1e8;

/// The entity of the reader's file that produced `face`, as the file numbers it: "#123" (STEP)
/// or "DE 45" (IGES); empty when it is not found.
std::string entity_label(XSControl_Reader& reader, const TopoDS_Shape& face);

/// Checks the geometry of `face` (see the file comment). The error's code and values say what is
/// wrong (the part, "its surface", and the item, "pole (3, 4)"); the caller names the file and
/// the face.
Status check_face_geometry(const TopoDS_Face& face);

}  // namespace plyfit::importers::occt
