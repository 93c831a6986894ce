// Private to the kernel: the metrics of §7.1 and the residual checks, computed after the scan.
#pragma once

#include "drape/drape.hpp"
#include "named_values.hpp"

#include <cstdint>

namespace plyfit::detail {

/// A node status, its name (to_string) and the count of NodeCounts its nodes add to (none
/// for a pending node; a mapped base-path point counts as `auxiliary`, not `mapped`).
struct NodeStatusRow {
  NodeStatus value;
  const char* name;
  std::uint64_t NodeCounts::*count;
};
inline constexpr NodeStatusRow kNodeStatuses[] = {
    {NodeStatus::kMapped, "mapped", &NodeCounts::mapped},
    {NodeStatus::kOutside, "outside", &NodeCounts::outside},
    {NodeStatus::kOffPly, "off_ply", &NodeCounts::off_ply},
    {NodeStatus::kShearLimit, "shear_limit", &NodeCounts::shear_limit},
    {NodeStatus::kFailed, "failed", &NodeCounts::failed},
    {NodeStatus::kOverlap, "overlap", &NodeCounts::overlap},
    {NodeStatus::kConflict, "conflict", &NodeCounts::conflict},
    {NodeStatus::kPathEnd, "path_end", &NodeCounts::path_end},
    {NodeStatus::kPending, "pending", nullptr},
};
static_assert(lists_enum(kNodeStatuses, NodeStatus::kPending));

/// Fills res.metrics (node counts, thread angles, energy, the paper's thread angles and energy,
/// areas, residual checks, the floor of the solvers' tolerance) and the nodes' thread angles.
void compute_metrics(const DrapeSurface& s, const Tolerances& tol, DrapeResult& res);

}  // namespace plyfit::detail
