#pragma once
/// \file Faces: a NURBS surface with trim loops, and the small interface the drape sees.

#include <plyfit/kernel/nurbs_curve.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace plyfit {

/// Nearest point of a face to a query point.
struct Projection {
  Vec2 uv = Vec2::Zero();
  Vec3 point = Vec3::Zero();
  double distance = 0.0;  ///< |point - query|
  bool ok = false;        ///< false if no point of the face could be evaluated
};

/// What the drape needs from a mold: evaluation, the in/out test, seams, projection.
/// Multi-face draping and other surface kinds implement this without touching the solvers.
class DrapeSurface {
 public:
  virtual ~DrapeSurface() = default;
  /// Point and first derivatives at uv (uv is wrapped across closed seams first).
  virtual SurfaceEval1 eval1(const Vec2& uv) const = 0;
  /// Point and derivatives up to second order.
  virtual SurfaceEval2 eval2(const Vec2& uv) const = 0;
  /// Unit outward normal of the face (orientation applied), with its limit at poles.
  virtual SurfaceNormal normal(const Vec2& uv) const = 0;
  /// +1 when the face normal is Su x Sv, -1 when the face is reversed.
  virtual double orientation() const = 0;
  /// True when the derivatives in `e` span no tangent plane (a pole or collapsed edge).
  virtual bool degenerate(const SurfaceEval1& e) const = 0;
  /// True when uv (after wrapping) lies on the face: in the domain and inside the trims.
  virtual bool contains(const Vec2& uv) const = 0;
  /// Parameter domain of the underlying surface.
  virtual const ParamDomain& domain() const = 0;
  /// uv moved into the domain across closed seams (identity for open directions).
  virtual Vec2 wrap(const Vec2& uv) const = 0;
  /// to - from, taken the short way across closed seams.
  virtual Vec2 delta(const Vec2& from, const Vec2& to) const = 0;
  /// Nearest point of the face to p.
  virtual Projection project(const Vec3& p) const = 0;
  /// Characteristic size of the face (bounding-box diagonal), model units.
  virtual double size() const = 0;
  /// Characteristic parametric speeds |dS/du|, |dS/dv| (for scaling parameter tolerances).
  virtual Vec2 speeds() const = 0;
  /// The face boundary as closed (u, v) polylines: trim loops, or the domain rectangle
  /// (whose edges across a closed seam are not boundaries: contains() is true on both sides).
  virtual std::vector<std::vector<Vec2>> boundary_loops() const = 0;
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
  bool closed_u() const { return closed_u_; }
  bool closed_v() const { return closed_v_; }

  std::vector<std::vector<Vec2>> boundary_loops() const override;
  /// Area of the face (given, or by Gauss quadrature over the domain with the trims).
  double area() const { return area_; }
  /// Bounding box of points sampled on the face.
  const BBox3& bbox() const { return bbox_; }

  SurfaceEval1 eval1(const Vec2& uv) const override;
  SurfaceEval2 eval2(const Vec2& uv) const override;
  SurfaceNormal normal(const Vec2& uv) const override;
  double orientation() const override { return reversed_ ? -1.0 : 1.0; }
  bool degenerate(const SurfaceEval1& e) const override {
    return surface_->is_degenerate(e.du, e.dv);
  }
  bool contains(const Vec2& uv) const override;
  const ParamDomain& domain() const override { return surface_->domain(); }
  Vec2 wrap(const Vec2& uv) const override;
  Vec2 delta(const Vec2& from, const Vec2& to) const override;
  Projection project(const Vec3& p) const override;
  double size() const override { return size_; }
  Vec2 speeds() const override { return Vec2(surface_->speed_u(), surface_->speed_v()); }

 private:
  Face() = default;
  bool inside_trims(const Vec2& uv) const;
  void build_slabs();
  double compute_area() const;

  std::shared_ptr<const NurbsSurface> surface_;
  std::vector<TrimLoop> loops_;
  bool reversed_ = false, closed_u_ = false, closed_v_ = false;
  std::string name_;
  double area_ = 0.0;
  BBox3 bbox_;
  double size_ = 1.0;
  Tolerances tol_;
  // Trim segments sorted into horizontal slabs for the crossing-number test.
  struct Seg {
    Vec2 a, b;
  };
  std::vector<Seg> segs_;
  std::vector<std::vector<int>> slabs_;
  double slab_v0_ = 0.0, slab_h_ = 1.0;
  Vec2 loops_min_ = Vec2::Zero(), loops_max_ = Vec2::Zero();
};

/// Samples the face on a grid of about n x n points per direction (more for many knot
/// spans) and returns the contained samples' (uv, point) pairs; used for projection seeds,
/// bounding boxes and area.
std::vector<std::pair<Vec2, Vec3>> sample_face(const Face& face, int n);

}  // namespace plyfit
