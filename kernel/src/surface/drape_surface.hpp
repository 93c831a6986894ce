#pragma once
/// \file DrapeSurface: the small interface the drape sees (one face or a shell), and poles.

#include <plyfit/kernel/mold.hpp>

#include <cstdint>
#include <vector>

namespace plyfit {

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

}  // namespace plyfit
