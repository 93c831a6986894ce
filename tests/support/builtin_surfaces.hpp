#pragma once
// Built-in molds as the library user gets them (MoldSurface), for tests of public APIs.

#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/mold.hpp>

#include <catch2/catch.hpp>

#include <map>
#include <string>

namespace plyfit::support {

/// The face of built-in mold `name` with `params`, required to build.
inline MoldSurface builtin_surface(const std::string& name,
                                   const std::map<std::string, double>& params = {}) {
  auto fd = builtin_mold(name, params);
  REQUIRE(fd);
  auto m = MoldSurface::from_face(*fd);
  REQUIRE(m);
  return *m;
}

}  // namespace plyfit::support
