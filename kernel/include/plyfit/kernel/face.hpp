#pragma once
/// \file Faces: a NURBS surface with trim loops, and the small interface the drape sees.

#include <plyfit/kernel/nurbs_curve.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace plyfit {

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

/// A pole of a drape surface: an edge of one face's parameter domain that the surface
/// collapses to one 3D point (a sphere's pole, a cone's apex, any NURBS whose first or last
/// row of poles coincides). Near it (u, v) is polar: the solvers find points there through
/// the fan of derivatives along the edge (Face::poles).
struct Pole {
  SurfaceLocation at;         ///< a location on the edge (its free parameter mid-range)
  bool u_fixed = true;        ///< the edge is u = at.uv.x() (v runs along it), else v = at.uv.y()
  double lo = 0.0, hi = 1.0;  ///< range of the free parameter along the edge
  double inward = 1.0;        ///< sign of a step of the fixed parameter into the domain
  Vec3 point = Vec3::Zero();  ///< the edge's one 3D point
  /// The location on the edge at free parameter t.
  SurfaceLocation on_edge(double t) const {
    return at.with_uv(u_fixed ? Vec2(at.uv.x(), t) : Vec2(t, at.uv.y()));
  }
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

/// What the drape needs from a mold: evaluation, the in/out test, moving across seams and
/// (for a shell of several faces) shared edges, projection, the boundary. One face (Face) and
/// a shell of faces (Shell) implement it; the scan and the solvers only see this.
class DrapeSurface {
 public:
  virtual ~DrapeSurface() = default;
  /// Point and first derivatives at a location (wrapped across closed seams first).
  virtual SurfaceEval1 eval1(const SurfaceLocation& at) const = 0;
  /// Point and derivatives up to second order.
  virtual SurfaceEval2 eval2(const SurfaceLocation& at) const = 0;
  /// Unit outward normal (the face's orientation applied), with its limit at poles.
  virtual SurfaceNormal normal(const SurfaceLocation& at) const = 0;
  /// +1 when the outward normal at `at` is Su x Sv of its face, -1 when that face is reversed.
  virtual double orientation(const SurfaceLocation& at) const = 0;
  /// True when the derivatives in `e`, evaluated at `at`, span no tangent plane: a pole or
  /// collapsed edge.
  virtual bool degenerate(const SurfaceLocation& at, const SurfaceEval1& e) const = 0;
  /// True when the location lies on the surface: in its face's domain and trims (on a shell,
  /// also within the sewing gap of a shared edge).
  virtual bool contains(const SurfaceLocation& at) const = 0;
  /// Parameter domain of the surface of the face `at` lies on (its chart).
  virtual const ParamDomain& domain(const SurfaceLocation& at) const = 0;
  /// Characteristic parametric speeds |dS/du|, |dS/dv| of the face `at` lies on (for scaling
  /// parameter tolerances).
  virtual Vec2 speeds(const SurfaceLocation& at) const = 0;
  /// The location with its parameters moved into the domain across closed seams.
  virtual SurfaceLocation wrap(const SurfaceLocation& at) const = 0;
  /// The point reached from `from` by going straight in its face's parameters to `uv`: on
  /// one face, (uv, from.face) itself (wrapped or not); on a shell, where that path crosses a
  /// shared edge it continues on the neighbouring face (the crossing point's 3D position
  /// mapped to the neighbour's (u, v), the rest of the step carried over through the tangent
  /// planes), never on this face's surface extended past the edge. A path across a free edge
  /// stays on its face, past the edge.
  virtual SurfaceLocation locate(const SurfaceLocation& from, const Vec2& uv) const = 0;
  /// True when two locations' parameters can be combined directly: they are on one face.
  bool same_chart(const SurfaceLocation& a, const SurfaceLocation& b) const {
    return a.face == b.face;
  }
  /// The parameter step in `from`'s face that leads to `to`: on one face to - from, taken the
  /// short way across closed seams; between two faces, to first order through the tangent
  /// plane at `from` (3D difference of the points).
  virtual Vec2 delta(const SurfaceLocation& from, const SurfaceLocation& to) const = 0;
  /// Nearest point of the surface to p.
  virtual Projection project(const Vec3& p) const = 0;
  /// Characteristic size of the surface (bounding-box diagonal), model units.
  virtual double size() const = 0;
  /// Area of the surface (its faces' areas summed), model units squared.
  virtual double area() const = 0;
  /// True when the surface can close on itself: a face closed across a seam, or a shell that
  /// is not a disc (a tube, a closed body). A drape on it tests every node for overlap.
  virtual bool closes_on_itself() const = 0;
  /// Number of faces (1 for a single face).
  virtual std::int32_t face_count() const = 0;
  /// The free boundary (see BoundaryLoop): trim loops, or a face's domain rectangle; never
  /// the edges shared by two faces of a shell.
  virtual std::vector<BoundaryLoop> boundary() const = 0;
  /// Bounding box of the surface (points sampled on its faces).
  virtual BBox3 bbox() const = 0;
  /// Area of face k (0 <= k < face_count()).
  virtual double face_area(std::int32_t k) const = 0;
  /// What double rounding makes a point of face k uncertain by, model units
  /// (NurbsSurface::rounding).
  virtual double face_rounding(std::int32_t k) const = 0;
  /// The largest face_rounding of the surface's faces: the solvers' floor for eq. (9).
  virtual double rounding() const = 0;
  /// The location of point p, which a solve reached at `at` off at's face, on the surface
  /// where it holds p within `reach` (3D): on at's face itself when `at` lies past one of its
  /// poles (the surface extended past a collapsed edge, as a sphere's, continues it across
  /// the pole), on a shell's neighbour past a pole the faces share, or on one reached without
  /// crossing their shared edge; `at` itself where no such location is found.
  virtual SurfaceLocation settle(const SurfaceLocation& at, const Vec3& p, double reach) const {
    (void)p;
    (void)reach;
    return at;
  }
  /// True when `at` lies in a hole of its face: off the face, but inside the face's parameter
  /// domain and its outer trim loop, so that the face's surface runs on under the hole (a
  /// drape goes on across it on that surface, see DrapeNode::kInHole). False past the outer
  /// loop or the domain, and on a surface that has no such holes.
  virtual bool in_hole(const SurfaceLocation& at) const {
    (void)at;
    return false;
  }
  /// Crease angle (radians) between the faces of two locations: the largest angle between
  /// their outward normals along the shared edges joining them; 0 on one face.
  virtual double crease_angle(const SurfaceLocation& a, const SurfaceLocation& b) const {
    (void)a;
    (void)b;
    return 0.0;
  }
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
};

/// A validated face. Evaluation beyond the domain extends the surface past its edges.
class Face final : public DrapeSurface {
 public:
  /// Validates the surface and the loops (each loop >= 3 finite points).
  static Result<Face> create(FaceData data, const Tolerances& tol = {});

  const NurbsSurface& surface() const { return *surface_; }
  const std::vector<TrimLoop>& loops() const { return loops_; }
  bool trimmed() const { return !loops_.empty(); }
  const std::string& name() const { return name_; }
  /// The same face with its orientation reversed (its normal flipped).
  Face flipped() const {
    Face f = *this;
    f.reversed_ = !f.reversed_;
    return f;
  }
  bool closed_u() const { return closed_u_; }
  bool closed_v() const { return closed_v_; }

  /// The face boundary as closed (u, v) polylines: the trim loops, or the domain rectangle.
  std::vector<std::vector<Vec2>> boundary_loops() const;
  /// Bounding box of points sampled on the face.
  BBox3 bbox() const override { return bbox_; }
  /// Parameter domain of the face's surface.
  const ParamDomain& domain() const { return surface_->domain(); }
  /// Characteristic parametric speeds |dS/du|, |dS/dv|.
  Vec2 speeds() const { return Vec2(surface_->speed_u(), surface_->speed_v()); }
  /// +1 when the outward normal is Su x Sv, -1 when the face is reversed.
  double orientation() const { return reversed_ ? -1.0 : 1.0; }
  /// True when the derivatives in `e` span no tangent plane (a pole or collapsed edge).
  bool degenerate(const SurfaceEval1& e) const { return surface_->is_degenerate(e.du, e.dv); }
  /// uv moved into the domain across closed seams (identity for open directions).
  Vec2 wrap(const Vec2& uv) const {
    Vec2 w = uv;
    const auto& d = domain();
    if (closed_u_ && (w.x() < d.u0 || w.x() > d.u1)) {
      const double P = d.width_u();
      w.x() = d.u0 + (w.x() - d.u0) - P * std::floor((w.x() - d.u0) / P);
    }
    if (closed_v_ && (w.y() < d.v0 || w.y() > d.v1)) {
      const double P = d.width_v();
      w.y() = d.v0 + (w.y() - d.v0) - P * std::floor((w.y() - d.v0) / P);
    }
    return w;
  }
  /// to - from, taken the short way across closed seams.
  Vec2 delta(const Vec2& from, const Vec2& to) const {
    Vec2 d = to - from;
    const auto& dom = domain();
    if (closed_u_) d.x() -= dom.width_u() * std::round(d.x() / dom.width_u());
    if (closed_v_) d.y() -= dom.width_v() * std::round(d.y() / dom.width_v());
    return d;
  }
  /// True when uv (after wrapping) lies on the face: in the domain and inside the trims.
  bool contains(const Vec2& uv) const;
  /// True when uv (after wrapping) is off the face but in the domain and inside the outer
  /// trim loop (the loop of largest (u, v) area): in a hole (see DrapeSurface::in_hole).
  bool in_hole(const Vec2& uv) const;
  /// The nearest point of the face to p by a damped Newton iteration from `seed` (parameters
  /// kept in the domain, on the face when `on_face`); ok is false if it cannot evaluate.
  Projection project_from(const Vec3& p, const Vec2& seed, bool on_face) const;

  // DrapeSurface (face 0 only).
  SurfaceEval1 eval1(const SurfaceLocation& at) const override;
  SurfaceEval2 eval2(const SurfaceLocation& at) const override;
  SurfaceNormal normal(const SurfaceLocation& at) const override;
  double orientation(const SurfaceLocation&) const override { return orientation(); }
  bool degenerate(const SurfaceLocation&, const SurfaceEval1& e) const override {
    return degenerate(e);
  }
  bool contains(const SurfaceLocation& at) const override { return contains(at.uv); }
  const ParamDomain& domain(const SurfaceLocation&) const override { return domain(); }
  Vec2 speeds(const SurfaceLocation&) const override { return speeds(); }
  SurfaceLocation wrap(const SurfaceLocation& at) const override { return {wrap(at.uv), at.face}; }
  SurfaceLocation locate(const SurfaceLocation& from, const Vec2& uv) const override {
    return {uv, from.face};
  }
  Vec2 delta(const SurfaceLocation& from, const SurfaceLocation& to) const override {
    return delta(from.uv, to.uv);
  }
  Projection project(const Vec3& p) const override;
  double size() const override { return size_; }
  /// Area of the face (given, or by Gauss quadrature over the domain with the trims).
  double area() const override { return area_; }
  bool closes_on_itself() const override { return closed_u_ || closed_v_; }
  double face_area(std::int32_t) const override { return area_; }
  double face_rounding(std::int32_t) const override { return surface_->rounding(); }
  double rounding() const override { return surface_->rounding(); }
  std::int32_t face_count() const override { return 1; }
  std::vector<BoundaryLoop> boundary() const override;
  SurfaceLocation settle(const SurfaceLocation& at, const Vec3& p, double reach) const override;
  bool in_hole(const SurfaceLocation& at) const override { return in_hole(at.uv); }
  /// The face's poles: domain edges its surface collapses to one point (found once).
  const std::vector<Pole>& poles() const { return poles_; }

 private:
  Face() = default;
  bool inside_trims(const Vec2& uv) const;
  bool inside_trims_fast(const Vec2& uv) const;  // cells_ first, then inside_trims
  void build_slabs();
  double compute_area() const;

  std::shared_ptr<const NurbsSurface> surface_;
  std::vector<TrimLoop> loops_;
  bool reversed_ = false, closed_u_ = false, closed_v_ = false;
  bool natural_ = false;  // the one loop runs along the domain's border
  int outer_ = -1;        // the outer loop (largest (u, v) area) when there are holes, else -1
  std::string name_;
  double area_ = 0.0;
  BBox3 bbox_;
  double size_ = 1.0;
  Tolerances tol_;
  std::vector<Pole> poles_;
  // Trim segments sorted into horizontal slabs for the crossing-number test.
  struct Seg {
    Vec2 a, b;
  };
  std::vector<Seg> segs_;
  std::vector<std::vector<int>> slabs_;
  double slab_v0_ = 0.0, slab_h_ = 1.0;
  Vec2 loops_min_ = Vec2::Zero(), loops_max_ = Vec2::Zero();
  // Cells of the loops' box classified as inside, outside or touched by the boundary.
  static constexpr std::uint8_t kCellUnknown = 0, kCellInside = 1, kCellOutside = 2,
                                kCellBoundary = 3;
  std::vector<std::uint8_t> cells_;
  int cells_n_ = 1;
  Vec2 cell_size_ = Vec2::Ones();
};

/// Samples the face on a grid of about n x n points per direction (more for many knot
/// spans) and returns the contained samples' (uv, point) pairs; used for projection seeds,
/// bounding boxes and area.
std::vector<std::pair<Vec2, Vec3>> sample_face(const Face& face, int n);

}  // namespace plyfit
