#pragma once
// What plyfit optimize prints and writes: the stdout table, optimize.json and front.svg.

#include "job/drape_job.hpp"

#include <plyfit/kernel/optimize.hpp>

#include <string>

namespace plyfit::cli {

/// Why a drape of the search is not feasible, or its error, as text.
std::string note_of(const Evaluation& e);

/// The stdout table: the scene, the best per objective, the Pareto front.
std::string optimize_table(const DrapeJob& scene, const OptimizeResult& r, const OptimizeOptions& o,
                           double seconds, int jobs);
/// optimize.json: the inputs, the best per objective, the front and every drape; `run`
/// (threads, seconds) is the only part that changes between equal runs.
std::string optimize_json(const DrapeJob& scene, const OptimizeResult& r, const OptimizeOptions& o,
                          double seconds, int jobs);
/// best-OBJECTIVE.ini: the scene of the best drape for `ob` (which must have one), with a
/// comment giving its figures; `path` is the scene file searched.
std::string best_scene_ini(const DrapeJob& scene, const MoldSurface& face, const OptimizeResult& r,
                           Objective ob, const std::string& path);
/// The drapes of the search that are feasible.
int feasible_count(const OptimizeResult& r);
/// front.svg: the feasible drapes and the Pareto front in three panels (energy - max shear,
/// energy - flat area, max shear - flat area).
std::string optimize_svg(const DrapeJob& scene, const OptimizeResult& r);

}  // namespace plyfit::cli
