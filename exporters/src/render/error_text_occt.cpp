// The text of the OpenCASCADE module's error codes (occt/src): checks of a STEP or IGES file's
// text before it is read, of its faces' geometry as read, and of their areas. The file, the face
// and the entity (Error::input, face, where) are named by describe().
#include "render/message_text.hpp"

#include <cstdio>

namespace plyfit::exporters::render {

namespace {

// "1e+08" (a limit in a sentence).
std::string limit(const Values& x, std::size_t k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0e", x.number(k));
  return buf;
}

}  // namespace

std::string text_file_not_readable(const Values&) {
  return "cannot be opened for reading";
}

std::string text_file_number_not_finite(const Values& x) {
  return "the number " + x.text(0) + " is not finite";
}

std::string text_file_number_too_large(const Values& x) {
  return "the number " + x.text(0) + " is beyond " + limit(x, 1) +
         " in magnitude (no mold is that large)";
}

std::string text_step_word_for_number(const Values& x) {
  return x.text(0).insert(0, 1, '\'') + "' is no STEP value (a number was expected)";
}

std::string text_step_nesting_too_deep(const Values& x) {
  return "parentheses nested more than " + x.n(0) + " deep (a STEP entity nests a few)";
}

std::string text_step_reference_cycle(const Values& x) {
  return "refers to itself through a cycle of references (" + x.text(0) + ")";
}

std::string text_step_references_too_deep(const Values& x) {
  return "references chained more than " + x.n(0) + " deep below it";
}

std::string text_face_geometry_not_finite(const Values& x) {
  return x.text(0) + ": " + x.text(1) + " is not finite";
}

std::string text_face_geometry_too_large(const Values& x) {
  return x.text(0) + ": " + x.text(1) + " is " + x.brief(2) + x.text(3) + ", beyond " +
         limit(x, 4) + " (no mold is that large)";
}

std::string text_face_weight_not_positive(const Values& x) {
  return x.text(0) + ": " + x.text(1) + " is not a positive finite number";
}

std::string text_face_tolerance_invalid(const Values& x) {
  return x.text(0) + ": " + x.text(1) + " is not a finite length";
}

std::string text_face_scale_invalid(const Values& x) {
  return x.text(0) + ": " + x.text(1) + "'s scale is not a finite non-zero number";
}

std::string text_face_area_not_measured(const Values& x) {
  return "area not measured (" + x.text(0) + "): an invalid face";
}

}  // namespace plyfit::exporters::render
