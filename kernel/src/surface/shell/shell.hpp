#pragma once
/// \file Shells: several faces of a mold sewn along shared edges, draped as one surface.

#include "surface/face.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace plyfit {

/// Several faces sewn along shared edges, draped as one surface: the drape crosses shared
/// edges as if they were not there and stops only at free edges, trims and holes.
///
/// A location on a shell is a face and (u, v) on it. Moving in a face's parameters across a
/// shared edge (locate()) continues on the neighbouring face: the crossing point of the
/// face's boundary polyline is mapped in 3D to the neighbour's (u, v) (nearest point of the
/// neighbour's polyline of that edge, then a projection onto its surface), and the rest of
/// the step is carried over by unfolding it about the edge: its component along the edge is
/// kept, its component across the edge turned into the neighbour's tangent plane. Neither
/// face is ever extended past a shared edge. A point within the sewing gap of a shared edge
/// (between the two faces' polylines) is on the shell.
class Shell final : public DrapeSurface {
 public:
  /// Validates every face (Face::create) and the shared edges (each used by exactly two
  /// faces, their two sides within the sewing gap), orients the faces consistently and finds
  /// the free boundary; errors name the face or edge.
  static Result<Shell> create(ShellData data, const Tolerances& tol = {});

  /// Face k (0 <= k < face_count()).
  const Face& face(std::int32_t k) const { return *faces_[static_cast<std::size_t>(k)]; }
  /// Index of face k in its mold file.
  int source_face(std::int32_t k) const { return source_[static_cast<std::size_t>(k)]; }
  /// Number of shared edges.
  std::int32_t edge_count() const { return static_cast<std::int32_t>(edges_.size()); }
  /// The two faces of shared edge e.
  std::pair<std::int32_t, std::int32_t> edge_faces(std::int32_t e) const;
  /// Largest angle between the outward normals of the two faces along shared edge e
  /// (radians, sampled along the edge): 0 where they join tangentially (G1), the crease
  /// angle where they meet at a crease (G0 only).
  double crease_angle(std::int32_t e) const { return edges_[static_cast<std::size_t>(e)].crease; }
  /// Largest crease angle over the shared edges between faces f and g (0 if none).
  double crease_angle(std::int32_t f, std::int32_t g) const;
  /// Euler characteristic V - E + F of the shell (collapsed edges left out) and its number
  /// of free boundary loops: a disc has 1 and 1.
  int euler_characteristic() const { return euler_; }
  int free_loop_count() const { return static_cast<int>(boundary_.size()); }
  /// The plain data of the shell: its faces' (as oriented), edges and sewing tolerance.
  ShellData data() const;
  /// The sewing gap: points this close (3D) to a shared edge are on the shell.
  double gap() const { return gap_; }

  SurfaceEval1 eval1(const SurfaceLocation& at) const override {
    return face(at.face).eval1(at.uv);
  }
  SurfaceEval2 eval2(const SurfaceLocation& at) const override {
    return face(at.face).eval2(at.uv);
  }
  SurfaceNormal normal(const SurfaceLocation& at) const override {
    return face(at.face).normal(at.uv);
  }
  double orientation(const SurfaceLocation& at) const override {
    return face(at.face).orientation();
  }
  bool degenerate(const SurfaceLocation& at, const SurfaceEval1& e) const override {
    return face(at.face).degenerate(e);
  }
  bool contains(const SurfaceLocation& at) const override;
  const ParamDomain& domain(const SurfaceLocation& at) const override {
    return face(at.face).domain();
  }
  Vec2 speeds(const SurfaceLocation& at) const override { return face(at.face).speeds(); }
  SurfaceLocation wrap(const SurfaceLocation& at) const override {
    return {face(at.face).wrap(at.uv), at.face};
  }
  SurfaceLocation locate(const SurfaceLocation& from, const Vec2& uv) const override;
  Vec2 delta(const SurfaceLocation& from, const SurfaceLocation& to) const override {
    if (from.face == to.face) return face(from.face).delta(from.uv, to.uv);
    return delta_between_faces(from, to);
  }
  Projection project(const Vec3& p) const override;
  double size() const override { return size_; }
  double area() const override { return area_; }
  bool closes_on_itself() const override { return closes_; }
  std::int32_t face_count() const override { return static_cast<std::int32_t>(faces_.size()); }
  std::vector<BoundaryLoop> boundary() const override { return boundary_; }
  BBox3 bbox() const override { return bbox_; }
  double face_area(std::int32_t k) const override { return face(k).area(); }
  double face_rounding(std::int32_t k) const override { return face(k).rounding(); }
  double rounding() const override { return rounding_; }
  SurfaceLocation settle(const SurfaceLocation& at, const Vec3& p, double reach) const override;
  /// In a hole of the location's face that no neighbour face's sewing gap covers.
  bool in_hole(const SurfaceLocation& at) const override {
    return face(at.face).in_hole(at.uv) && !contains(at);
  }
  double crease_angle(const SurfaceLocation& a, const SurfaceLocation& b) const override {
    return a.face == b.face ? 0.0 : crease_angle(a.face, b.face);
  }

  ~Shell() override;
  Shell(Shell&&) noexcept;
  Shell& operator=(Shell&&) noexcept;

 private:
  Shell();
  struct Topology;       // per face: boundary segments, their edges, inward sides (topology.hpp)
  class BoundaryTracer;  // the free boundary loops and the Euler characteristic
  struct Edge {
    // Per use (two): face, and the (u, v) points and 3D points of its polyline.
    std::int32_t face[2] = {-1, -1};
    std::vector<Vec2> uv[2];
    std::vector<Vec3> xyz[2];
    std::vector<int> seg[2];  // per polyline segment: the face's boundary segment
    double crease = 0.0;
  };

  // The steps of create() (build.cpp, orient.cpp, boundary_loops.cpp).
  Status check_tags(const ShellData& data) const;
  Status build_faces(ShellData& data);
  void build_topology(const std::vector<std::vector<TrimLoop>>& loops);
  void measure();
  Status build_edges(std::int32_t edge_count, double& gap);
  bool trace_use(Edge& E, int u, std::int32_t k, std::int32_t e) const;
  Status set_gap(double measured, double tolerance);
  Status orient();
  double agreement(std::int32_t e) const;
  Vec3 inward_3d(std::int32_t face, std::int32_t e, const Vec2& uv, const SurfaceEval1& ev) const;
  void measure_creases();
  void trace_boundary();
  void find_neighbours();
  void add_neighbour(std::int32_t f, std::int32_t g, const Vec2& seed);

  // Moving across shared edges (locate.cpp).
  SurfaceLocation locate_from(const SurfaceLocation& from, const Vec2& uv, std::int32_t except,
                              int depth) const;
  bool outward(std::int32_t face, int si, const Vec2& r) const;
  int first_crossing(std::int32_t face, const Vec2& p, const Vec2& q, std::int32_t except,
                     double& t) const;
  Vec2 delta_between_faces(const SurfaceLocation& from, const SurfaceLocation& to) const;
  bool near_shared_edge(std::int32_t face, const Vec2& uv, int* segment) const;
  SurfaceLocation cross_edge(std::int32_t face, int segment, const Vec2& x, const Vec2& rest,
                             Vec2* rest_out) const;
  Vec3 unfold(const Vec2& df, double inward, const SurfaceEval1& ef, std::int32_t g, int gs,
              const SurfaceEval1& eg, const Vec2& rest) const;

  std::vector<std::unique_ptr<Face>> faces_;
  std::vector<int> source_;
  std::vector<Edge> edges_;
  std::unique_ptr<Topology> topo_;
  std::vector<BoundaryLoop> boundary_;
  // Per face: the faces that share an edge or a pole with it, and a (u, v) on each near the
  // shared part (seeds for settle()).
  struct Neighbour {
    std::int32_t face;
    std::vector<Vec2> seeds;
  };
  std::vector<std::vector<Neighbour>> neighbours_;
  Tolerances tol_;
  double tolerance_ = 0.0;  // the sewing tolerance given
  double gap_ = 0.0, size_ = 1.0, area_ = 0.0, rounding_ = 0.0;
  BBox3 bbox_;
  int euler_ = 1;
  bool closes_ = false;
};

}  // namespace plyfit
