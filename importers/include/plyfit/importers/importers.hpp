#pragma once
/// \file Mold importers: a registry of one-file plugins keyed by lower-case extension.
///
/// Opening a file reads it and lists its faces (kernel::Mold) without converting any
/// surface; a face is converted to kernel data only when asked for.

#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace plyfit::importers {

/// Options of every importer.
struct ImportOptions {
  /// Importer key that overrides the file extension ("step", "iges"); empty: by extension.
  std::string format;
  /// Tolerances; trim_chord_rel sets the accuracy of trim polylines.
  Tolerances tolerances;
  /// Reading stops with an error when transferring the file's entities takes longer than
  /// this (seconds): a corrupt file can make the reader's repairs run a very long time.
  double time_limit_s = 120.0;
  /// Sewing tolerance for convert_shell (mm); 0: from the file (see MoldFile::convert_shell).
  double sewing_tolerance = 0.0;
};

/// An opened mold file. Faces are indexed 0.. in the order of a depth-first walk of the file's
/// transferred shapes (OpenCASCADE's TopExp::MapShapes over faces: solids, shells and
/// compounds in file order, each face once). Lengths are in millimetres whatever the file's
/// unit. Not thread-safe.
class MoldFile {
 public:
  virtual ~MoldFile() = default;
  /// The file's faces and metadata, listed without converting surfaces (the per-face entries
  /// are computed on the first call; convert_face() alone does not compute the others). Areas
  /// are plyfit's integration to 1e-6 relative (estimated; a face short of it is named in the
  /// warnings), except for faces already described, whose areas are to 1e-9.
  virtual const Mold& mold() const = 0;
  /// Number of faces (no listing computed).
  virtual int face_count() const = 0;
  /// The entry of face `index` alone (computed once), with its area to 1e-9 relative
  /// (estimated: the area a drape reports; short of it, the file's warnings say so), or an
  /// error naming the file and the face.
  virtual Result<FaceInfo> describe(int index) const = 0;
  /// The file's metadata (source, format, schema, unit, reader warnings) without computing
  /// the face entries (those not described yet are placeholders of kind "unknown").
  virtual const Mold& summary() const = 0;
  /// Converts face `index` (0-based, as listed) to kernel data: the surface as NURBS
  /// restricted to the face (periodic surfaces clamped, closed_u/v set when the face spans a
  /// whole period), its trim loops in (u, v) as polylines within
  /// tolerances.trim_chord_rel * face size (none for a face bounded by its surface's natural
  /// boundary), its orientation (reversed), area and name. Converts that face alone.
  virtual Result<FaceData> convert_face(int index) = 0;
  /// Sews faces `indices` (each once, in any order; empty: every face of the file) into a
  /// shell and converts them: faces[k] is face indices[k] converted as convert_face() does
  /// (same NURBS, closed_u/v), but with explicit trim loops whose segments name the shared
  /// edge they lie on (ShellData, TrimLoop::edges). OpenCASCADE's BRepBuilderAPI_Sewing
  /// (manifold) joins edges closer than the sewing tolerance: options.sewing_tolerance, else the
  /// larger of the file's precision (STEP uncertainty, IGES resolution) and the largest
  /// tolerance of the faces' edges, clamped to [1e-7 mm, 1e-4 * shell size]. A shared edge
  /// bounds exactly two of the faces; an edge of one face is free, so is a closed face's seam;
  /// an edge of more than two faces is free with a warning. Faces are oriented consistently
  /// across shared edges, each connected part of the shell keeping the file's orientation on
  /// most of its faces (the others are reversed, with a warning). Several connected parts are
  /// allowed, with a warning. Warnings are appended to summary().warnings. Errors (an index out
  /// of range or repeated, a face that does not convert, sewing that fails) name the file and
  /// the faces.
  virtual Result<ShellData> convert_shell(const std::vector<int>& indices) = 0;
  /// Every face index of the file, 0 .. face_count() - 1.
  std::vector<int> all_faces() const;
};

/// A curve of a file (a free 3D curve, a wire's edge, or a face's edge when the file has no
/// other): one edge of the file's shape as a polyline within tolerances.curve_chord_rel of the
/// curves' size (their bounding-box diagonal).
struct FileCurve {
  int index = 0;        ///< 0.. in the order of a depth-first walk of the file's edges
  std::string name;     ///< the entity's name or label in the file, may be empty
  std::string kind;     ///< line, circle, ellipse, bspline, ...
  bool closed = false;  ///< its ends are one vertex (a closed curve); then the last point is not
                        ///< repeated
  double length = 0.0;  ///< mm, of the exact curve
  std::vector<Vec3> points;  ///< mm, in the edge's direction
};

/// A registered importer.
struct Importer {
  std::string key;                      ///< e.g. "step"
  std::vector<std::string> extensions;  ///< lower-case, without the dot
  std::string description;              ///< one line for help texts
  /// Opens a file: reads it and lists its faces (see MoldFile), or returns an Error naming the
  /// file and the problem.
  std::function<Result<std::unique_ptr<MoldFile>>(const std::string& path,
                                                  const ImportOptions& options)>
      open;
  /// Reads a file's curves (see FileCurve): free curves and wire edges, else face edges; an
  /// empty list when it has none. Errors name the file and the problem.
  std::function<Result<std::vector<FileCurve>>(const std::string& path,
                                               const ImportOptions& options)>
      curves;
};

/// All registered importers, in registration order.
const std::vector<Importer>& registry();
/// Importer for a key or extension (case-insensitive), or nullptr.
const Importer* find_importer(const std::string& key_or_extension);
/// Comma-separated list of supported extensions, for error messages.
std::string supported_extensions();

/// Opens `path` with the importer named by options.format or by the file's extension.
/// Errors name the file and the problem (missing, unreadable, corrupt, unknown extension,
/// no faces).
Result<std::unique_ptr<MoldFile>> open_mold(const std::string& path,
                                            const ImportOptions& options = {});

/// The curves of `path` (Importer::curves), read with the importer named by options.format or
/// by the file's extension.
Result<std::vector<FileCurve>> read_curves(const std::string& path,
                                           const ImportOptions& options = {});

/// Opens `path` and converts face `index` into a surface ready to drape.
Result<MoldSurface> load_face(const std::string& path, int index,
                              const ImportOptions& options = {});

/// Opens `path` and sews faces `indices` (empty: all) into a shell (MoldFile::convert_shell).
/// `warnings`, when given, receives the file's reader and sewing warnings.
Result<ShellData> load_shell(const std::string& path, const std::vector<int>& indices,
                             const ImportOptions& options = {},
                             std::vector<Warning>* warnings = nullptr);

}  // namespace plyfit::importers
