#pragma once
// Checks of a drape's net shared by the kernel, importer and CLI tests.

#include <plyfit/kernel/drape.hpp>

#include <catch2/catch.hpp>

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

/// A drape over a shell that crosses its edges cleanly: no node failed, in conflict or laid
/// over cloth, and no seam gap.
inline void check_clean_crossing(const DrapeResult& r) {
  CHECK(r.metrics.nodes.failed == 0);
  CHECK(r.metrics.nodes.conflict == 0);
  CHECK(r.metrics.nodes.overlap == 0);
  CHECK(seam_gaps(r) == 0);
}

// Two nets with the same nodes: every node reached by one is reached by the other with the
// same status, and mapped nodes lie within tol of each other. Returns the mapped count.
inline std::size_t same_net(const DrapeResult& a, const DrapeResult& b, double tol) {
  std::size_t mapped = 0;
  CHECK(a.nodes.size() == b.nodes.size());
  for (const DrapeNode& n : a.nodes) {
    const DrapeNode* m = b.find(n.id);
    INFO("node (" << n.id.i << ", " << n.id.j << ") " << to_string(n.status));
    REQUIRE(m);
    CHECK(m->status == n.status);
    if (n.mapped() && m->mapped()) {
      ++mapped;
      const double e = (n.point - m->point).norm();
      if (e > tol) FAIL_CHECK("mapped nodes " << e << " apart");
    }
  }
  return mapped;
}

}  // namespace plyfit::support
