#include "job/outcome.hpp"

#include <nlohmann/json.hpp>

namespace plyfit::cli {

std::string outcome_to_json(const JobOutcome& o, int exit_code) {
  const auto& n = o.metrics.nodes;
  nlohmann::json j = {{"status", o.status},           {"error", o.error},
                      {"error_code", o.error_code},   {"exit_code", exit_code},
                      {"mapped", o.mapped},           {"auxiliary", n.auxiliary},
                      {"outside", n.outside},         {"off_ply", n.off_ply},
                      {"shear_limit", n.shear_limit}, {"failed", n.failed},
                      {"overlap", n.overlap},         {"conflict", n.conflict},
                      {"path_end", n.path_end},       {"shear_max_deg", o.shear_max_deg},
                      {"total_ms", o.total_ms},       {"files", o.files}};
  return j.dump(2) + "\n";
}

Result<JobOutcome> outcome_from_json(const std::string& text, int* exit_code) {
  try {
    const auto j = nlohmann::json::parse(text);
    JobOutcome o;
    o.status = j.at("status").get<std::string>();
    o.error = j.at("error").get<std::string>();
    o.error_code = j.at("error_code").get<std::string>();
    o.mapped = j.at("mapped").get<std::uint64_t>();
    o.metrics.nodes.mapped = o.mapped;
    o.metrics.nodes.auxiliary = j.at("auxiliary").get<std::uint64_t>();
    o.metrics.nodes.outside = j.at("outside").get<std::uint64_t>();
    o.metrics.nodes.off_ply = j.at("off_ply").get<std::uint64_t>();
    o.metrics.nodes.shear_limit = j.at("shear_limit").get<std::uint64_t>();
    o.metrics.nodes.failed = j.at("failed").get<std::uint64_t>();
    o.metrics.nodes.overlap = j.value("overlap", std::uint64_t{0});
    o.metrics.nodes.conflict = j.value("conflict", std::uint64_t{0});
    o.metrics.nodes.path_end = j.value("path_end", std::uint64_t{0});
    o.shear_max_deg = j.at("shear_max_deg").get<double>();
    o.total_ms = j.at("total_ms").get<double>();
    o.files = j.at("files").get<std::vector<std::string>>();
    if (exit_code) *exit_code = j.at("exit_code").get<int>();
    return o;
  } catch (const nlohmann::json::exception& e) {
    return Error{ErrorCode::kOutcomeUnreadable, "", {std::string(e.what())}};
  }
}

}  // namespace plyfit::cli
