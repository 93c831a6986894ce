// The text of the ply definition's errors (kernel/src/drape/ply_definition.cpp).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_seed_not_finite(const Values&) {
  return "the seed point must be finite";
}

std::string text_seed_off_mold(const Values& x) {
  if (x.number(0) < 0) return "no point of the mold could be found near the seed";
  return "the seed lies " + x.brief(0) + " from the mold, more than half the mold's size (" +
         x.brief(1) + "): a wrong unit, frame or mold?";
}

std::string text_rosette_zero(const Values&) {
  return "the rosette direction must be a finite non-zero vector";
}

std::string text_rosette_along_normal(const Values& x) {
  return "the rosette direction lies " + x.brief(0) +
         " deg from the surface normal at the seed: its projection onto the surface (the 0 deg "
         "direction) is undefined; give a direction along the surface";
}

std::string text_ply_angle_range(const Values&) {
  return "the ply angle must be in [-180, 180] degrees";
}

}  // namespace plyfit::exporters::render
