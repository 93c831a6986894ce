#pragma once
// Built-in shells for the tests (no Catch here: the callers check the result).

#include <plyfit/kernel/builtin_molds.hpp>
#include "surface/shell/shell.hpp"

#include <map>
#include <string>
#include <utility>

namespace plyfit::support {

/// The built-in shell `name` (builtin_shell) with `params`, sewn (Shell::create); the first
/// error of the two otherwise.
inline Result<Shell> make_builtin_shell(const std::string& name,
                                        const std::map<std::string, double>& params = {}) {
  auto data = builtin_shell(name, params);
  if (!data) return data.error();
  return Shell::create(std::move(data).value());
}

}  // namespace plyfit::support
