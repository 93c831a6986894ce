#pragma once
/// \file The drape: initial conditions (§4.2), the base path (§5.1), the frontier scan (§6.2)
/// and the metrics of §7.1, over a DrapeSurface.

#include <plyfit/kernel/face.hpp>
#include <plyfit/kernel/ply.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/solvers.hpp>
#include <plyfit/kernel/tolerances.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace plyfit {

/// What became of a node the scan reached.
enum class NodeStatus : std::uint8_t {
  kMapped,      ///< on the face, all constraints satisfied
  kOutside,     ///< its solution lies outside the face (domain or trims)
  kOffPly,      ///< beyond the ply rectangle: no cloth there
  kShearLimit,  ///< the thread angle would pass the lock angle (eq. 12) or come within
                ///< Tolerances::fold_angle of 0 or pi, or no point fits its links (the cell is
                ///< sheared so flat they pass below the face), or its cell would fold (the net
                ///< around it is sheared flat), or the node has one mapped neighbour and a
                ///< stopped one (its thread would fold past it): ShearStop says which, and
                ///< NodeCounts::shear_limit_reasons counts them
  kFailed,      ///< the solver found no solution (see the solver's reason)
  kOverlap,     ///< the cloth would lie on cloth already laid: the base path or the surface
                ///< closes on itself (a closed plane section, a seam crossed all round), a
                ///< thread turns back on itself, or a net sheared past 60 degrees comes back
                ///< over itself
  /// Two fronts of cloth met at the node and disagree: no point of the surface satisfies all
  /// its links (over-determined on a 2-D surface), so the cloth cannot be laid there without a
  /// dart or a splice. Either the node was solved from two neighbours and its link to a
  /// further mapped neighbour is off by more than 1e-9 d (the scan's kFrontMismatchRel:
  /// "the fronts disagree: a third link is off"), or its only mapped neighbours lie on one
  /// thread, farther apart than its two links ("the fronts disagree: the thread between them
  /// would stretch"). The cloth's own incompatibility (a CAD draping tool's "conflict"), not
  /// a failure of the solver; the cloth goes no further from it, as from a failed node.
  kConflict,
  /// A base-path point beyond the path's end: the base plane's section of the surface turns
  /// back, or ends where the plane touches the surface, within one link ahead of the last path
  /// point (the plane nearly tangent to the surface there; SolveResult::section_ends). No
  /// point of the section lies ahead, so the path, the seed of the drape, stops there.
  kPathEnd,
  kPending,  ///< internal: in the frontier
};
/// "mapped", "outside", "off_ply", "shear_limit", "failed", "overlap", "conflict", "path_end",
/// "pending".
const char* to_string(NodeStatus s);

/// A node the drape reached.
struct DrapeNode {
  static constexpr std::uint8_t kOnPath = 1;    ///< a base-path node (auxiliary or crossing)
  static constexpr std::uint8_t kExtended = 2;  ///< kOutside with a solution on the surface
                                                ///< extended past the face (point/uv valid)
  static constexpr std::uint8_t kHasAngle = 4;  ///< thread_angle is defined
  static constexpr std::uint8_t kStart = 8;     ///< the start point
  /// Solved from a weft and a warp neighbour (the two-sphere solve of §5.2): the links to those
  /// two give the paper's thread angle of eq. (12) (DrapeMetrics::paper); kFromPlusX and
  /// kFromPlusY say which ones (see set_solved_from).
  static constexpr std::uint8_t kSolvedTwo = 16;
  static constexpr std::uint8_t kFromPlusX = 32;  ///< with kSolvedTwo: the weft one is +x (else -x)
  static constexpr std::uint8_t kFromPlusY = 64;  ///< with kSolvedTwo: the warp one is +y (else -y)
  /// kOutside and kExtended, in a hole of the face (DrapeSurface::in_hole): the cloth goes on
  /// from it on the face's surface under the hole (the base path and the sweeps continue
  /// across a cutout as if it were not there; the flat pattern cuts the hole out).
  static constexpr std::uint8_t kInHole = 128;
  // Fields ordered so that Eigen's 16-byte alignment of Vec2 leaves no padding: 96 bytes.
  Vec3 point = Vec3::Zero();  ///< 3D position (mapped, or extended, else zero)
  double thread_angle = 0.0;  ///< gamma between weft and warp at a mapped regular node, radians
  Vec2 uv = Vec2::Zero();     ///< surface parameters on face `face`
  Vec2 ply = Vec2::Zero();    ///< ply coordinates
  /// Index in DrapeResult::nodes of the node across the thread link in each ThreadDir
  /// (+x, -x, +y, -y), or -1 if that node was never reached. A link split by the base path
  /// leads to the path node on it.
  std::int32_t nb[4] = {-1, -1, -1, -1};
  NodeId id;
  std::uint32_t order = 0;  ///< order in which the node was resolved
  NodeStatus status = NodeStatus::kPending;
  std::uint8_t flags = 0;
  std::uint16_t face = 0;  ///< face (chart) of `uv`: see at()
  bool mapped() const { return status == NodeStatus::kMapped; }
  /// Mapped, or in a hole of the face (kInHole): a node the drape goes on from.
  bool carries() const { return mapped() || (flags & kInHole) != 0; }
  bool has(std::uint8_t f) const { return (flags & f) != 0; }
  /// Where the node lies on the surface (mapped, or extended).
  SurfaceLocation at() const { return {uv, face}; }
  /// Sets uv and face.
  void set_at(const SurfaceLocation& a) {
    uv = a.uv;
    face = static_cast<std::uint16_t>(a.face);
  }
  /// Records that the node was solved from its neighbours across the weft link `weft` (kPlusX
  /// or kMinusX) and the warp link `warp` (kPlusY or kMinusY): kSolvedTwo and its direction
  /// bits (flags, so that the node keeps its size); a node solved again keeps the last pair.
  void set_solved_from(ThreadDir weft, ThreadDir warp) {
    flags = static_cast<std::uint8_t>((flags & ~(kFromPlusX | kFromPlusY)) | kSolvedTwo |
                                      (weft == ThreadDir::kPlusX ? kFromPlusX : 0) |
                                      (warp == ThreadDir::kPlusY ? kFromPlusY : 0));
  }
};

/// Map from NodeId to node index. Regular nodes live in a sparse grid of dense 32 x 32
/// blocks (neighbours share a block; a few bytes per node), path-only nodes in a small hash;
/// memory grows with the nodes reached, never with the size of the ply.
class NodeIndex {
 public:
  /// Index of `id`, or -1.
  std::int64_t find(const NodeId& id) const;
  /// Inserts id -> index (id must be absent).
  void insert(const NodeId& id, std::uint32_t index);
  /// Removes `id`; false if it is absent. (A regular node's block stays: see truncate().)
  bool erase(const NodeId& id);
  /// What the index has allocated, for truncate().
  struct Mark {
    std::size_t blocks = 0, block_slots = 0, cells_capacity = 0;
  };
  Mark mark() const { return {block_count_, blocks_.size(), cells_.capacity()}; }
  /// Drops the blocks of regular nodes added since `m` (their ids erased already) and gives
  /// back the memory they took: the index allocates as if they had never been added.
  void truncate(const Mark& m);
  std::size_t size() const { return size_; }
  std::size_t memory_bytes() const;

 private:
  static constexpr int kBlockBits = 5;
  static constexpr int kBlock = 1 << kBlockBits;  // 32 x 32 nodes per block
  struct Slot {
    std::uint64_t key;
    std::uint32_t value;
  };
  // The key of NodeId::path(INT32_MIN): no node has it (path indices stay within
  // +-Ply::kMaxPathNodes). (All ones would be the key of regular node (-1, -1).)
  static constexpr std::uint64_t kEmpty = (std::uint64_t{0x7fffffff} << 32) | 0x80000000u;
  static std::int64_t probe(const std::vector<Slot>& slots, std::uint64_t key);
  static void put(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key,
                  std::uint32_t value);
  static bool remove(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key);
  std::vector<Slot> blocks_;  // block key -> block number
  std::size_t block_count_ = 0;
  std::vector<std::int32_t> cells_;  // kBlock^2 entries per block, -1 = absent
  std::vector<Slot> path_;           // path-only node key -> index
  std::size_t path_count_ = 0;
  std::size_t size_ = 0;
  mutable std::uint64_t last_key_ = kEmpty;  // one-entry cache of the last block looked up
  mutable std::int64_t last_block_ = -1;
};

/// A link between two nodes.
enum class LinkKind : std::uint8_t { kWeft, kWarp, kBase };
struct DrapeLink {
  std::uint32_t a = 0, b = 0;  ///< node indices
  double rest = 0.0;           ///< rest length (the 2D distance)
  LinkKind kind = LinkKind::kWeft;
};

/// 3D initial conditions (§4.2.2) and the 2D ply with its initial conditions (§4.2.1).
struct DrapeProblem {
  PlySpec ply;
  Vec3 start = Vec3::Zero();         ///< 3D start point; projected onto the face
  Vec3 base_normal = Vec3::UnitY();  ///< base-plane normal; the plane passes through the start
  std::vector<Vec3> sweeps;          ///< 3D sweep directions, paired in order with ply.sweeps
};

/// Initial guess of the two-sphere solver.
enum class GuessRule : std::uint8_t {
  kPaper,          ///< eqs. (10)-(11): both threads continued; else the cell's parallelogram
  kParallelogram,  ///< the cell's fourth corner: uv_a + uv_b - uv_c; else eqs. (10)-(11)
  /// Both threads continued through their last four nodes (cubic extrapolation in (u, v),
  /// the mean of the two) where the two continuations agree, else the cell's parallelogram
  /// corrected by the twist of the two neighbouring cells; else as kPaper. The guess lands
  /// about 1e-6 d from the node at d = 1/2000 of the face (kPaper: about 1e-3 d), which saves
  /// Newton iterations; the solution is the same.
  kExtrapolated,
};
/// "paper", "parallelogram", "extrapolated".
const char* to_string(GuessRule g);

/// Options of the drape.
struct DrapeOptions {
  /// Lock angle (radians): the largest shear pi/2 - gamma allowed; gamma_min = pi/2 - lock,
  /// gamma_max = pi/2 + lock (eq. 12). pi/2 (the default) disables the test.
  double lock_angle = 1.5707963267948966;
  GuessRule guess = GuessRule::kExtrapolated;
  Tolerances tol;
  /// Test every mapped node for landing on cloth already laid (status kOverlap). false skips
  /// the test (the cloth may then lie on itself unflagged): only to measure its cost.
  bool overlap_test = true;
  /// The scan maps up to this many nodes ahead of the overlap test, then tests them in the
  /// order they were mapped (nodes tested together cost the drape 1-4 % less at 10^6 nodes);
  /// where one lies on laid cloth the scan goes back to the batch's start and on node by node
  /// for the rest of the drape. The drape is the same whatever the value, to the bit; 1 tests
  /// each node as it is mapped. The batch's undo log and a copy of the frontier grow with it.
  std::uint32_t overlap_batch = 4096;
  /// Stop (status partial) once this many nodes have been reached.
  std::uint64_t max_nodes = 50'000'000;
  /// Set by another thread to stop the drape (status partial, "cancelled").
  const std::atomic<bool>* cancel = nullptr;
  /// Called about every 65536 resolved nodes with the number of mapped nodes.
  std::function<void(std::uint64_t mapped)> progress;
};

/// Node counts by status (regular and auxiliary nodes apart).
struct NodeCounts {
  std::uint64_t mapped = 0;     ///< mapped regular mesh points (the paper's "area")
  std::uint64_t auxiliary = 0;  ///< mapped auxiliary base-path points
  std::uint64_t outside = 0;
  std::uint64_t off_ply = 0;
  std::uint64_t shear_limit = 0;
  std::uint64_t failed = 0;
  std::uint64_t overlap = 0;   ///< stopped where the cloth would lie on itself
  std::uint64_t conflict = 0;  ///< where two fronts of cloth met and disagree (kConflict)
  std::uint64_t path_end = 0;  ///< base-path points past where the path ends (kPathEnd)
  /// The failed nodes counted by the solver's reason (SolveResult::reason, e.g. "no convergence
  /// within the iteration cap"); the counts add up to `failed`.
  std::map<std::string, std::uint64_t> failed_reasons;
  /// The shear-limit nodes counted by the guard that stopped them (to_string(ShearStop):
  /// "lock", "fold_angle", "flat_cell", "cell_folds", "behind_stop"); the counts add up to
  /// `shear_limit`.
  std::map<std::string, std::uint64_t> shear_limit_reasons;
  /// The conflict nodes counted by their reason ("the fronts disagree: a third link is off",
  /// "the fronts disagree: the thread between them would stretch"); the counts add up to
  /// `conflict`.
  std::map<std::string, std::uint64_t> conflict_reasons;
};

/// The metrics of §7.1 and independent residual checks.
struct DrapeMetrics {
  NodeCounts nodes;
  std::uint64_t area_mesh_points = 0;  ///< = nodes.mapped
  double flat_area = 0.0;              ///< 2D area of the mapped cells (cells cut by the path count
                                       ///< their mapped parts)
  double surface_area = 0.0;           ///< 3D area those cells cover
  double gamma_min = 0.0, gamma_max = 0.0;  ///< thread angles, radians (0 if none)
  double shear_energy = 0.0;                ///< sum of cos^2(gamma) over mapped regular nodes
  std::uint64_t angles = 0;                 ///< nodes with a thread angle
  /// The paper's own thread angles (eq. 12, §7.1, Table 2): at each mapped node solved from a
  /// weft and a warp neighbour (DrapeNode::kSolvedTwo), the angle at the node between its
  /// links to those two, as they point (x1 - x and x2 - x of eq. 12): a node solved from its
  /// +x and -y neighbours (a sweep along (-1, 1), the paper's case (c)) has pi minus the angle
  /// a node solved from its -x and -y ones has on the same cell. Beside them the same angles
  /// oriented, each link taken along +x or +y (one gamma for both kinds of node: the thread
  /// angle of our own figures). Nodes solved from one neighbour, or on the base path, have
  /// none.
  struct PaperFigures {
    double gamma_min = 0.0, gamma_max = 0.0;  ///< radians, as eq. (12) (0 if no node has it)
    double oriented_gamma_min = 0.0;          ///< radians, links along +x and +y
    double oriented_gamma_max = 0.0;
    double energy = 0.0;       ///< sum of cos^2(gamma) over those nodes (eq. 14; either angle)
    double shear_max = 0.0;    ///< largest |pi/2 - gamma| (radians; either angle)
    std::uint64_t angles = 0;  ///< nodes with the angle
  };
  PaperFigures paper;
  /// max | |p_a - p_b| - rest | / d over links between mapped nodes.
  double edge_length_max_rel = 0.0;
  /// max |S(u, v) - p| over mapped nodes, with S evaluated afresh (model units).
  double surface_distance_max = 0.0;
  /// max distance of mapped base-path nodes from the base plane / d.
  double base_plane_max_rel = 0.0;
  /// Solver statistics.
  std::uint64_t solves = 0, iterations = 0, evaluations = 0;
  /// Largest final residual |F1| + |F2| of eq. (9) over the solves that mapped a node, / d
  /// (links closed by no solve, where a node had more known neighbours than a solver uses,
  /// show in edge_length_max_rel, not here).
  double solve_residual_max_rel = 0.0;
  /// The floor of eq. (9)'s tolerance on this surface (residual_floor at its bounding box's
  /// farthest corner, with a sphere of radius d; model units): what the surface's evaluation
  /// and the coordinates' rounding leave of the residual. Solves stop at the larger of it and
  /// Tolerances::newton_residual_rel * d.
  double newton_floor = 0.0;

  // Figures derived from the above, owned here so that writers and commands do not compute
  // them again.
  /// Largest shear |pi/2 - gamma| over the nodes with a thread angle (radians; 0 if none).
  double shear_max = 0.0;
  /// surface_area over the area of the surface: the part of the face (or shell) the mapped
  /// cells cover (more than 1 + kCoverageSlack: cloth on cloth, see DrapeResult::warnings).
  double coverage = 0.0;
  /// Largest crease angle (radians) of the shared edges that links between mapped nodes
  /// cross (0 on one face, or where every join crossed is tangent).
  double crease_angle_max = 0.0;
  /// Per face of the surface (one for a single face).
  struct FaceFigures {
    double area = 0.0;          ///< the face's area
    std::uint64_t mapped = 0;   ///< mapped regular nodes on the face
    double covered_area = 0.0;  ///< 3D area of the mapped cells on it (each cell's area
                                ///< shared equally among its corners' faces)
  };
  std::vector<FaceFigures> faces;
};

/// Everything the drape computed.
struct DrapeResult {
  bool partial = false;                  ///< stopped early, or some nodes failed or conflict
  std::vector<std::string> warnings;     ///< why partial, and other notes
  std::vector<DrapeNode> nodes;          ///< every node reached, in resolution order
  NodeIndex index;                       ///< NodeId -> position in `nodes`
  std::vector<std::uint32_t> base_path;  ///< base-path nodes in order, mapped or kInHole
  /// Why each failed, conflict or shear-limit node (kFailed, kConflict, kShearLimit: its
  /// status tells which) was not mapped: (index in `nodes`, the reason; for kShearLimit the
  /// code of its ShearStop), in resolution order.
  std::vector<std::pair<std::uint32_t, const char*>> failures;
  std::shared_ptr<const Ply> ply;
  DrapeMetrics metrics;
  Vec3 start_point = Vec3::Zero();  ///< the start on the face
  SurfaceLocation start_at;
  double start_moved = 0.0;           ///< distance from the given 3D start to the face
  Vec3 base_normal = Vec3::UnitY();   ///< unit base-plane normal
  Vec3 base_tangent = Vec3::UnitX();  ///< 3D direction of the base path at the start
  double gamma_min_limit = 0.0;       ///< gamma_min of the lock angle (radians; 0 without one)
  double drape_ms = 0.0;              ///< wall time of drape()

  /// Node by id, or nullptr.
  const DrapeNode* find(const NodeId& id) const {
    const auto k = index.find(id);
    return k < 0 ? nullptr : &nodes[static_cast<std::size_t>(k)];
  }
  /// The node across the thread link from `id` in direction dir, if reached.
  const DrapeNode* neighbour(const NodeId& id, ThreadDir dir) const;
  /// The node across the thread link from node n in direction dir, if reached.
  const DrapeNode* neighbour(const DrapeNode& n, ThreadDir dir) const {
    const std::int32_t k = n.nb[static_cast<int>(dir)];
    return k < 0 ? nullptr : &nodes[static_cast<std::size_t>(k)];
  }
  /// Rest length of the thread link from node n in direction dir (the split length if the
  /// base path cuts that link).
  double rest_length(const DrapeNode& n, ThreadDir dir) const;
  /// Every link between two mapped nodes (thread links, split at the base path, and the
  /// base path's own links), each once.
  std::vector<DrapeLink> links() const;
  /// Threads as maximal runs of consecutive mapped nodes (auxiliary points included where a
  /// thread crosses the path), at least two nodes each, as node indices in increasing x
  /// (weft) or y (warp).
  std::vector<std::vector<std::uint32_t>> threads(bool weft) const;
  /// Approximate bytes held per reached node (nodes + index).
  double bytes_per_node() const;
};

/// Drapes the ply on `surface`. Errors (bad input) name the problem; numerical trouble during
/// the scan is reported per node, never as an error.
Result<DrapeResult> drape(const DrapeSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options = {});

/// A drape leaves the overlap test's grid (up to 64 MiB of pages and its slot table) to the
/// next drape on the same thread, which reuses the memory instead of having the system map
/// and zero it again (optimize drapes again and again on each worker thread). This frees
/// what the calling thread holds, e.g. before measuring a first drape's memory.
void release_drape_scratch();

}  // namespace plyfit
