// plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]: drapes scenes on one
// mold face with different initial conditions and prints the comparison of the paper's
// Tables 2 and 4 (our figures and the paper's own thread angles), marking the best scene for
// each criterion among those that cover the face.

#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "job/scene_file.hpp"
#include "job/scene_names.hpp"
#include "report/compare_report.hpp"

#include <filesystem>
#include <iostream>
#include <optional>
#include <utility>

namespace plyfit::cli {
namespace {

namespace fs = std::filesystem;

const OptionTable& compare_options() {
  static const OptionTable table = {
      help_option(),
      {"csv", "", "", "print CSV (full precision)"},
      {"markdown", "", "", "print a Markdown table"},
      output_option("OUTROOT", "also write each scene's outputs into OUTROOT/<scene name>/"),
      {"force", "", "", "compare scenes on different molds or faces anyway (with a warning)"},
      scenes_option(),
  };
  return table;
}

const CommandHelp kCompareHelp = {
    "plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]",
    "Drapes every scene (one mold face, different initial conditions) and prints,\n"
    "per scene, the figures of the paper's Tables 2 and 4: area (mapped mesh\n"
    "points), flat area (the flat pattern's outline), thread angles gamma min and\n"
    "max, max shear, shear energy sum cos^2(gamma), the same three by the paper's\n"
    "own thread angle (eq. 12), the coverage of the face by the mapped cells and\n"
    "by the outline, and the nodes stopped by the shear limit. The best scene for\n"
    "each criterion is marked among the ok scenes whose outline covers the face as\n"
    "well as the best, within 0.5% (a fitting that covers less never wins). Scenes\n"
    "on different molds or faces are refused unless --force.\n"};

/// The mold a job drapes: resolved file (or built-in spec), face and side.
std::string mold_identity(const DrapeJob& job) {
  std::string m = job.mold;
  if (m.rfind("builtin:", 0) != 0) {
    std::error_code ec;
    const auto c = fs::weakly_canonical(m, ec);
    if (!ec) m = c.string();
  }
  return m + " face " + std::to_string(job.face) + (job.flip_normal ? " (flipped)" : "");
}

// Every scene's job, loaded before any drape; a bad scene is printed (none: nullopt).
std::optional<std::vector<DrapeJob>> load_jobs(const std::vector<std::string>& paths,
                                               const std::vector<std::string>& names,
                                               const std::optional<std::string>& outroot) {
  std::vector<DrapeJob> jobs;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    auto raw = raw_from_scene(paths[i]);
    if (!raw) {
      print_error(raw.error(), scene_namer(paths[i]));
      return std::nullopt;
    }
    auto job = make_job(*raw, false);
    if (!job) {
      print_error(job.error(), input_namer(*raw, drape_options()));
      return std::nullopt;
    }
    job->outdir = outroot ? (fs::path(*outroot) / names[i]).string() : "";
    jobs.push_back(std::move(job).value());
  }
  return jobs;
}

// Scenes on different molds are refused (printed: false), or compared with a warning when
// forced.
bool same_molds(const std::vector<DrapeJob>& jobs, const std::vector<std::string>& paths,
                bool force) {
  for (std::size_t i = 1; i < jobs.size(); ++i) {
    const std::string mine = mold_identity(jobs[i]), first = mold_identity(jobs[0]);
    if (mine == first) continue;
    if (!force) {
      print_error(Error{ErrorCode::kDifferentMolds, "", {paths[i], mine, paths[0], first}});
      return false;
    }
    std::cerr << "plyfit: warning: comparing scenes on different molds: " << paths[i] << " drapes "
              << mine << ", but " << paths[0] << " drapes " << first << "\n";
  }
  return true;
}

// A scene's row: its figures, or its error's text and code.
Row row_of(const std::string& name, const Result<JobOutcome>& out, const DrapeJob& job) {
  Row r;
  r.name = name;
  if (!out) {
    r.error = exporters::describe(out.error(), job.name_input);
    r.error_code = to_string(out.error().code);
    return r;
  }
  const auto& m = out->metrics;
  r.ok = true;
  r.partial = out->status == "partial";
  r.warnings = out->warnings;
  r.values = {static_cast<double>(m.area_mesh_points),
              out->flat_outline_area,
              m.gamma_min * kRadToDeg,
              m.gamma_max * kRadToDeg,
              m.shear_max * kRadToDeg,
              m.shear_energy,
              m.paper.gamma_min * kRadToDeg,
              m.paper.gamma_max * kRadToDeg,
              m.paper.shear_max * kRadToDeg,
              m.paper.energy,
              100.0 * m.coverage,
              100.0 * out->outline_coverage,
              static_cast<double>(m.nodes.shear_limit)};
  return r;
}

int run_compare(const Options& o) {
  if (o.given("csv") && o.given("markdown"))
    return error_exit(kExitUsage, Error{ErrorCode::kOptionsExclusive, "", {"--csv", "--markdown"}});
  const auto& paths = o.all("scene");
  const auto names = unique_scene_names(paths);
  const auto jobs = load_jobs(paths, names, o.text("output"));
  if (!jobs) return kExitFailure;
  if (!same_molds(*jobs, paths, o.given("force"))) return kExitUsage;
  std::vector<Row> rows;
  std::vector<std::pair<Error, std::size_t>> failed;  // each failed scene's error, its job
  for (std::size_t i = 0; i < jobs->size(); ++i) {
    const auto out = run_job((*jobs)[i], nullptr, true);
    rows.push_back(row_of(names[i], out, (*jobs)[i]));
    rows.back().path = paths[i];
    if (!out) failed.emplace_back(Error(out.error()).in(paths[i]), i);
  }
  mark_best(rows);
  if (o.given("csv"))
    print_compare_csv(rows, std::cout);
  else if (o.given("markdown"))
    print_compare_markdown(rows, std::cout);
  else
    print_compare_text(rows, std::cout);
  for (const auto& [e, i] : failed) print_error(e, (*jobs)[i].name_input);
  return failed.empty() ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterCompare{
    options_command("compare", "compare drapes of one mold face (the paper's Tables 2 and 4)", 40,
                    {compare_options, {"scene", "scene files", true}, kCompareHelp}, run_compare)};

}  // namespace
}  // namespace plyfit::cli
