#pragma once
// The plies of a laminate draped: each ply's job made from its scene, each distinct mold (file,
// faces, side, tolerances) read and converted once, and the plies draped N at a time by worker
// threads sharing the loaded surfaces. A ply that fails fails alone.

#include "job/drape_job.hpp"
#include "job/laminate_file.hpp"

#include <atomic>
#include <optional>
#include <string>
#include <vector>

namespace plyfit::cli {

/// A ply of the laminate and how its drape went.
struct PlyRun {
  LaminatePly ply;
  std::optional<DrapeJob> job;  ///< none when its keys are wrong
  JobOutcome outcome;           ///< status "error" until it ran; error text and code
  std::string error_line;       ///< for status error: the error as one line ("TEXT [code]")
  bool ran = false;             ///< its drape was started
  bool succeeded() const { return outcome.status == "ok" || outcome.status == "partial"; }
};

/// Names a ply's keys in messages: "FILE [ply NAME]: key 'KEY'" (its angle as `angle`).
exporters::InputNamer ply_namer(const LaminatePly& ply);

/// Drapes every ply of the laminate, `jobs` at a time (threads). `cancel` stops the running
/// drapes (their outcome: cancelled); `on_done` is called (from a worker, one at a time) as
/// each ply ends. Returns the plies in stacking order.
std::vector<PlyRun> drape_plies(const Laminate& laminate, int jobs, const std::atomic<bool>* cancel,
                                const std::function<void(const PlyRun&)>& on_done);

}  // namespace plyfit::cli
