#pragma once
/// \file Mold files written by plyfit itself: one kernel face (NURBS surface with its trims)
/// as a STEP or IGES file that plyfit's importers, and any CAD system, read back. Used by
/// `plyfit sample` to make the sample molds under samples/.

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::exporters {

/// Options of write_mold().
struct MoldWriteOptions {
  /// "step" or "iges"; empty: from the file extension (.step/.stp, .iges/.igs).
  std::string format;
  /// Name given to the face (STEP: the ADVANCED_FACE and its surface; IGES: a name property,
  /// entity 406 form 15, on the surface). Empty: no name.
  std::string name;
  /// Time stamp written into the file header (STEP FILE_NAME, IGES global section dates)
  /// instead of the current time, so that equal inputs give equal bytes.
  std::string timestamp = "2000-01-01T00:00:00";
};

/// Mold formats write_mold() knows: "step", "iges".
std::vector<std::string> mold_formats();

/// Writes `face` as a one-face mold file at `path`, atomically (temporary file + rename): its
/// NURBS surface, bounded by the surface's natural boundary (seams and collapsed edges as
/// OpenCASCADE makes them) when exact_loops is empty or natural_outer, else by the first exact
/// loop, with every further exact loop as a hole. Each trim curve is an edge whose curve on
/// the surface is the exact (u, v) curve (its 3D curve is OpenCASCADE's approximation of the
/// surface image). The face keeps plyfit's orientation: the file's face normal is Su x Sv, or
/// its opposite when face.reversed. Reals are written with 17 significant digits, so that
/// they read back bit for bit (the writers' defaults keep only 10 to 13); magnitudes below
/// 1e-99 are written as 0, 1e99 and above are refused. Errors name the file and the problem
/// (unknown format, invalid surface or trim, a trim off the domain, write failure).
Status write_mold(const BuiltinFace& face, const std::string& path,
                  const MoldWriteOptions& options = {});

/// Writes a kernel face whose trim loops are polylines: each loop becomes one edge whose curve
/// on the surface is the degree-1 B-spline through the loop's points (so that they read back
/// as they are); the first loop is the outer boundary. An untrimmed face is bounded by its
/// surface's natural boundary. Otherwise as write_mold(const BuiltinFace&, ...).
Status write_mold(const FaceData& face, const std::string& path,
                  const MoldWriteOptions& options = {});

/// Writes the faces of `shell` as one mold file, sewn into a shell where OpenCASCADE's sewing
/// (BRepBuilderAPI_Sewing, tolerance: the shell's, at least twice the trim tolerance of the
/// largest face) joins them; faces it cannot join stay apart in the file. A face whose loops
/// all lie on its domain's border is bounded by its surface's natural boundary (seams and
/// collapsed edges as OpenCASCADE makes them); any other face by its loops, each cut into one
/// edge per run of segments on the same shared edge (degree-1 curves on the surface through
/// the loop's points; runs whose surface image is a point are collapsed edges). Each face
/// carries FaceData::name (empty: "face N", N its index in the shell) and keeps plyfit's
/// orientation. Otherwise as write_mold(): atomic, 17 significant digits, fixed time stamp,
/// errors naming the file and the face.
Status write_shell(const ShellData& shell, const std::string& path,
                   const MoldWriteOptions& options = {});

}  // namespace plyfit::exporters
