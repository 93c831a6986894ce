#pragma once
/// \file Warnings as plyfit's JSON writes them (report.json, plybook.json, plyfit info --json):
/// each its code, for programs, and its sentence, for people (messages.hpp).

#include <plyfit/exporters/messages.hpp>

#include <nlohmann/json.hpp>

#include <vector>

namespace plyfit::exporters {

/// [{"code": "separate_shells", "text": "sewing: the 4 faces form ..."}, ...]
inline nlohmann::json warnings_json(const std::vector<Warning>& warnings) {
  nlohmann::json out = nlohmann::json::array();
  for (const Warning& w : warnings)
    out.push_back({{"code", to_string(w.code)}, {"text", message(w)}});
  return out;
}

}  // namespace plyfit::exporters
