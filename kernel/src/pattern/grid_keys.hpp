#pragma once
/// \file Keys of a uniform 3D grid (internal to pattern/).

#include <plyfit/kernel/types.hpp>

#include <cmath>
#include <cstdint>

namespace plyfit::detail {

/// Calls f(key) for every cell of the uniform grid of edge `cell` that the box [lo, hi]
/// meets. Keys hold 21 bits per axis: cells 2^21 apart share a key, which only adds
/// candidates to a lookup.
template <class F>
void for_grid_cells(const Vec3& lo, const Vec3& hi, double cell, F&& f) {
  auto idx = [&](double x) { return static_cast<std::int64_t>(std::floor(x / cell)); };
  for (std::int64_t i = idx(lo.x()); i <= idx(hi.x()); ++i)
    for (std::int64_t j = idx(lo.y()); j <= idx(hi.y()); ++j)
      for (std::int64_t k = idx(lo.z()); k <= idx(hi.z()); ++k)
        f((static_cast<std::uint64_t>(i & 0x1fffff) << 42) |
          (static_cast<std::uint64_t>(j & 0x1fffff) << 21) |
          static_cast<std::uint64_t>(k & 0x1fffff));
}

}  // namespace plyfit::detail
