// Private to the kernel: the metrics of §7.1 and the residual checks, computed after the scan.
#pragma once

#include "drape/drape.hpp"

namespace plyfit::detail {

/// Fills res.metrics (node counts, thread angles, energy, the paper's thread angles and energy,
/// areas, residual checks, the floor of the solvers' tolerance) and the nodes' thread angles.
void compute_metrics(const DrapeSurface& s, const Tolerances& tol, DrapeResult& res);

}  // namespace plyfit::detail
