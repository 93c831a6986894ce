#pragma once
/// \file The 2D ply model of the paper (§3, §4.2.1): inextensible warp and weft threads on a
/// grid, a straight base path at any angle, and the auxiliary mesh points where the path
/// crosses threads, with the topology change of Fig. 7.
///
/// Ply coordinates are 2D, in model units. Regular node (i, j) is the crossing of warp
/// thread i (the vertical line x = i * d_weft) and weft thread j (the horizontal line
/// y = j * d_warp); a weft link joins (i, j) and (i + 1, j) with rest length d_weft, a warp
/// link joins (i, j) and (i, j + 1) with rest length d_warp. The base path is the line
/// start + tau * dir; path node k (k = 0 at the start, k > 0 ahead, k < 0 behind) is the
/// start or a crossing of the path with a thread. A path node that falls on a thread
/// crossing (within ply_merge_rel * d) is that regular node; a regular link the path crosses
/// strictly inside is split into two links to the path node, with their shorter rest
/// lengths.

#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace plyfit {

/// Identifies a node of the ply: a regular crossing (i, j) or path node k.
struct NodeId {
  static constexpr std::int32_t kPathMarker = INT32_MAX;
  std::int32_t i = 0, j = 0;  ///< regular: (i, j); path node k: (kPathMarker, k)
  static NodeId regular(std::int32_t i, std::int32_t j) { return {i, j}; }
  static NodeId path(std::int32_t k) { return {kPathMarker, k}; }
  bool is_path_only() const { return i == kPathMarker; }
  std::uint64_t key() const {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
           static_cast<std::uint32_t>(j);
  }
  bool operator==(const NodeId& o) const { return i == o.i && j == o.j; }
  bool operator!=(const NodeId& o) const { return !(*this == o); }
};

/// The four thread directions from a regular node: along the weft (+x, -x) and along the
/// warp (+y, -y).
enum class ThreadDir : std::uint8_t { kPlusX = 0, kMinusX = 1, kPlusY = 2, kMinusY = 3 };
/// The opposite direction.
inline ThreadDir opposite(ThreadDir d) {
  return static_cast<ThreadDir>(static_cast<int>(d) ^ 1);
}
/// True for the weft directions (+x, -x).
inline bool is_weft(ThreadDir d) {
  return static_cast<int>(d) < 2;
}

/// A node on the base path.
struct PathNode {
  double tau = 0.0;  ///< signed distance from the start along the path direction
  Vec2 pos;          ///< ply coordinates
  NodeId id;         ///< regular (i, j) if it falls on a crossing, else path(k)
  /// The thread link the node splits, if any: `link_from` and its direction (+x or +y).
  std::optional<NodeId> link_from;
  ThreadDir link_dir = ThreadDir::kPlusX;
};

/// A neighbour across a link, with the link's rest length.
struct PlyNeighbour {
  NodeId id;
  double rest = 0.0;
};

/// Input of the ply model.
struct PlySpec {
  double d_weft = 1.0;  ///< weft link length = spacing of the warp threads (along x)
  double d_warp = 1.0;  ///< warp link length = spacing of the weft threads (along y)
  /// Optional cloth rectangle [0, W] x [0, H]; absent: unbounded cloth.
  std::optional<Vec2> rect;
  Vec2 start = Vec2::Zero();      ///< start point of the base path (anywhere)
  Vec2 base_dir = Vec2::UnitX();  ///< base path direction (normalised on construction)
  /// Sweep directions, at most one per half-plane; none may be parallel to the base path.
  std::vector<Vec2> sweeps;
};

/// Checks sweep direction k (0-based, as given: any length) against the base path direction
/// `base_dir`: finite and non-zero, and at least tol.sweep_min_angle from the path (nearer, the
/// half-plane it sweeps would be decided by the last digits given). The error names "sweep
/// direction k+1" and the angle it makes.
Status check_sweep_direction(const Vec2& base_dir, const Vec2& sweep, std::size_t k,
                             const Tolerances& tol = {});

/// The ply: geometry of nodes, the base path (generated lazily both ways), the half-planes
/// and the links. Knows nothing of the surface.
class Ply {
 public:
  /// Validates the spec (positive finite spacings and rectangle, non-zero directions, sweeps
  /// as check_sweep_direction() asks and in different half-planes, start inside the
  /// rectangle).
  static Result<Ply> create(PlySpec spec, const Tolerances& tol = {});

  const PlySpec& spec() const { return spec_; }
  /// min(d_weft, d_warp): the scale of ply tolerances.
  double d() const { return d_; }
  /// 2D position of a regular node.
  Vec2 pos(std::int32_t i, std::int32_t j) const {
    return Vec2(i * spec_.d_weft, j * spec_.d_warp);
  }
  /// 2D position of any node (path nodes must have been generated).
  Vec2 pos(const NodeId& id) const;
  /// +1 or -1: the half-plane of a point (left or right of the path direction), 0 on the
  /// path (within the merge tolerance).
  int side(const Vec2& p) const;
  /// Index of the sweep direction for half-plane `side`, or -1 if that side is not swept.
  int sweep_for_side(int side) const {
    return side > 0 ? sweep_plus_ : side < 0 ? sweep_minus_ : -1;
  }
  /// Distance from the base path to p along its half-plane's sweep direction (eq. of §6.2's
  /// ordering); 0 on the path.
  double sweep_distance(const Vec2& p) const;
  /// True when p lies on the cloth (inside the rectangle, or always when unbounded).
  bool on_ply(const Vec2& p) const;

  /// Path node k, generating nodes up to k on demand. Returns nullptr if node k would lie off
  /// the ply (beyond the rectangle) or beyond `max_path_nodes` nodes either way.
  const PathNode* path_node(std::int32_t k);
  /// Path node k if already generated.
  const PathNode* path_node_if(std::int32_t k) const;
  /// If the regular node (i, j) lies on the path, its path index.
  std::optional<std::int32_t> path_index_of(std::int32_t i, std::int32_t j) const;

  /// Neighbour of regular node (i, j) in direction dir: the adjacent regular node, or the
  /// path node splitting the link (only if already generated; otherwise nullopt).
  std::optional<PlyNeighbour> neighbour(std::int32_t i, std::int32_t j, ThreadDir dir) const;
  /// Thread neighbours of a node: for a regular node its four neighbours (see neighbour());
  /// for a path-only node the two ends of the link it splits. Directions are reported as seen
  /// from the node.
  struct ThreadNeighbour {
    ThreadDir dir;
    PlyNeighbour n;
  };
  std::vector<ThreadNeighbour> thread_neighbours(const NodeId& id) const;

  /// The path direction (unit) and the first sweep direction etc. as given.
  const Vec2& base_dir() const { return spec_.base_dir; }

  /// Cap on generated path nodes either way (an unbounded ply's path ends at the surface).
  static constexpr std::int32_t kMaxPathNodes = 1 << 24;

 private:
  Ply() = default;
  bool generate_next(bool forward);
  std::optional<std::int32_t> path_index_at_tau(double tau) const;

  PlySpec spec_;
  double d_ = 1.0;
  double merge_ = 1e-9;
  int sweep_plus_ = -1, sweep_minus_ = -1;
  std::vector<PathNode> ahead_;   // k = 0, 1, 2, ...
  std::vector<PathNode> behind_;  // k = -1, -2, ...
  bool ahead_done_ = false, behind_done_ = false;
};

}  // namespace plyfit
