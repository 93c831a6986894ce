// Private to the kernel: the metrics of §7.1 and the residual checks, computed after the scan.
#pragma once

#include "drape/drape.hpp"

namespace plyfit::detail {

/// Fills res.metrics (node counts, thread angles, energy, the paper's thread angles and energy,
/// areas, residual checks) and the nodes' thread angles.
void compute_metrics(const DrapeSurface& s, DrapeResult& res);

}  // namespace plyfit::detail
