#include "report/batch_report.hpp"

#include "commands/commands.hpp"
#include "report/text_format.hpp"

#include <plyfit/exporters/laminate.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <ostream>
#include <sstream>

namespace plyfit::cli {

using exporters::csv_field;

void print_batch_table(const std::vector<SceneRun>& runs, std::ostream& os) {
  std::vector<std::vector<std::string>> rows = {
      {"scene", "status", "mapped", "max shear (deg)", "time (s)", "outputs"}};
  for (const auto& r : runs) {
    std::string outputs;
    if (!r.outdir.empty())
      outputs = r.outdir + "/ (" + std::to_string(r.files.size()) + " files)";
    else
      outputs = r.error.empty() ? "-" : error_line(r.error, r.error_code);
    const bool ran = succeeded(r);
    rows.push_back({r.name, r.status, ran ? std::to_string(r.mapped) : "-",
                    ran ? fixed(r.shear_max_deg, 3) : "-",
                    r.status == "not run" ? "-" : fixed(r.seconds, 2), outputs});
  }
  print_columns(rows, os);
}

std::map<std::string, int> count_statuses(const std::vector<SceneRun>& runs) {
  std::map<std::string, int> c = {{"ok", 0},      {"partial", 0},   {"error", 0},
                                  {"crashed", 0}, {"cancelled", 0}, {"not run", 0}};
  for (const auto& r : runs) c[r.status]++;
  return c;
}

std::string batch_count_line(const std::vector<SceneRun>& runs, double elapsed) {
  const auto counts = count_statuses(runs);
  std::ostringstream os;
  os << "plyfit batch: " << runs.size() << " scenes: " << counts.at("ok") << " ok, "
     << counts.at("partial") << " partial, " << counts.at("error") << " error, "
     << counts.at("crashed") << " crashed, " << counts.at("cancelled") << " cancelled, "
     << counts.at("not run") << " not run; " << fixed(elapsed, 1) << " s\n";
  return os.str();
}

std::string summary_json(const std::vector<SceneRun>& runs, const std::string& outroot,
                         const std::string& shard, int jobs, bool interrupted, double elapsed) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const auto& r : runs) {
    nlohmann::json j = {
        {"index", r.index},
        {"name", r.name},
        {"scene", r.path},
        {"status", r.status},
        {"error", r.error},
        {"error_code", r.error_code},
        {"exit_code", r.exit_code >= 0 ? nlohmann::json(r.exit_code) : nullptr},
        {"signal", r.signal ? nlohmann::json(r.signal) : nullptr},
        {"mapped", r.mapped},
        {"shear_max_deg", r.shear_max_deg},
        {"time_s", r.seconds},
        {"outdir", r.outdir.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.outdir)},
        {"files", r.files}};
    scenes.push_back(std::move(j));
  }
  nlohmann::json counts;
  for (const auto& [k, v] : count_statuses(runs)) counts[k == "not run" ? "not_run" : k] = v;
  counts["total"] = runs.size();
  const nlohmann::json j = {
      {"outroot", outroot},
      {"shard", shard.empty() ? nlohmann::json(nullptr) : nlohmann::json(shard)},
      {"jobs", jobs},
      {"interrupted", interrupted},
      {"elapsed_s", elapsed},
      {"counts", counts},
      {"scenes", scenes}};
  return j.dump(2) + "\n";
}

std::string summary_csv(const std::vector<SceneRun>& runs) {
  std::ostringstream os;
  os << "index,name,scene,status,exit_code,mapped,shear_max_deg,time_s,outdir,files,error,"
        "error_code\n";
  for (const auto& r : runs) {
    std::string files;
    for (const auto& f : r.files) files += (files.empty() ? "" : ";") + f;
    std::ostringstream shear;
    shear.precision(17);
    shear << r.shear_max_deg;
    os << r.index << "," << csv_field(r.name) << "," << csv_field(r.path) << "," << r.status << ","
       << (r.exit_code >= 0 ? std::to_string(r.exit_code) : "") << "," << r.mapped << ","
       << shear.str() << "," << fixed(r.seconds, 3) << "," << csv_field(r.outdir) << ","
       << csv_field(files) << "," << csv_field(r.error) << "," << r.error_code << "\n";
  }
  return os.str();
}

}  // namespace plyfit::cli
