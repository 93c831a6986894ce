// Private to the kernel: the frontier scan of §6.2 as one class whose parts live in
// scan.cpp (the frontier, node bookkeeping, overlap and fold tests, the overlap test in
// batches), base_path.cpp (§5.1) and guesses.cpp (the per-node solves of §5.2 and §6.1 with
// their initial guesses). The scan sees the surface only through DrapeSurface and its
// SurfaceLocations: it never knows about faces.
#pragma once

#include "drape/drape.hpp"
#include "drape/solvers/solvers.hpp"

#include "drape/scan/overlap_grid.hpp"

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <queue>
#include <unordered_map>
#include <vector>

namespace plyfit::detail {

// The cloth overlaps itself where a new node lands within kOverlapRel * d (3D) of a mapped
// node at least kOverlapSeparation * d away from it on the ply (2D): a closed plane
// section, or a closed face wrapped all round.
inline constexpr double kOverlapRel = 0.5;
inline constexpr double kOverlapSeparation = 2.0;
// A node solved from two neighbours whose link to a further known neighbour is off by more
// than this (relative to d) is not mapped: two fronts met around a hole in the net and
// disagree. Fronts that agree do so to the solver's tolerance.
inline constexpr double kFrontMismatchRel = 1e-9;
// How often (resolved nodes) the scan checks for cancellation and reports progress.
inline constexpr std::uint32_t kCancelEvery = 4096;
inline constexpr std::uint32_t kProgressEvery = 65536;
// A regular node farther than this many cell diagonals from the base path line has plain
// regular neighbours (no link split by the path); the extrapolated guess's stencil spans
// kStencilCells cell diagonals.
inline constexpr double kFarFromPathCells = 2.0;
inline constexpr double kStencilCells = 6.0;
// GuessRule::kExtrapolated: the two threads' cubic continuations are used when they agree to
// this fraction of the cell's step (scaled (u, v) lengths); else the twist-corrected
// parallelogram.
inline constexpr double kExtrapolationAgreement = 1e-4;
// ... and an extrapolated guess is used only within this fraction of the cell's step from the
// parallelogram a + b - c (smooth regions: O(d^2) relative; near a pole (u, v) is not smooth).
inline constexpr double kExtrapolationTrust = 0.1;

struct FrontierEntry {
  double sweep;  // distance from the base path along the sweep direction
  double dist;   // distance to the start (tie-break)
  std::int32_t i, j;
  std::uint32_t node;
};
struct FrontierLater {
  bool operator()(const FrontierEntry& a, const FrontierEntry& b) const {
    if (a.sweep != b.sweep) return a.sweep > b.sweep;
    if (a.dist != b.dist) return a.dist > b.dist;
    if (a.i != b.i) return a.i > b.i;
    return a.j > b.j;
  }
};

/// The scan: maps the base path both ways from the start, then the frontier in sweep order.
class Scanner {
 public:
  Scanner(const DrapeSurface& s, Ply& ply, const DrapeOptions& opt, DrapeResult& res);

  /// Maps the base path (t3: its 3D direction at the start) and scans the frontier.
  void run(const Vec3& t3);
  bool truncated() const { return truncated_; }
  bool cancelled() const { return cancelled_; }
  std::uint64_t path_off_ply() const { return path_off_ply_; }
  /// A slit along the base path's line: thread links across the line beyond the path's
  /// ends that join cloth mapped by the two sweeps (the path stopped where the surface has a
  /// gap that is no hole of one face, or where its plane's section left the face or curled
  /// back, and the cloth goes on beyond it; see path_slits()).
  struct PathSlit {
    std::uint64_t links = 0;   ///< such links (0: no slit)
    Vec2 stop = Vec2::Zero();  ///< ply position of the path node where the path stopped
  };
  /// Finds the slit after the scan (never on a path that crossed its gaps).
  PathSlit path_slits() const;
  /// Nodes off the base path whose thread, continued from one neighbour, cannot follow the
  /// surface for one link (the section of its plane, square to the surface, turns back or
  /// ends within the link): marked outside. The first one's ply point, for the warning.
  struct ThreadEnds {
    std::uint64_t nodes = 0;
    Vec2 first = Vec2::Zero();
  };
  const ThreadEnds& thread_ends() const { return thread_ends_; }

 private:
  DrapeNode& node(std::uint32_t k) { return res_.nodes[k]; }

  // scan.cpp
  std::optional<NodeId> neighbour_id(const NodeId& id, ThreadDir d) const;
  bool far_from_path(const Vec2& p) const;
  std::uint32_t node_for(const NodeId& id, const Vec2& pos);
  void resolve(std::uint32_t idx, const SolveResult& r);
  bool overlaps(std::uint32_t k);
  void stop_overlap(std::uint32_t k);
  // The neighbour across the link in direction d if the cloth goes on from it: mapped, or in
  // a hole of the face (DrapeNode::carries).
  const DrapeNode* mapped_nb(const DrapeNode& n, ThreadDir d) const {
    const std::int32_t k = n.nb[static_cast<int>(d)];
    if (k < 0) return nullptr;
    const DrapeNode& m = res_.nodes[static_cast<std::size_t>(k)];
    return m.carries() ? &m : nullptr;
  }
  bool cancelled_now();
  void push_neighbours(std::uint32_t idx);
  void step(std::uint32_t qi);
  // The overlap test speculated: see scan().
  void checkpoint();
  bool settle();
  void roll_back(std::size_t tested);
  // Node k is about to change otherwise than by being solved or linked to a new node: keeps
  // it as it was, if the checkpoint has it.
  void keep(std::uint32_t k) {
    if (speculating_ && k < cp_.nodes) undo_.emplace_back(k, res_.nodes[k]);
  }
  bool folds_back(std::uint32_t k) const;
  ShearStop shear_stop(const SolveResult& r) const;
  bool behind_lock(const DrapeNode& q) const;
  void scan();

  // base_path.cpp
  void map_path(const Vec3& t3);
  Vec3 path_chord(const DrapeNode& a) const;
  Vec3 path_plane(const DrapeNode& from, const Vec3& travel) const;

  // guesses.cpp
  SolveResult solve_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                        const DrapeNode& b, ThreadDir db, double rb);
  bool extrapolated_guess(const DrapeNode& q, const DrapeNode& a, ThreadDir da, const DrapeNode& b,
                          ThreadDir db, const DrapeNode& c, TwoSphereStep& step) const;
  bool in_domain(const SurfaceLocation& chart, const Vec2& uv) const;
  bool one_chart(std::initializer_list<const DrapeNode*> nodes) const;
  SolveResult solve_one(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra);

  const DrapeSurface& s_;
  Ply& ply_;
  const DrapeOptions& opt_;
  DrapeResult& res_;
  SolverSettings st_;
  std::priority_queue<FrontierEntry, std::vector<FrontierEntry>, FrontierLater> heap_;
  std::unordered_map<std::uint32_t, std::uint32_t> path_pos_;  // node -> position on the path
  double far_ = 0.0;  // distance from the path line beyond which far_from_path() holds
  std::uint32_t order_ = 0;
  std::uint64_t path_off_ply_ = 0;
  Vec2 path_stop_[2] = {Vec2::Zero(), Vec2::Zero()};  // where the path stopped, +tau and -tau
  bool truncated_ = false, cancelled_ = false;
  bool one_face_ = true;  // every location is in one chart: guesses need no chart checks
  double cell_ = 1.0;     // overlap radius
  OverlapGrid grid_;
  ThreadEnds thread_ends_;
  std::uint32_t popped_ = 0;  // frontier entries taken
  // The overlap test speculated (scan()): the scan's state at the last checkpoint, the nodes
  // it changed since (as they were), the nodes resolved since that await the test, and after
  // a roll-back the nodes the batch had already tested (recorded in the grid: not again).
  struct Checkpoint {
    std::priority_queue<FrontierEntry, std::vector<FrontierEntry>, FrontierLater> heap;
    std::size_t nodes = 0, capacity = 0, failures = 0;
    NodeIndex::Mark index;
    std::uint32_t order = 0, popped = 0;
    ThreadEnds thread_ends;
    bool truncated = false;
    std::uint64_t solves = 0, iterations = 0, evaluations = 0;
    double residual_max = 0.0;
  };
  bool speculating_ = false;
  Checkpoint cp_;
  std::vector<std::pair<std::uint32_t, DrapeNode>> undo_;
  std::vector<std::uint32_t> solved_;  // checkpoint nodes solved since (pending there)
  std::vector<std::uint32_t> linked_;  // checkpoint nodes linked to new nodes since
  std::vector<std::uint32_t> pending_;
  std::vector<std::uint32_t> replay_;
  std::size_t replayed_ = 0;
};

}  // namespace plyfit::detail
