// Private to the kernel: the solves of one drape kept for the next drape of the same ply on the
// same surface (automatic darts drape it again with more darts). A node whose solve sees the
// same cloth as in the last drape takes the last drape's solve instead of solving again.
#pragma once

#include "drape/scan/node_index.hpp"
#include "drape/solvers/solvers.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace plyfit::detail {

/// Per node of its drape (by index in DrapeResult::nodes), its solve and what the solve saw;
/// the next drape finds a node's entry through that drape's NodeIndex (a vector and the index
/// the drape built anyway: no hash map of its own).
struct SolveMemo {
  struct Entry {
    std::uint64_t seen = 0;  // hash of the nodes the solve read (Scanner::seen)
    SolveResult r;
    std::uint8_t flags = 0;  // the node's kSolvedTwo, kFromPlusX and kFromPlusY
    float du = 0.0f, dv = 0.0f;
    std::uint8_t guess = 0;  // its guess's error and rule (Scanner::GuessKind)
    bool kept = false;       // a solve is kept here
  };
  std::vector<Entry> nodes;
  std::shared_ptr<const NodeIndex> index;  ///< the drape's nodes by id (set after its scan)
  std::uint64_t reused = 0;                ///< solves taken from the last drape's memo
};

}  // namespace plyfit::detail
