#pragma once
/// \file The drape: initial conditions (§4.2), the base path (§5.1), the frontier scan (§6.2)
/// and the metrics of §7.1, over a DrapeSurface.

#include <plyfit/kernel/metrics.hpp>
#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/ply.hpp>
#include <plyfit/kernel/result.hpp>
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

class NodeIndex;  // NodeId -> node position (kernel internal)

/// What became of a node the scan reached.
enum class NodeStatus : std::uint8_t {
  kMapped,      ///< on the face, all constraints satisfied
  kOutside,     ///< its solution lies outside the face (domain or trims)
  kOffPly,      ///< beyond the ply rectangle: no cloth there
  kShearLimit,  ///< the thread angle would pass the lock angle (eq. 12), or the node has one
                ///< mapped neighbour and one stopped at the lock (its thread would fold past
                ///< it); NodeCounts::shear_limit_reasons counts them. Never without a lock.
  kFailed,      ///< the solver found no solution (see the solver's reason)
  kOverlap,     ///< the cloth would lie on cloth already laid: the base path or the surface
                ///< closes on itself (a closed plane section, a seam crossed all round), a
                ///< thread turns back on itself, a net sheared past 60 degrees comes back
                ///< over itself, or the cloth folds flat (the fold guards: a thread angle
                ///< within Tolerances::fold_angle of 0 or pi, a cell sheared so flat that its
                ///< links pass below the face, a cell that would fold over its fourth corner);
                ///< NodeCounts::overlap_reasons counts them
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

/// A link between two nodes.
enum class LinkKind : std::uint8_t { kWeft, kWarp, kBase };
struct DrapeLink {
  std::uint32_t a = 0, b = 0;  ///< node indices
  double rest = 0.0;           ///< rest length (the 2D distance)
  LinkKind kind = LinkKind::kWeft;
};

/// The curve the base path (the seed curve) follows on the surface.
enum class SeedCurve : std::uint8_t {
  /// The section of the surface by the base plane (the paper, §4.2.2).
  kPlane,
  /// The geodesic leaving the start along the base plane's section: each path point lies in the
  /// plane through the point before it that holds the surface normal there and the point
  /// before that (the straightest discrete curve: great circles on a sphere, helices on a
  /// cylinder, exactly).
  kGeodesic,
  /// A given curve (DrapeProblem::seed_polyline), projected onto the surface: each path point
  /// is the point of the curve at link length from the point before it.
  kCurve,
};
/// "plane", "geodesic", "curve".
const char* to_string(SeedCurve c);

/// 3D initial conditions (§4.2.2) and the 2D ply with its initial conditions (§4.2.1).
struct DrapeProblem {
  PlySpec ply;
  Vec3 start = Vec3::Zero();         ///< 3D start point; projected onto the face
  Vec3 base_normal = Vec3::UnitY();  ///< base-plane normal; the plane passes through the start
  std::vector<Vec3> sweeps;          ///< 3D sweep directions, paired in order with ply.sweeps
  SeedCurve seed_curve = SeedCurve::kPlane;  ///< what the base path follows from the start
  /// kCurve: the curve (a 3D polyline, mm) the base path follows, through the start to within
  /// Tolerances::seed_curve_rel of the mold's size, on the surface to within the same.
  std::vector<Vec3> seed_polyline;
  bool seed_polyline_closed = false;  ///< its last point joins its first
  /// Darts: cuts in the ply along curves on the part (3D polylines, mm, each within
  /// Tolerances::boundary_on_mold_rel of the mold's size from it). Thread links whose segment
  /// on the part crosses a dart are not enforced: the cloth on its two sides drapes
  /// independently (DrapeResult::darts).
  std::vector<std::vector<Vec3>> darts;
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
  double lock_angle = kPi / 2;
  GuessRule guess = GuessRule::kExtrapolated;
  Tolerances tol;
  /// Test every mapped node for landing on cloth already laid (status kOverlap). false skips
  /// the test (the cloth may then lie on itself unflagged): only to measure its cost.
  bool overlap_test = true;
  /// Stop (status partial) once this many nodes have been reached.
  std::uint64_t max_nodes = 50'000'000;
  /// Set by another thread to stop the drape (status partial, "cancelled").
  const std::atomic<bool>* cancel = nullptr;
  /// Called about every 65536 resolved nodes with the number of mapped nodes.
  std::function<void(std::uint64_t mapped)> progress;
};

/// A dart as the drape laid it: its curve on the part and its two cut lines in the ply.
struct DartResult {
  std::vector<Vec3> curve;  ///< on the part, from its first point to its tip (the last point)
  double length = 0.0;      ///< on the part, mm
  Vec3 tip = Vec3::Zero();  ///< its last point on the part
  /// The curve carried into the ply through the cells of each side (left and right of the
  /// curve seen from outside, along it): the dart's two cut lines, where each side's cloth
  /// ends. Points of the curve with no mapped cell of that side near them are left out.
  std::vector<Vec2> line_left, line_right;
  /// The region between the cut lines (closed at their ends): cloth cut out where the two sides
  /// would overlap on the part (removed_area), or a gap the cloth leaves open on the part
  /// (opening_area), mm^2 in the ply; the larger of the two is what the dart does.
  double removed_area = 0.0, opening_area = 0.0;
  double width_max = 0.0;           ///< largest distance between the cut lines, mm in the ply
  std::uint64_t links_cut = 0;      ///< links between mapped nodes across it, not enforced
  std::uint64_t nodes_cut_out = 0;  ///< ply nodes no side's cloth holds (in the cut-out V)
  /// A seam: the line where two fronts of cloth met, cut by the scan itself (--darts auto),
  /// not a curve given or proposed before the drape.
  bool seam = false;
};

/// Everything the drape computed.
struct DrapeResult {
  bool partial = false;                  ///< stopped early, or some nodes failed or conflict
  std::vector<Warning> warnings;         ///< why partial, and other notes (codes with data)
  std::vector<DrapeNode> nodes;          ///< every node reached, in resolution order
  std::shared_ptr<NodeIndex> index;      ///< NodeId -> position in `nodes` (kernel internal)
  std::vector<std::uint32_t> base_path;  ///< base-path nodes in order, mapped or kInHole
  /// Why each failed, conflict, shear-limit or overlap node (kFailed, kConflict, kShearLimit,
  /// kOverlap: its status tells which) was not mapped: (index in `nodes`, the reason; for
  /// kShearLimit and kOverlap a code, NodeCounts), in resolution order.
  std::vector<std::pair<std::uint32_t, const char*>> failures;
  std::shared_ptr<const Ply> ply;
  DrapeMetrics metrics;
  Vec3 start_point = Vec3::Zero();  ///< the start on the face
  SurfaceLocation start_at;
  double start_moved = 0.0;                  ///< distance from the given 3D start to the face
  Vec3 base_normal = Vec3::UnitY();          ///< unit base-plane normal
  Vec3 base_tangent = Vec3::UnitX();         ///< 3D direction of the base path at the start
  SeedCurve seed_curve = SeedCurve::kPlane;  ///< what the base path followed
  double gamma_min_limit = 0.0;  ///< gamma_min of the lock angle (radians; 0 without one)
  double drape_ms = 0.0;         ///< wall time of drape() (drape_auto_darts: of all its drapes)
  /// Links not enforced because they cross a dart, as sorted keys (link_key()).
  std::vector<std::uint64_t> cut_links;
  /// Per node (when as long as `nodes`): true when some link of it is in cut_links.
  std::vector<bool> cut_ends;
  std::vector<DartResult> darts;  ///< per DrapeProblem::darts, in order
  std::uint32_t drapes = 1;       ///< drapes made (drape_auto_darts: up to its max_drapes)
  bool darts_auto = false;        ///< the darts were proposed by drape_auto_darts
  /// drape_auto_darts: nodes of the last drape that took the drape before's solve (they saw
  /// the same cloth: neighbours and theirs the same) instead of solving again.
  std::uint64_t solves_reused = 0;

  /// The key of the link between nodes a and b (indices into `nodes`, either order).
  static std::uint64_t link_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
  }
  /// True when the link between nodes a and b crosses a dart.
  bool cut(std::uint32_t a, std::uint32_t b) const;

  /// Node by id, or nullptr.
  const DrapeNode* find(const NodeId& id) const;
  /// The node across the thread link from `id` in direction dir, if reached.
  const DrapeNode* neighbour(const NodeId& id, ThreadDir dir) const;
  /// The node across the thread link from node n in direction dir, if reached.
  const DrapeNode* neighbour(const DrapeNode& n, ThreadDir dir) const {
    const std::int32_t k = n.nb[static_cast<int>(dir)];
    return k < 0 ? nullptr : &nodes[static_cast<std::size_t>(k)];
  }
  /// The node across the thread link from node n in direction dir, if reached and the link
  /// crosses no dart: the cloth's links (the net's topology is neighbour()).
  const DrapeNode* linked(const DrapeNode& n, ThreadDir dir) const {
    const DrapeNode* m = neighbour(n, dir);
    if (!m || cut_links.empty()) return m;
    const std::uint32_t a = index_of(n);
    if (cut_ends.size() == nodes.size() && !cut_ends[a]) return m;
    return cut(a, index_of(*m)) ? nullptr : m;
  }
  std::uint32_t index_of(const DrapeNode& n) const {
    return static_cast<std::uint32_t>(&n - nodes.data());
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

/// A mapped cell part: its cell (lower-left regular node (i, j)) and its nodes (indices into
/// DrapeResult::nodes, counter-clockwise).
struct MappedCell {
  std::int32_t i = 0, j = 0;
  std::vector<std::uint32_t> nodes;
};
/// Every mapped cell part, row by row (j, then i), parts of one cell in cell_parts order.
std::vector<MappedCell> mapped_cells(const DrapeResult& r);

/// Drapes the ply on `surface`. Errors (bad input) name the problem; numerical trouble during
/// the scan is reported per node, never as an error.
Result<DrapeResult> drape(const MoldSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options = {});

/// Drapes with automatic darts: where the drape ends in conflict or at the shear limit
/// (conflict or shear_limit nodes), one dart per zone of such stops (the mapped nodes next to
/// them, within two spacings of each other) is proposed: from the zone's node nearest the ply's
/// start (its tip, where the cloth is still laid) outward along the thread or bisector of the
/// threads nearest the direction from the start, walked on the surface to the face's edge;
/// then the ply is draped again with them (a zone near a dart lengthens it), until it is laid
/// with no such stop or `max_drapes` drapes were made. From the second proposal on, where the
/// darts from the edge have not laid the ply, seam darts along the lines where fronts of cloth
/// met (conflict nodes, overlaps on laid cloth) join them: a closed shell has no edge to walk
/// to. DrapeResult::drapes says how many; the warning darts_not_enough, when stops remain.
/// Errors as drape()'s.
Result<DrapeResult> drape_auto_darts(const MoldSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options = {}, int max_drapes = 3);

/// A drape leaves the overlap test's grid (up to 64 MiB of pages and its slot table) to the
/// next drape on the same thread, which reuses the memory instead of having the system map
/// and zero it again (optimize drapes again and again on each worker thread). This frees
/// what the calling thread holds, e.g. before measuring a first drape's memory.
void release_drape_scratch();

}  // namespace plyfit
