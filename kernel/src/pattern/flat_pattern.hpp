#pragma once
/// \file flat_pattern() on the kernel's surface interface (the public one forwards here).

#include "surface/drape_surface.hpp"

#include <plyfit/kernel/flat_pattern.hpp>

namespace plyfit {

/// Computes the flat pattern of a drape on `surface` (see the public flat_pattern()).
FlatPattern flat_pattern(const DrapeSurface& surface, const DrapeResult& result,
                         const FlatPatternOptions& options = {});

}  // namespace plyfit
