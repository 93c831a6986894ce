// plyfit batch SCENE... [-j N] [-o OUTROOT] [--shard K/N]: runs every scene in a child process
// (commands/batch_runner.hpp), N at a time, each into OUTROOT/<name>/, then prints a summary
// table and writes OUTROOT/summary.json and summary.csv.

#include "commands/batch_runner.hpp"
#include "commands/commands.hpp"
#include "job/scene_names.hpp"
#include "report/batch_report.hpp"

#include <plyfit/exporters/atomic_file.hpp>

#include <unistd.h>
#include <algorithm>
#include <cstdlib>
#include <iostream>

namespace plyfit::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const OptionTable& batch_options() {
  static const OptionTable table = {
      help_option(),
      jobs_option("scenes"),
      output_option("OUTROOT", "output root folder", "batch-out"),
      {"shard", "K/N", "",
       "run only the scenes whose index (0-based, in the given order) mod N is K"},
      quiet_option(),
      scenes_option(),
  };
  return table;
}

const CommandHelp kBatchHelp = {
    "plyfit batch SCENE... [-j N] [-o OUTROOT] [--shard K/N]",
    "Runs `plyfit drape SCENE` for every scene, N at a time, each in its own process and\n"
    "into OUTROOT/<scene name>/ (the file name without extension; a repeated name gets\n"
    "-2, -3, ...). A failing or crashing scene does not stop the others. Prints a summary\n"
    "table and writes OUTROOT/summary.json and OUTROOT/summary.csv (with --shard K/N:\n"
    "summary-shard-K-of-N.json/.csv). Exit 0 when every scene succeeded (ok or partial),\n"
    "1 otherwise, 130 when interrupted (Ctrl-C: finished scenes keep their outputs,\n"
    "running ones leave nothing, the summary lists them as cancelled or not run).\n"};

/// --shard K/N: this shard's scenes are those whose index mod N is K.
struct Shard {
  long k = 0, n = 1;
  std::string text;  ///< as given; empty: no shard
};

Result<Shard> parse_shard(const std::string& text) {
  Shard s;
  s.text = text;
  const auto slash = text.find('/');
  char* end = nullptr;
  bool good = slash != std::string::npos && slash > 0 && slash + 1 < text.size();
  if (good) {
    s.k = std::strtol(text.c_str(), &end, 10);
    good = end == text.c_str() + slash;
    s.n = std::strtol(text.c_str() + slash + 1, &end, 10);
    good = good && *end == '\0' && s.n >= 1 && s.k >= 0 && s.k < s.n;
  }
  if (!good) return Error{ErrorCode::kBadShard, "shard", {text}};
  return s;
}

/// This shard's scenes, named over the whole list so that every shard names scenes alike.
std::vector<SceneRun> shard_scenes(const std::vector<std::string>& paths, const Shard& shard) {
  const auto names = unique_scene_names(paths);
  std::vector<SceneRun> runs;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (static_cast<long>(i % static_cast<std::size_t>(shard.n)) != shard.k) continue;
    SceneRun r;
    r.index = i;
    r.path = paths[i];
    r.name = names[i];
    runs.push_back(std::move(r));
  }
  return runs;
}

// The table, the count line and the summaries (false when one cannot be written).
bool report(const std::vector<SceneRun>& runs, const fs::path& outroot, const Shard& shard,
            int jobs, bool interrupted, Clock::time_point t0) {
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  print_batch_table(runs, std::cout);
  std::cout << batch_count_line(runs, elapsed());
  const std::string stem = shard.text.empty() ? "summary"
                                              : "summary-shard-" + std::to_string(shard.k) +
                                                    "-of-" + std::to_string(shard.n);
  bool written = true;
  for (const auto& [file, text] :
       {std::pair{outroot / (stem + ".json"),
                  summary_json(runs, outroot.string(), shard.text, jobs, interrupted, elapsed())},
        std::pair{outroot / (stem + ".csv"), summary_csv(runs)}}) {
    if (auto st = exporters::write_file_atomic(file.string(), text); !st) {
      print_error(st.error());
      written = false;
    }
  }
  return written;
}

Status create_folder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return Error{ErrorCode::kCannotCreateFolder, dir.string(), {ec.message()}};
  return ok_status();
}

int run_batch(const Options& o) {
  auto jobs = jobs_value(o);
  if (!jobs) return error_exit(kExitUsage, jobs.error(), o.namer());
  auto shard = o.given("shard") ? parse_shard(*o.text("shard")) : Result<Shard>(Shard{});
  if (!shard) return error_exit(kExitUsage, shard.error(), o.namer());

  const fs::path outroot = *o.text("output");
  const fs::path work = outroot / (".plyfit-batch-" + std::to_string(::getpid()));
  for (const auto& dir : {outroot, work})
    if (auto st = create_folder(dir); !st) return error_exit(kExitFailure, st.error());
  std::vector<SceneRun> runs = shard_scenes(o.all("scene"), *shard);
  const auto t0 = Clock::now();
  const bool interrupted =
      run_scenes(runs, static_cast<int>(*jobs), outroot, work, !o.given("quiet"));
  const bool written = report(runs, outroot, *shard, static_cast<int>(*jobs), interrupted, t0);
  if (interrupted) return kExitInterrupted;
  const bool all_ok = std::all_of(runs.begin(), runs.end(), succeeded);
  return all_ok && written ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterBatch{options_command(
    "batch", "run many scenes in parallel, each into its own folder, with a summary", 30,
    {batch_options, {"scene", "scene files", true}, kBatchHelp}, run_batch)};

}  // namespace
}  // namespace plyfit::cli
