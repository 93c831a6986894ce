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
namespace detail {
class DartSet;
struct SolveMemo;
/// A drape made again (automatic darts): its darts already on the surface (DartSet::of, walked
/// on it; nullptr: the problem's darts), the last drape's solves (SolveMemo), where to keep
/// its own (nullptr: none kept, none taken), whether the scan cuts seams where fronts of cloth
/// meet and disagree (Scanner::seam_where_fronts_meet).
struct Redrape {
  const DartSet* darts = nullptr;
  const SolveMemo* last = nullptr;
  SolveMemo* next = nullptr;
  bool seams = false;
};
}  // namespace detail
/// drape() made again (detail::Redrape).
Result<DrapeResult> drape(const DrapeSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options, const detail::Redrape& again);
/// drape_auto_darts() on the kernel's surface interface.
Result<DrapeResult> drape_auto_darts(const DrapeSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options, int max_drapes);

}  // namespace plyfit
