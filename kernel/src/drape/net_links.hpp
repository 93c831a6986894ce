// Private to the kernel: the enumeration of a drape's links behind DrapeResult::links() and the
// metrics' residual check, as a template (no std::function per link).
#pragma once

#include "drape/drape.hpp"

#include <cstdint>
#include <cstdlib>

namespace plyfit::detail {

// Calls f(a, b, rest, kind) for every link between two mapped nodes: thread links (split at
// the base path) from their regular end, then the base path's own links; see links().
template <class F>
void for_each_link(const DrapeResult& r, F&& f) {
  const auto& nodes = r.nodes;
  for (std::uint32_t k = 0; k < nodes.size(); ++k) {
    const DrapeNode& n = nodes[k];
    if (!n.mapped() || n.id.is_path_only()) continue;
    for (int d = 0; d < 4; ++d) {
      const auto dir = static_cast<ThreadDir>(d);
      const DrapeNode* m = r.linked(n, dir);  // links across a dart are not the cloth's
      if (!m || !m->mapped()) continue;
      // Regular-regular links once (from their -x / -y end); links to path nodes from the
      // regular end, both sides.
      const bool plus = dir == ThreadDir::kPlusX || dir == ThreadDir::kPlusY;
      if (!m->id.is_path_only() && !plus) continue;
      f(k, static_cast<std::uint32_t>(m - nodes.data()), r.rest_length(n, dir),
        is_weft(dir) ? LinkKind::kWeft : LinkKind::kWarp);
    }
  }
  const auto& bp = r.base_path;
  for (std::size_t k = 1; k < bp.size(); ++k) {
    const DrapeNode& a = nodes[bp[k - 1]];
    const DrapeNode& b = nodes[bp[k]];
    if (!a.mapped() || !b.mapped()) continue;  // a link across a hole of the face
    // A path along a thread between two crossings is that thread's link, listed already.
    if (!a.id.is_path_only() && !b.id.is_path_only() &&
        std::abs(a.id.i - b.id.i) + std::abs(a.id.j - b.id.j) == 1)
      continue;
    f(bp[k - 1], bp[k], (b.ply - a.ply).norm(), LinkKind::kBase);
  }
}

}  // namespace plyfit::detail
