#pragma once
// Checks of a drape's net shared by the kernel, importer and CLI tests.

#include <plyfit/kernel/drape.hpp>

#include <cstddef>

namespace plyfit::support {

/// Seam gaps of a drape over several faces: nodes that are not mapped (nor off the ply) while
/// their two neighbours along one thread are mapped, on different faces, and near enough for
/// the node to lie between them (their distance at most the two links' rest lengths). Such a
/// node would be a hole in the net at a shared edge; a drape over a shell must have none.
inline std::size_t seam_gaps(const DrapeResult& r) {
  std::size_t gaps = 0;
  for (const DrapeNode& n : r.nodes) {
    if (n.mapped() || n.status == NodeStatus::kOffPly || n.status == NodeStatus::kPending) continue;
    for (const ThreadDir d : {ThreadDir::kPlusX, ThreadDir::kPlusY}) {
      const DrapeNode* a = r.neighbour(n, d);
      const DrapeNode* b = r.neighbour(n, opposite(d));
      if (!a || !b || !a->mapped() || !b->mapped() || a->face == b->face) continue;
      if ((a->point - b->point).norm() <= r.rest_length(n, d) + r.rest_length(n, opposite(d)))
        ++gaps;
    }
  }
  return gaps;
}

}  // namespace plyfit::support
