// Private to the kernel: the frontier scan of §6.2 as one class whose parts live in
// scan.cpp (the frontier, node bookkeeping, overlap and fold tests), base_path.cpp (§5.1)
// and guesses.cpp (the per-node solves of §5.2 and §6.1 with their initial guesses). The
// scan sees the surface only through DrapeSurface and its SurfaceLocations: it never knows
// about faces.
#pragma once

#include "drape/darts.hpp"
#include "drape/drape.hpp"
#include "drape/solvers/solvers.hpp"

#include "drape/scan/overlap_grid.hpp"
#include "drape/scan/solve_memo.hpp"
#include "drape/seed_curve.hpp"

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <queue>
#include <unordered_map>
#include <unordered_set>
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
// A guess is corrected by its neighbours' guess errors (Scanner::correct_guess) only when the
// correction is shorter than kGuessCorrectionTrust of the guess's step from its neighbour and
// longer than kGuessCorrectionMinRel * d (scaled (u, v) lengths).
inline constexpr double kGuessCorrectionTrust = 0.1;
inline constexpr double kGuessCorrectionMinRel = 1e-8;

// The overlap nodes' reasons besides the fold guards' (to_string(ShearStop)): the node lands
// on cloth already laid (Scanner::overlaps), a thread turns back there (Scanner::folds_back).
inline constexpr const char* kOnLaidCloth = "on_laid_cloth";
inline constexpr const char* kThreadTurnsBack = "thread_turns_back";

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
  /// SeedCurve::kCurve: the curve the base path follows (kept by the caller during run()).
  void follow(const SeedPolyline* curve) { seed_curve_ = curve; }
  /// The darts the scan cuts the cloth along (kept by the caller during run()).
  void cut_along(const DartSet* darts) { darts_ = darts->empty() ? nullptr : darts; }
  /// Solves from `last` (the last drape's, or nullptr) where a node sees the same cloth, and
  /// every solve kept in `next` (nullptr: none kept, none taken); both kept by the caller
  /// during run().
  void memo(const SolveMemo* last, SolveMemo* next);
  /// Where fronts of cloth meet and disagree at a node, solve it from one front and cut its
  /// links to the other (a seam: seams.cpp); off by default (the node is a conflict).
  void seam_where_fronts_meet(bool on);
  /// The links the seams cut (DrapeResult::link_key), in the order they were cut.
  const std::vector<std::uint64_t>& seam_links() const { return seam_links_; }
  /// Per dart: the ply nodes no side's cloth holds (their links to both sides cross it).
  const std::vector<std::uint64_t>& cut_out() const { return cut_out_; }
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
  // The flags a node's solve sets (set_solved_from): cleared before a solve tried again.
  static constexpr std::uint8_t kSolveFlags =
      DrapeNode::kSolvedTwo | DrapeNode::kFromPlusX | DrapeNode::kFromPlusY;

  // scan.cpp
  std::optional<NodeId> neighbour_id(const NodeId& id, ThreadDir d) const;
  bool far_from_path(const Vec2& p) const;
  bool beyond_path(const Vec2& p) const;
  std::uint32_t node_for(const NodeId& id, const Vec2& pos);
  void resolve(std::uint32_t idx, const SolveResult& r);
  bool overlaps(std::uint32_t k);
  void stop_overlap(std::uint32_t k, const char* why);
  // The neighbour across the link in direction d if the cloth goes on from it: mapped, or in
  // a hole of the face (DrapeNode::carries).
  const DrapeNode* mapped_nb(const DrapeNode& n, ThreadDir d) const {
    const std::int32_t k = n.nb[static_cast<int>(d)];
    if (k < 0) return nullptr;
    const DrapeNode& m = res_.nodes[static_cast<std::size_t>(k)];
    if (!m.carries()) return nullptr;
    if (!cuts_.empty() && cut_end(static_cast<std::uint32_t>(k))) {
      const std::uint32_t ni = res_.index_of(n);
      if (cut_end(ni) && cuts_.count(DrapeResult::link_key(ni, static_cast<std::uint32_t>(k))))
        return nullptr;  // across a dart
    }
    return &m;
  }
  bool cancelled_now();
  void push_neighbours(std::uint32_t idx);
  void step(std::uint32_t qi);
  struct Known {  // a neighbour the cloth goes on from, and its direction
    ThreadDir dir;
    const DrapeNode* n;
  };
  int known_neighbours(const DrapeNode& q, Known known[4]) const;
  int best_pair(const DrapeNode& q, const Known known[4], int nk, int& best_a, int& best_b) const;
  SolveResult solve_from_two(std::uint32_t qi, const Known known[4], int nk);
  SolveResult solve_known(std::uint32_t qi, const Known known[4], int nk);

  // solve_memo.cpp
  std::uint64_t seen(const DrapeNode& q) const;
  SolveResult solve_or_reuse(std::uint32_t qi, const Known known[4], int nk);

  // seams.cpp
  struct SeamFront {  // a group of a node's known neighbours (bits of Known[]), ranked
    unsigned mask = 0;
    int size = 0;
    int pair = 0;              // best_pair's score (-1: one neighbour)
    std::uint32_t newest = 0;  // the latest resolution order among its members
  };
  int seam_fronts(const DrapeNode& q, const Known known[4], int nk, SeamFront out[16]) const;
  bool solve_across_seam(std::uint32_t qi, SolveResult& r);

  // dart_cuts.cpp
  bool near_dart(const Known known[4], int nk) const;
  bool solve_beside_darts(std::uint32_t qi, const Known known[4], int nk, SolveResult& r);
  void cut_link(std::uint32_t a, const DrapeNode* b);
  void unpark(std::int32_t k);
  void finish_cuts();
  bool folds_back(std::uint32_t k) const;
  ShearStop shear_stop(const SolveResult& r) const;
  bool behind_lock(const DrapeNode& q) const;
  void scan();

  // base_path.cpp
  void map_path(const Vec3& t3);
  Vec3 path_chord(const DrapeNode& a) const;
  Vec3 path_plane(const DrapeNode& from, const Vec3& travel) const;
  struct PathAim {
    Vec3 plane_normal, travel;
  };
  std::optional<PathAim> path_aim(const DrapeNode& from, const Vec3& travel, double rest, bool fwd,
                                  CurvePlace& place) const;

  // guesses.cpp
  SolveResult solve_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                        const DrapeNode& b, ThreadDir db, double rb);
  TwoSphereStep two_sphere_step(const DrapeNode& q, const DrapeNode& a, double ra,
                                const DrapeNode& b, double rb) const;
  // The rule that made a two-sphere solve's initial guess (guess_two).
  enum class GuessKind : std::uint8_t { kNone, kCubic, kTwist, kPaper, kParallelogram };
  const DrapeNode* guess_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                             const DrapeNode& b, ThreadDir db, double rb, TwoSphereStep& step,
                             GuessKind& kind) const;
  void correct_guess(const DrapeNode& a, const DrapeNode& b, GuessKind kind,
                     TwoSphereStep& step) const;
  void record_guess_error(const DrapeNode& q, GuessKind kind, const std::optional<Vec2>& guess,
                          const SolveResult& r);
  bool cell_folds(const SolveResult& r, const DrapeNode& a, const DrapeNode& b,
                  const DrapeNode& corner) const;
  GuessKind extrapolated_guess(const DrapeNode& q, const DrapeNode& a, ThreadDir da,
                               const DrapeNode& b, ThreadDir db, const DrapeNode& c,
                               TwoSphereStep& step) const;
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
  double path_t_[2] = {0.0, 0.0};  // the path's nodes' extent along the base line (-, +)
  bool truncated_ = false, cancelled_ = false;
  bool one_face_ = true;  // every location is in one chart: guesses need no chart checks
  double cell_ = 1.0;     // overlap radius
  OverlapGrid grid_;
  // Per node, the error of its two-sphere solve's initial guess (solution minus guess, (u, v),
  // as floats: it only corrects a guess) and the rule that made it (kNone: none recorded).
  struct GuessError {
    float du = 0.0f, dv = 0.0f;
  };
  std::vector<GuessError> guess_error_;
  std::vector<GuessKind> guess_kind_;
  ThreadEnds thread_ends_;
  std::uint32_t popped_ = 0;  // frontier entries taken
  const SeedPolyline* seed_curve_ = nullptr;
  const DartSet* darts_ = nullptr;
  std::unordered_set<std::uint64_t> cuts_;  // links across a dart (DrapeResult::link_key)
  // Per node: an end of a link in cuts_ (the set is asked only for links with both ends so:
  // most links are far from every cut, and a lookup in the set divides).
  std::vector<bool> cut_ends_;
  bool cut_end(std::uint32_t k) const { return k < cut_ends_.size() && cut_ends_[k]; }
  std::unordered_set<std::uint32_t> parked_;  // nodes whose cloth so far lies across a dart
  std::vector<std::uint64_t> cut_out_;        // per dart: nodes left parked at the end
  bool seams_ = false;                        // seam_where_fronts_meet
  std::vector<std::uint64_t> seam_links_;     // links the seams cut
  const SolveMemo* memo_last_ = nullptr;
  SolveMemo* memo_next_ = nullptr;
  bool curve_along_ = true;  // the curve's later points lie ahead along t3
};

}  // namespace plyfit::detail
