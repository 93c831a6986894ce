#pragma once
/// \file Built-in shells: exact analytic molds of several faces sewn along shared edges, for
/// drapes across faces without a file (and for the tests that compare them with one face).
/// Lengths in millimetres, angles in degrees, outward normals.

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/shell.hpp>

#include <map>
#include <string>
#include <vector>

namespace plyfit {

/// Every built-in shell.
const std::vector<BuiltinInfo>& builtin_shells();
/// True when `name` is a built-in shell.
bool is_builtin_shell(const std::string& name);
/// The shell of built-in `name` with `params` overriding the defaults. Errors name an unknown
/// shell, an unknown key or an invalid value.
Result<ShellData> builtin_shell(const std::string& name,
                                const std::map<std::string, double>& params);

}  // namespace plyfit
