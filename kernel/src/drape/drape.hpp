#pragma once
/// \file drape() on the kernel's surface interface: the public drape() forwards here, and the
/// kernel's own callers (and its tests) drape a Face or Shell directly.

#include "drape/scan/node_index.hpp"
#include "surface/drape_surface.hpp"

#include <plyfit/kernel/drape.hpp>

namespace plyfit {

/// Drapes the ply on `surface` (see the public drape()).
Result<DrapeResult> drape(const DrapeSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options = {});
/// drape_auto_darts() on the kernel's surface interface.
Result<DrapeResult> drape_auto_darts(const DrapeSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options, int max_drapes);

}  // namespace plyfit
