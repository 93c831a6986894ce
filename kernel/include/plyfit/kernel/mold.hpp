#pragma once
/// \file Molds: what a mold file holds (listed before any face is converted), the plain data
/// of faces and shells (NURBS + trims, mm; shared edges) that importers and built-in molds
/// produce, and MoldSurface, a face or shell ready to drape.

#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace plyfit {

/// One face of a mold, described without converting its surface.
struct FaceInfo {
  int index = 0;                   ///< stable index (see the importers' documentation)
  std::string name;                ///< name or label from the file, may be empty
  std::string kind;                ///< original surface kind: bspline, bezier, plane, cylinder, ...
  int degree_u = 0, degree_v = 0;  ///< degrees (0 when the kind has none, e.g. a plane)
  int poles_u = 0, poles_v = 0;    ///< pole counts (0 when the kind has none)
  bool rational = false;
  bool trimmed = false;   ///< bounded by trim loops other than its natural boundary
  int holes = 0;          ///< inner loops
  bool reversed = false;  ///< the face's orientation reverses its surface normal
  double area = 0.0;      ///< area, mm^2 (0 when not measured)
  /// False for a face whose area could not be measured (an invalid face: its boundary does not
  /// bound a region of its surface that an integration within its work cap can measure).
  bool area_measured = true;
  BBox3 bbox;  ///< bounding box, mm
  /// The faces it shares an edge with in the file's own topology (indices, ascending; no
  /// sewing: faces written apart share none), and how many of its edges no other face
  /// shares (seams excepted); -1 when the file's topology was not read.
  std::vector<int> neighbours = {};
  int free_edges = -1;
};

/// A mold file's content: its faces and where they come from.
struct Mold {
  std::string source;  ///< file path, or "builtin:NAME..." for a built-in mold
  std::string format;  ///< importer key (step, iges) or "builtin"
  std::string schema;  ///< file schema / flavour (e.g. AUTOMOTIVE_DESIGN, IGES 5.3)
  std::string unit;    ///< the file's length unit; geometry is converted to millimetres
  std::vector<FaceInfo> faces;
  /// What reading, listing and sewing it found that did not stop them (codes with data: the
  /// reader's own messages, summarised, faces whose area falls short, separate shells, ...).
  std::vector<Warning> warnings;
};

/// A point of a drape surface: the face it lies on and its parameters (u, v) there. The face
/// is the chart the parameters belong to; a surface of one face has only face 0. The drape's
/// scan and solvers hold locations and hand them back to the surface; they never look at the
/// face themselves.
struct SurfaceLocation {
  Vec2 uv = Vec2::Zero();
  std::int32_t face = 0;
  SurfaceLocation() = default;
  /// Parameters on face `f` (implicit from (u, v), any Eigen expression of them: a point of a
  /// one-face surface).
  template <typename Derived>
  SurfaceLocation(const Eigen::MatrixBase<Derived>& p, std::int32_t f = 0)  // NOLINT
      : uv(p), face(f) {}
  /// Parameters `p` on the same face (chart).
  SurfaceLocation with_uv(const Vec2& p) const { return {p, face}; }
  bool operator==(const SurfaceLocation& o) const { return uv == o.uv && face == o.face; }
  bool operator!=(const SurfaceLocation& o) const { return !(*this == o); }
};

/// Nearest point of a surface to a query point.
struct Projection {
  SurfaceLocation at;
  Vec3 point = Vec3::Zero();
  double distance = 0.0;  ///< |point - query|
  bool ok = false;        ///< false if no point of the surface could be evaluated
};

/// The free boundary of a surface as its faces' parameters see it: a closed polyline of
/// locations that the drape cannot cross. Segment k joins points k and k + 1 (the last one
/// back to point 0), on one face, or on two faces where the boundary passes from one face
/// to the next at a corner of a shell. A segment that is no boundary is kept, marked, so
/// that the loop stays closed: a collapsed edge (a pole: no 3D length) or the seam of a face
/// closed on itself (contains() is true on both sides).
struct BoundaryLoop {
  /// kJunction: a segment of no length joining two faces' copies of one 3D point (a corner
  /// of a shell where the free boundary passes from one face to the next).
  enum Kind : std::uint8_t { kEdge = 0, kCollapsed = 1, kSeam = 2, kJunction = 3 };
  std::vector<SurfaceLocation> points;
  std::vector<Kind> kinds;  ///< per segment
};

/// A closed polyline in the (u, v) plane; the first point is not repeated at the end.
struct TrimLoop {
  /// Marks a segment that lies on no shared edge: a free edge (or a seam of a closed face).
  static constexpr std::int32_t kFreeEdge = -1;
  std::vector<Vec2> points;
  /// For a face of a shell: the shared edge each segment lies on (segment k runs from
  /// points[k] to points[k + 1], the last one back to points[0]), an index into the shell's
  /// edges, or kFreeEdge. Empty: every segment is free (a face on its own).
  std::vector<std::int32_t> edges = {};
};

/// Plain data of a face, as importers and built-in molds produce it.
struct FaceData {
  NurbsSurfaceData surface;
  /// Trim loops in (u, v): empty for an untrimmed face (the whole domain). One outer loop
  /// and any number of holes; containment is even-odd over all loops, so loop orientation
  /// does not matter for contains().
  std::vector<TrimLoop> loops;
  bool reversed = false;  ///< the face normal is -(Su x Sv)
  bool closed_u = false;  ///< the surface closes on itself across the u seam (u0 == u1)
  bool closed_v = false;  ///< likewise in v
  double area = -1.0;     ///< area if known (e.g. from the CAD kernel), else computed
  std::string name;       ///< name or label from the file, may be empty
  /// The validated surface of `surface` when its producer has built one (an importer that
  /// measured the face on it): Face::create takes it instead of building it again when it is
  /// made_from() `surface` and the tolerances, and builds its own otherwise. May be null.
  std::shared_ptr<const NurbsSurface> built = {};
};

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

/// A shared edge of a shell: the two faces it joins (positions in the shell) and how sharply.
struct SharedEdge {
  std::int32_t face_a = 0, face_b = 0;
  /// Largest angle between the two faces' outward normals along the edge (radians, sampled
  /// along it): 0 where they join tangentially, the crease angle at a crease.
  double crease = 0.0;
};

/// The free boundary of one face (the part of its boundary on no shared edge): its runs (each
/// a stretch between shared edges, or a whole loop with none) and their length (mm, along the
/// boundary polyline). Free edges that meet at a corner with no shared edge between them make
/// one run.
struct FreeBoundary {
  int runs = 0;
  double length = 0.0;
};

class DrapeSurface;  // the drape's view of a surface (kernel internal)

/// A face or a shell of faces, validated and ready to drape (drape(), flat_pattern()).
/// Cheap to copy (the surface is shared and immutable).
class MoldSurface {
 public:
  /// Validates one face (NURBS, trims); errors name the problem.
  static Result<MoldSurface> from_face(FaceData data, const Tolerances& tol = {});
  /// Validates a shell (every face, and every shared edge used by exactly two faces).
  static Result<MoldSurface> from_shell(ShellData data, const Tolerances& tol = {});
  /// Wraps a kernel surface (kernel internal).
  explicit MoldSurface(std::shared_ptr<const DrapeSurface> surface);

  /// Number of faces (1 for a single face).
  std::int32_t face_count() const;
  /// Area of face k.
  double face_area(std::int32_t k) const;
  /// What double rounding makes a point of face k uncertain by (mm): the floor of the solvers'
  /// residual on it.
  double face_rounding(std::int32_t k) const;
  /// Area of the surface (its faces' areas summed), mm^2.
  double area() const;
  /// Characteristic size (bounding-box diagonal), mm.
  double size() const;
  /// Bounding box of points sampled on the faces.
  BBox3 bbox() const;
  /// Point and first derivatives at a location.
  SurfaceEval1 eval1(const SurfaceLocation& at) const;
  /// Unit outward normal at a location.
  SurfaceNormal normal(const SurfaceLocation& at) const;
  /// Nearest point of the surface to p.
  Projection project(const Vec3& p) const;
  /// The free boundary loops.
  std::vector<BoundaryLoop> boundary() const;
  /// Parameter domain of the face `at` lies on.
  const ParamDomain& domain(const SurfaceLocation& at) const;
  /// The shared edges of a shell (none for a single face).
  std::vector<SharedEdge> shared_edges() const;
  /// Face k's free boundary.
  FreeBoundary free_boundary(std::int32_t k) const;

  /// The kernel's surface (kernel internal: its type is complete only inside the kernel).
  const DrapeSurface& impl() const { return *surface_; }

 private:
  std::shared_ptr<const DrapeSurface> surface_;
};

/// The faces of `surface` reached from face `seed` across shared edges whose crease angle is at
/// most `max_crease` (radians): the seed first, then breadth first (positions in the shell).
std::vector<std::int32_t> connected_faces(const MoldSurface& surface, std::int32_t seed,
                                          double max_crease);

/// The shell of some of `data`'s faces (positions, in the given order; each at most once):
/// edges shared by two of them keep joining them (renumbered), edges to a face left out are free.
ShellData sub_shell(const ShellData& data, const std::vector<std::int32_t>& faces);

}  // namespace plyfit
