#pragma once
// What a drape job reports to `plyfit batch`: `plyfit drape ... --outcome FILE` writes it as
// JSON (atomically), and the batch reads it back for its summary.

#include "job/drape_job.hpp"

#include <string>

namespace plyfit::cli {

/// The outcome as JSON text: status, error and error_code, exit_code, counts, max shear, time,
/// files.
std::string outcome_to_json(const JobOutcome& outcome, int exit_code);

/// Reads an outcome written by outcome_to_json; the exit code goes to `exit_code`.
Result<JobOutcome> outcome_from_json(const std::string& text, int* exit_code = nullptr);

}  // namespace plyfit::cli
