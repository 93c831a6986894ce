#pragma once
// What plyfit batch prints and writes: the table of scenes and the count line on stdout,
// summary.json and summary.csv.

#include "commands/batch_runner.hpp"

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace plyfit::cli {

/// One line per scene: name, status, mapped nodes, max shear, time, outputs or the error
/// (with its code).
void print_batch_table(const std::vector<SceneRun>& runs, std::ostream& os);

/// Scenes by status (ok, partial, error, crashed, cancelled, not run).
std::map<std::string, int> count_statuses(const std::vector<SceneRun>& runs);

/// "plyfit batch: N scenes: A ok, B partial, ...; T s".
std::string batch_count_line(const std::vector<SceneRun>& runs, double elapsed);

/// summary.json: the run (output root, shard, jobs, interrupted, elapsed), the counts and every
/// scene.
std::string summary_json(const std::vector<SceneRun>& runs, const std::string& outroot,
                         const std::string& shard, int jobs, bool interrupted, double elapsed);
/// summary.csv: one row per scene.
std::string summary_csv(const std::vector<SceneRun>& runs);

}  // namespace plyfit::cli
