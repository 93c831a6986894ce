// The text of the splices' errors and warnings (kernel/src/pattern/splice.cpp).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_roll_narrower_than_cells(const Values& x) {
  return "the roll width " + x.brief(0) + " mm is narrower than two cells across the warp (" +
         x.brief(1) + " mm): no piece could hold a whole cell on each side of a seam";
}

std::string text_splice_overlap_negative(const Values& x) {
  return "the splice overlap " + x.brief(0) + " mm is negative: give 0 (a butt joint) or more";
}

std::string text_splice_overlap_too_wide(const Values& x) {
  return "the splice overlap " + x.brief(0) + " mm leaves less than one cell (" + x.brief(2) +
         " mm) of new cloth per piece on a roll " + x.brief(1) +
         " mm wide: give an overlap below the roll width less a cell";
}

std::string text_splice_value_not_finite(const Values& x) {
  return "the " + x.text(0) + " must be a finite number";
}

std::string text_splice_stagger_negative(const Values& x) {
  return "the splice stagger " + x.brief(0) + " mm is negative: give 0 (no stagger) or more";
}

std::string warning_splice_stagger_unmet(const Values& x) {
  return "the roll leaves no room to keep the seams " + x.brief(0) +
         " mm from the other plies' seams: the nearest seam is " + x.brief(1) +
         " mm from one (seams placed as without the stagger)";
}

}  // namespace plyfit::exporters::render
