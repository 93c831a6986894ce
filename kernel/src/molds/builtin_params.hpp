// Private to the kernel: the parameters of a built-in mold or shell, defaults overridden by
// the given ones, with errors naming an unknown built-in, an unknown key or a bad value.
#pragma once

#include <plyfit/kernel/builtin_molds.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace plyfit::detail {

/// The info of built-in `name` in `list` and its parameter values (defaults, then `params`).
/// `what` names the kind ("mold", "shell") in messages.
inline Result<std::pair<const BuiltinInfo*, std::map<std::string, double>>> builtin_params(
    const std::vector<BuiltinInfo>& list, const std::string& what, const std::string& name,
    const std::map<std::string, double>& params) {
  const BuiltinInfo* info = nullptr;
  for (const auto& b : list)
    if (b.name == name) info = &b;
  if (!info) {
    std::string names;
    for (const auto& b : list) names += (names.empty() ? "" : ", ") + b.name;
    return Error{"unknown built-in " + what + " '" + name + "' (known: " + names + ")"};
  }
  std::map<std::string, double> v;
  for (const auto& p : info->params) v[p.key] = p.value;
  for (const auto& [k, x] : params) {
    if (!v.count(k)) {
      std::string keys;
      for (const auto& p : info->params) keys += (keys.empty() ? "" : ", ") + p.key;
      return Error{"built-in " + what + " '" + name + "' has no parameter '" + k +
                   "' (its parameters: " + keys + ")"};
    }
    if (!std::isfinite(x))
      return Error{"parameter '" + k + "' of '" + name + "' is not a finite number"};
    v[k] = x;
  }
  return std::pair<const BuiltinInfo*, std::map<std::string, double>>{info, std::move(v)};
}

}  // namespace plyfit::detail
