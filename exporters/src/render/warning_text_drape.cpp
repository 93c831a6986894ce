// The text of the drape's warnings (kernel/src/drape).
#include "render/message_text.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>

namespace plyfit::exporters::render {

namespace {

// A share (values[k], 1 = the whole surface) as a whole percentage.
std::string percent(const Values& x, std::size_t k) {
  return std::to_string(static_cast<int>(std::lround(100 * x.number(k))));
}

}  // namespace

PLYFIT_SENTENCE(
    warning_start_far,
    "the 3D start lies {b0} mm from the surface, more than {b1} times its size ({b2} mm, the "
    "bounding-box diagonal): the drape starts at the nearest point of the surface, ({b3}, {b4}, "
    "{b5}), far from where it was asked to; check the start, the face and the unit");

PLYFIT_SENTENCE(warning_no_cell_mapped,
                "the drape maps no cell: the cloth leaves the face at the base path on every swept "
                "side (do the sweep directions point into the face from the base path?)");

PLYFIT_SENTENCE(warning_sweep_maps_no_node,
                "sweep direction {n0} maps no node: the cloth leaves the face at the base path on "
                "its side (the start on the face's edge?)");

namespace {

// The stops inside the surface that bound the cloth (values[first..first + 4]: at the shear
// limit, overlapping, failed, in conflict, past the base path's end), or what leaves the rest
// uncovered when there are none (otherwise).
std::string uncovered_because(const Values& x, std::size_t first, const char* otherwise) {
  static const char* const kStops[] = {"at the shear limit", "overlapping", "failed", "in conflict",
                                       "past the base path's end"};
  std::string stops;
  for (std::size_t k = 0; k < std::size(kStops); ++k)
    if (x.count(first + k) > 0)
      stops += (stops.empty() ? "" : ", ") + x.n(first + k) + " " + kStops[k];
  return stops.empty() ? std::string(otherwise) : "the cloth stops inside it (" + stops + ")";
}

}  // namespace

// values: the coverage, then the nodes stopped inside the surface by the shear limit, overlap,
// failure, conflict and the base path's end.
std::string warning_uncovered_area(const Values& x) {
  return "the mapped cells cover " + percent(x, 0) +
         "% of the surface, less than the cells along its boundary explain: " +
         uncovered_because(
             x, 1, "the sweeps do not reach the rest (another start, base path or sweep may)");
}

// values: the outline's coverage, the share it may fall short, then the stops as above.
std::string warning_outline_short(const Values& x) {
  char text[96];
  std::snprintf(text, sizeof text, "%.1f%% of the surface (%.1f%% uncovered, more than the %.1f%%",
                100 * x.number(0), 100 * (1 - x.number(0)), 100 * x.number(1));
  return std::string("the flat pattern's outline covers ") + text + " the coverage rule allows): " +
         uncovered_because(x, 2,
                           "the sweeps do not reach the rest (another start, base path or sweep "
                           "may), or the outline stops at the mapped cells where no cell corner "
                           "could be placed past the face's edge");
}

PLYFIT_SENTENCE(warning_path_ends,
                "the base path ends at ply ({b0}, {b1}): the base plane lies {b2} deg from the "
                "surface's tangent plane there and its section turns back (or ends where the plane "
                "touches the surface) within one link ahead, so the path cannot go on; a "
                "base-plane normal more nearly along the surface there carries the path further");

PLYFIT_SENTENCE(warning_cancelled, "cancelled");

PLYFIT_SENTENCE(warning_node_cap, "stopped at the node cap of {n0} nodes");

std::string warning_cloth_on_itself(const Values& x) {
  return "the mapped cells cover " + percent(x, 0) +
         "% of the surface: the cloth lies on itself somewhere";
}

PLYFIT_SENTENCE(warning_failed_nodes, "{n0} node(s) where the solver found no solution");

PLYFIT_SENTENCE(warning_conflict_nodes,
                "{n0} conflict node(s): two fronts of cloth met there and disagree (no point of "
                "the surface fits all their links), so the cloth cannot be laid there as one "
                "piece: a dart or a splice is needed there, or another start or base path");

PLYFIT_SENTENCE(warning_thread_ends,
                "{n0} node(s), the first at ply ({b1}, {b2}), marked outside: a thread continued "
                "from one neighbour cannot follow the surface for one link there (the section of "
                "its plane, square to the surface, turns back: the surface curls tighter than the "
                "thread spacing); a finer spacing follows it further");

PLYFIT_SENTENCE(
    warning_path_slit,
    "the base path stops at ply ({b0}, {b1}) while the cloth goes on beyond it along the path's "
    "line (the base plane's section ends there: at a gap in the surface that is no hole of one "
    "face, such as a missing face or a notch outside the face's outer boundary, or where the "
    "section leaves the face or curls back on itself): {n2} thread link(s) across the path's line "
    "there join the two sweeps' cloth unsolved (a slit in the flat pattern)");

std::string warning_darts_not_enough(const Values& x) {
  return "after " + x.n(2) + " drapes with automatic darts the ply still has " + x.n(0) +
         " conflict and " + x.n(1) +
         " shear-limit node(s): it is not laid as one piece within the lock";
}

}  // namespace plyfit::exporters::render
