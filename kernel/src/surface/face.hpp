#pragma once
/// \file Faces: a NURBS surface with trim loops.

#include "surface/drape_surface.hpp"

#include <plyfit/kernel/nurbs.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace plyfit {

/// A validated face. Evaluation beyond the domain extends the surface past its edges.
class Face final : public DrapeSurface {
 public:
  /// Validates the surface and the loops (each loop >= 3 finite points).
  static Result<Face> create(FaceData data, const Tolerances& tol = {});

  const NurbsSurface& surface() const { return *surface_; }
  const std::vector<TrimLoop>& loops() const { return loops_; }
  bool trimmed() const { return !loops_.empty(); }
  const std::string& name() const { return name_; }
  /// The plain data of the face (its area left to be measured again; its surface shared).
  FaceData data() const {
    FaceData d;
    d.surface = surface_->data();
    d.loops = loops_;
    d.reversed = reversed_;
    d.closed_u = closed_u_;
    d.closed_v = closed_v_;
    d.name = name_;
    d.built = surface_;
    return d;
  }
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
    if (closed_u_) d.x() = shortest(d.x(), dom.width_u());
    if (closed_v_) d.y() = shortest(d.y(), dom.width_v());
    return d;
  }
  /// x less the whole periods P nearest to it. Most steps are shorter than half a period:
  /// std::round (a call into libm) only when the quotient says otherwise; the same result.
  static double shortest(double x, double P) {
    const double q = x / P;
    return std::abs(q) < 0.5 ? x : x - P * std::round(q);
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
  SurfaceEval1 eval1(const SurfaceLocation& at) const override {
    const Vec2 w = wrap(at.uv);
    return surface_->eval1(w.x(), w.y());
  }
  SurfaceEval2 eval2(const SurfaceLocation& at) const override {
    const Vec2 w = wrap(at.uv);
    return surface_->eval2(w.x(), w.y());
  }
  SurfaceNormal normal(const SurfaceLocation& at) const override {
    const Vec2 w = wrap(at.uv);
    SurfaceNormal n = surface_->normal(w.x(), w.y());
    if (reversed_) n.n = -n.n;
    return n;
  }
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
  // The bounding box and size from samples on the face, and the area (given_area if > 0).
  Status measure(double given_area);
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
  // project()'s seeds: points sampled on the face, taken on the first projection (every drape
  // projects its start; most faces are never projected onto, so not at create) and shared by
  // the face's copies (the samples do not depend on its orientation).
  struct ProjectSamples {
    std::once_flag once;
    std::vector<std::pair<Vec2, Vec3>> points;
  };
  std::shared_ptr<ProjectSamples> project_samples_ = std::make_shared<ProjectSamples>();
};

/// Samples the face on a grid of about n x n points per direction (more for many knot
/// spans) and returns the contained samples' (uv, point) pairs; used for projection seeds,
/// bounding boxes and area.
std::vector<std::pair<Vec2, Vec3>> sample_face(const Face& face, int n);

/// The area on surface `s` of the region of (u, v) loops within its domain whose rings run
/// as a polygon boolean gives them (outer rings one way, holes the other): Green's theorem,
/// the integral over the loops of F dv with F(u, v) the area element integrated from the
/// domain's u0 to u (Gauss rules per knot span, exact along straight (u, v) segments to the
/// rules' order, where the adaptive quadrature of compute_area() converges only to first
/// order at trims).
double boundary_area(const NurbsSurface& s, const std::vector<std::vector<Vec2>>& loops);

}  // namespace plyfit
