#pragma once
/// \file The search of initial conditions (plyfit optimize): a search over a scene's initial
/// conditions (the seed point on the mold and
// the ply's angle) for the drape with the lowest shear energy, largest shear or flat-pattern
/// area, with the coverage of the face as a constraint. One face, many independent drapes,
/// run in parallel; the same input gives the same result whatever the number of threads.
/// Also the coverage rule it judges drapes by (shared with plyfit compare).

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/mold.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace plyfit {

/// Surface area of the region the flat pattern's outline covers: the integral over the
/// outline of the ratio of surface to flat area, constant per cell of the ply (its four
/// corners' 3D quadrilateral, on the surface extended past the face for corners outside it);
/// the cells the outline cuts count only their part inside it, whatever the grid's position.
/// Over the face's (or shell's) area it is the outline's coverage.
double outline_surface_area(const DrapeResult& res, const FlatPattern& flat);

/// A drape's outline coverage may fall this far (fraction of the face) below the best coverage
/// (at most 1) and still count as covering as much: the 589 drapes of the three sphere-octant
/// samples' searches (d = R/20) that reach the whole face cover 99.70% to 100.21% of it by
/// this measure, at most 0.30% short, with the grid's position against the boundary (by the
/// mapped cells, report.json's coverage, 88.5% to 96.8%).
constexpr double kCoverageSlack = 0.005;

/// WarningCode::kOutlineShort on res when the flat pattern's exact outline covers less of the
/// surface (area surface_area) than the coverage rule allows (1 - kCoverageSlack) and the drape
/// gave no reason for it (not partial, no kUncoveredArea; no ply rectangle): values the
/// outline's coverage, kCoverageSlack, then the nodes stopped inside the surface at the shear
/// limit, overlapping, failed, in conflict and past the base path's end.
void warn_outline_short(const FlatPattern& flat, double surface_area, DrapeResult& res);

/// A start for a drape of one face: the point of the face nearest the (u, v) centre of its
/// boundary (trim loops, or the domain) that lies inside the trims, the outward normal there,
/// and the base path along the surface's u direction (v where u collapses or where the face
/// closes round along u but not v, as a full cylinder): base-plane normal
/// and sweeps n x t, so that (t, n x t) turns about +n like (base2d, sweep2d) = ((1, 0),
/// (0, 1)) about +z.
struct FaceStart {
  Vec2 uv = Vec2::Zero();
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ(), tangent = Vec3::UnitX(),
       base_normal = Vec3::UnitY();
};
/// The start of one face (plyfit info --face N); errors: a shell, no point inside the trims,
/// no tangent plane there.
Result<FaceStart> face_start(const MoldSurface& face);

/// What a drape is judged by (smaller is better for each).
enum class Objective : std::uint8_t {
  kEnergy,    ///< shear energy sum cos^2(gamma) (DrapeMetrics::shear_energy)
  kMaxShear,  ///< largest |90 deg - gamma|
  kArea,      ///< area of the flat pattern's outline: the cloth to cut
};
/// Number of objectives.
constexpr int kObjectiveCount = 3;
/// "energy", "max-shear", "area".
const char* to_string(Objective o);
/// Parses one objective name.
std::optional<Objective> parse_objective(const std::string& name);

/// The initial conditions of a candidate drape, at a seed on the face. Angles are about the
/// face's outward normal at the seed, counter-clockwise, from the scene's directions carried
/// to the seed (see OptimizeResult::reference).
struct Candidate {
  Vec2 uv = Vec2::Zero();  ///< the seed (the 3D start) in the face's parameters
  double angle = 0.0;      ///< the ply (its threads) turned on the mold, radians
  double path = 0.0;       ///< the base path turned on the mold, radians
};

/// Figures of one drape (those the objectives and the constraint read).
struct Figures {
  double energy = 0.0;         ///< sum cos^2(gamma)
  double max_shear_deg = 0.0;  ///< largest |90 deg - gamma|
  double flat_area = 0.0;      ///< area of the flat pattern's outline (mm^2)
  /// Fraction of the face the cut ply covers: the outline's area carried onto the surface by
  /// the mapped cells' mean ratio of surface to flat area, over the face's area.
  double coverage = 0.0;
  double cell_coverage = 0.0;     ///< mapped cells' surface area / face area (report.json's)
  std::uint64_t mapped = 0;       ///< mapped mesh points
  std::uint64_t shear_limit = 0;  ///< nodes stopped by the shear limit
  std::uint64_t overlap = 0;      ///< nodes stopped where the cloth would lie on itself
  std::uint64_t off_ply = 0;      ///< nodes beyond the ply rectangle
  /// The objective's value.
  double value(Objective o) const;
};

/// One drape of the search.
struct Evaluation {
  int index = 0;      ///< position in OptimizeResult::evaluations
  std::string phase;  ///< "scene", "design" or "refine:<objective>"
  Candidate candidate;
  Vec3 seed = Vec3::Zero();       ///< the seed's 3D point
  std::string status;             ///< "ok", "partial" or "error"
  std::string note;               ///< why it is not feasible (empty when it is)
  std::vector<Warning> warnings;  ///< the drape's (a partial drape: why)
  std::optional<Error> error;     ///< the drape's error (status "error")
  bool feasible = false;
  Figures figures;
};

/// Options of the search.
struct OptimizeOptions {
  bool vary_start = true;  ///< move the seed over the face
  bool vary_angle = true;  ///< turn the ply about the normal at the seed
  bool vary_path = false;  ///< turn the base path about the normal at the seed
  /// Objectives refined, in order; the best of every objective is reported.
  std::vector<Objective> objectives = {Objective::kEnergy};
  int evaluations = 200;  ///< drapes of the search (the scene's own drape not counted)
  /// Smallest feasible coverage (fraction of the face); default: the largest coverage of any
  /// ok drape (the scene's included; at most 1) less kCoverageSlack. A coverage above 1 +
  /// kCoverageSlack is never feasible (cloth on cloth, or an outline that does not match).
  std::optional<double> min_coverage;
  /// Seeds lie within this distance (mm) of the scene's start; default: the whole face.
  std::optional<double> radius;
  /// |angle| <= this (radians); default: half the cloth's symmetry period.
  std::optional<double> angle_range;
  /// |path| <= this (radians); default: 90 degrees (a base path and its reverse are one).
  std::optional<double> path_range;
  int jobs = 1;  ///< drapes run at a time
  const std::atomic<bool>* cancel = nullptr;
  /// Called (from a worker, serialised) after each drape with the drapes done and planned.
  std::function<void(int done, int total)> progress;
};

/// The search's result.
struct OptimizeResult {
  /// Every drape: [0] is the scene as given, then the design, then the refinements.
  std::vector<Evaluation> evaluations;
  /// Index of the best feasible drape per objective (Objective order), -1 if none.
  int best[kObjectiveCount] = {-1, -1, -1};
  /// The Pareto front over (energy, max shear, flat area) of the feasible drapes, by energy.
  std::vector<int> front;
  double min_coverage = 0.0;         ///< the constraint used (fraction)
  bool min_coverage_default = true;  ///< min(best coverage, 1) less kCoverageSlack
  double best_coverage = 0.0;        ///< the largest coverage of an ok drape
  double angle_range = 0.0;          ///< |angle| bound used (radians; 0: fixed)
  double angle_period = 0.0;         ///< the cloth's symmetry period (radians)
  double path_range = 0.0;           ///< |path| bound used (radians; 0: fixed)
  std::optional<double> radius;
  Vec2 uv_lo = Vec2::Zero(), uv_hi = Vec2::Zero();  ///< the seeds' parameter box
  int design = 0;                                   ///< drapes of the space-filling design
  int skipped = 0;         ///< design seeds off the face or beyond the radius (not draped)
  bool cancelled = false;  ///< stopped by OptimizeOptions::cancel
  /// The scene's base-path direction at its start (the 3D direction its 2D base direction
  /// maps to): a seed's base path runs along its projection on the tangent plane there (a
  /// translational rosette), turned by the candidate's path angle.
  Vec3 reference = Vec3::UnitX();
};

/// The scene the search starts from: its drape and how its flat pattern is cut.
struct SearchScene {
  DrapeProblem problem;
  DrapeOptions drape;
  /// The cut outline's minimum width (FlatPatternOptions::min_width).
  std::optional<double> min_width;
};

/// Runs the search on `face` (one face). Errors: the surface is not one face, or the scene's
/// own drape fails (its error).
Result<OptimizeResult> optimize(const SearchScene& scene, const MoldSurface& face,
                                const OptimizeOptions& options);

/// The drape problem of a candidate: the scene with the candidate's seed, ply angle and sweeps
/// (both sides of the base path); an error when the reference direction is normal to the face
/// at the seed.
Result<DrapeProblem> candidate_problem(const SearchScene& scene, const MoldSurface& face,
                                       const OptimizeResult& r, const Candidate& c);

}  // namespace plyfit
