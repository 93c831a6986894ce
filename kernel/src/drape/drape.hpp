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
  std::shared_ptr<const DartSet> darts;
  const SolveMemo* last = nullptr;
  SolveMemo* next = nullptr;
  bool seams = false;
};
}  // namespace detail
/// drape() made again (detail::Redrape).
Result<DrapeResult> drape(const DrapeSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options, const detail::Redrape& again);
namespace detail {
/// A drape scanned but not yet measured (scan_drape), with what its scan left for the steps
/// after it: drape_auto_darts measures only the drape it keeps. `res` holds the nodes, their
/// statuses, failures and cut links, not yet the metrics, darts or warnings.
struct ScannedDrape {
  DrapeResult res;
  std::vector<std::uint64_t> cut_out;     ///< Scanner::cut_out
  std::vector<std::uint64_t> seam_links;  ///< Scanner::seam_links
  bool cancelled = false, truncated = false;
  std::uint64_t path_off_ply = 0;
  std::uint64_t thread_end_nodes = 0;  ///< Scanner::thread_ends
  Vec2 thread_end_first = Vec2::Zero();
  std::uint64_t slit_links = 0;  ///< Scanner::path_slits
  Vec2 slit_stop = Vec2::Zero();
  std::shared_ptr<const DartSet> darts;  ///< the darts it was draped with
  double scan_ms = 0.0;
};
/// The steps of drape() up to and with the scan.
Result<ScannedDrape> scan_drape(const DrapeSurface& surface, const DrapeProblem& problem,
                                const DrapeOptions& options, const Redrape& again);
/// The steps of drape() after the scan: the metrics, the darts' and seams' cut lines, the
/// warnings and the judgement.
DrapeResult measure_drape(const DrapeSurface& surface, const DrapeProblem& problem,
                          const DrapeOptions& options, ScannedDrape scanned);
/// The nodes of a status (a count over the nodes, before the metrics are made).
std::uint64_t count_status(const DrapeResult& r, NodeStatus status);
}  // namespace detail
/// drape_auto_darts() on the kernel's surface interface.
Result<DrapeResult> drape_auto_darts(const DrapeSurface& surface, const DrapeProblem& problem,
                                     const DrapeOptions& options, int max_drapes);

}  // namespace plyfit
