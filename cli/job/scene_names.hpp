#pragma once
// Scene names shared by batch and compare: the scene file's name without extension, made
// unique in the given order ("a", "a-2", "a-3", ...).

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace plyfit::cli {

/// Unique names for scene files, in the given order.
inline std::vector<std::string> unique_scene_names(const std::vector<std::string>& paths) {
  std::set<std::string> taken;
  std::vector<std::string> names;
  for (const auto& p : paths) {
    std::string base = std::filesystem::path(p).stem().string();
    if (base.empty() || base == "." || base == "..") base = "scene";
    std::string name = base;
    for (int k = 2; taken.count(name); ++k) name = base + "-" + std::to_string(k);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

}  // namespace plyfit::cli
