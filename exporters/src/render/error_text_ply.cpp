// The text of the ply definition's errors (kernel/src/drape/ply_definition.cpp).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

PLYFIT_SENTENCE(text_seed_not_finite, "the seed point must be finite");

std::string text_seed_off_mold(const Values& x) {
  if (x.number(0) < 0) return "no point of the mold could be found near the seed";
  return "the seed lies " + x.brief(0) + " from the mold, more than half the mold's size (" +
         x.brief(1) + "): a wrong unit, frame or mold?";
}

PLYFIT_SENTENCE(text_rosette_zero, "the rosette direction must be a finite non-zero vector");

PLYFIT_SENTENCE(
    text_rosette_along_normal,
    "the rosette direction lies {b0} deg from the surface normal at the seed: its projection onto "
    "the surface (the 0 deg direction) is undefined; give a direction along the surface");

PLYFIT_SENTENCE(text_ply_angle_range, "the ply angle must be in [-180, 180] degrees");

PLYFIT_SENTENCE(text_boundary_empty, "the boundary has no curve");

std::string text_boundary_curve_points(const Values& x) {
  if (x.number(2) == 0.0) return "boundary curve " + x.text(0) + " has a point that is not finite";
  return "boundary curve " + x.text(0) + " has " + x.n(1) +
         " points: a closed loop needs at least 3, an open curve 2";
}

PLYFIT_SENTENCE(text_boundary_gap,
                "boundary curve {t0} ends at ({t1}) {b2} mm from any other curve's end, more than "
                "the tolerance {b3} mm: the curves do not close into loops");

std::string text_boundary_off_mold(const Values& x) {
  if (x.number(1) < 0)
    return "boundary curve " + x.text(0) + " could not be projected onto the mold";
  return "boundary curve " + x.text(0) + " lies " + x.brief(1) + " mm from the mold at (" +
         x.text(3) + "), more than the tolerance " + x.brief(2) +
         " mm: a wrong curve, unit or frame?";
}

PLYFIT_SENTENCE(text_boundary_seed_outside,
                "the seed does not lie inside the ply boundary's region on the mold");

PLYFIT_SENTENCE(text_seed_curve_off_mold,
                "the seed curve lies {b0} mm from the mold at ({t2}), more than the tolerance {b1} "
                "mm: a wrong curve, unit or frame?");

PLYFIT_SENTENCE(text_seed_not_on_curve,
                "the start lies {b0} mm from the seed curve, more than the tolerance {b1} mm: put "
                "the seed on the curve");

std::string text_dart_curve_points(const Values& x) {
  return "dart " + x.n(0) + " has " + x.n(1) +
         " usable points: a dart needs at least 2 finite points";
}

std::string text_dart_off_mold(const Values& x) {
  if (x.number(1) < 0) return "dart " + x.n(0) + " could not be projected onto the mold";
  return "dart " + x.n(0) + " lies " + x.brief(1) + " mm from the mold at (" + x.text(3) +
         "), more than the tolerance " + x.brief(2) + " mm: a wrong curve, unit or frame?";
}

}  // namespace plyfit::exporters::render
