#pragma once
/// \file The metrics of a drape (§7.1 of the paper) and its node counts by status.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace plyfit {

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
  /// The shear-limit nodes counted by the guard that stopped them: "lock" (past the lock
  /// angle) and "behind_stop" (one neighbour mapped, one at the lock); the counts add up to
  /// `shear_limit`.
  std::map<std::string, std::uint64_t> shear_limit_reasons;
  /// The overlap nodes counted by the test that stopped them: "on_laid_cloth" (within half a
  /// spacing of cloth laid farther away on the ply), "thread_turns_back", and the fold guards
  /// "fold_angle", "flat_cell", "cell_folds" (the cloth folded onto itself); the counts add up
  /// to `overlap`.
  std::map<std::string, std::uint64_t> overlap_reasons;
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

}  // namespace plyfit
