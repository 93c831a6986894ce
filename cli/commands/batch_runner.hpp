#pragma once
// The scenes of plyfit batch, each run in a child process (`plyfit drape SCENE -o DIR --quiet
// --outcome FILE`), N at a time.
//
// Process model: a child process per scene isolates crashes and OpenCASCADE's global reader
// state. A child writes into a staging folder OUTROOT/.plyfit-batch-<pid>/<name>/ that is
// renamed to OUTROOT/<name>/ only when the drape succeeded, so a failed, crashed or cancelled
// scene leaves neither final nor temporary files behind. Ctrl-C (SIGINT) or SIGTERM: no new
// scene starts, running children get SIGINT (SIGKILL after kKillGraceSeconds, or at a second
// Ctrl-C), their staging folders are removed, and the summary says which scenes were
// cancelled and which were not run.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace plyfit::cli {

/// One scene of the batch and what became of it.
struct SceneRun {
  std::size_t index = 0;           ///< position in the given list
  std::string path;                ///< scene file as given
  std::string name;                ///< unique scene name (output folder name)
  std::string status = "not run";  ///< ok, partial, error, crashed, cancelled, not run
  std::string error;               ///< the error's text (exporters::describe)
  std::string error_code;          ///< and its code
  int exit_code = -1;              ///< -1: none (not run, or killed by a signal)
  int signal = 0;
  std::uint64_t mapped = 0;
  double shear_max_deg = 0.0;
  double seconds = 0.0;
  std::string outdir;  ///< final folder, empty if none
  std::vector<std::string> files;
  // While running:
  pid_t pid = -1;
  std::chrono::steady_clock::time_point started;
  std::string staging, outcome, log_out, log_err;
};

/// Ok or partial.
bool succeeded(const SceneRun& s);

/// Runs the scenes, `jobs` at a time, staging under `work` and publishing into `outroot`; a
/// progress line on stderr when `progress` and stderr is a terminal. Returns true when
/// interrupted (SIGINT, SIGTERM).
bool run_scenes(std::vector<SceneRun>& runs, int jobs, const std::filesystem::path& outroot,
                const std::filesystem::path& work, bool progress);

}  // namespace plyfit::cli
