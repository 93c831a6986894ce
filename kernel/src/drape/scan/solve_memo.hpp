// Private to the kernel: the solves of one drape kept for the next drape of the same ply on the
// same surface (automatic darts drape it again with more darts). A node whose solve sees the
// same cloth as in the last drape takes the last drape's solve instead of solving again.
#pragma once

#include "drape/solvers/solvers.hpp"

#include <cstdint>
#include <unordered_map>

namespace plyfit::detail {

/// Per regular node (NodeId::key), its solve and what the solve saw.
struct SolveMemo {
  struct Entry {
    std::uint64_t seen = 0;  // hash of the nodes the solve read (Scanner::seen)
    SolveResult r;
    std::uint8_t flags = 0;  // the node's kSolvedTwo, kFromPlusX and kFromPlusY
    float du = 0.0f, dv = 0.0f;
    std::uint8_t guess = 0;  // its guess's error and rule (Scanner::GuessKind)
  };
  std::unordered_map<std::uint64_t, Entry> nodes;
  std::uint64_t reused = 0;  ///< solves taken from the last drape's memo
};

}  // namespace plyfit::detail
