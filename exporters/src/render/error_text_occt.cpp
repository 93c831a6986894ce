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

PLYFIT_SENTENCE(text_file_missing, "no such file");

PLYFIT_SENTENCE(text_file_not_regular, "not a regular file");

PLYFIT_SENTENCE(text_file_empty, "empty file");

// Values: the format expected ("STEP" or "IGES"), the one the file looks like (or "").
std::string text_file_wrong_format(const Values& x) {
  const std::string looks = x.text(1);
  std::string hint;
  if (looks == "STEP") hint = "; it looks like STEP (--format step)";
  if (looks == "IGES") hint = "; it looks like IGES (--format iges)";
  return "not a " + x.text(0) + " file" + hint;
}

std::string text_file_truncated(const Values& x) {
  const bool step = x.text(0) == "STEP";
  return "truncated " + x.text(0) + " file (" +
         (step ? "no END-ISO-10303-21 trailer" : "no terminate section") + ")";
}

PLYFIT_SENTENCE(text_import_format_unknown, "unknown format '{t0}' (supported: {t1})");

PLYFIT_SENTENCE(text_file_extension_unknown,
                "unknown file extension '{t0}' (supported: {t1}; --format overrides)");

std::string text_face_index_range(const Values& x) {
  return "face " + x.n(0) + " out of range (the file has " + x.n(1) + " faces, 0.." +
         std::to_string(x.count(1) - 1) + ")";
}

PLYFIT_SENTENCE(text_read_time_limit, "reading took longer than the time limit ({n0} s)");

// Values: the reader's first warning's (warning_reader_messages()), or none.
std::string text_file_no_faces(const Values& x) {
  return "no faces (nothing in the file transfers to a surface" +
         (x.v.empty() ? "" : "; " + warning_reader_messages(x)) + ")";
}

PLYFIT_SENTENCE(text_face_listed_twice, "face {n0} is listed twice");

std::string text_sewing_tolerance_invalid(const Values& x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g mm", x.number(0));
  return std::string("invalid sewing tolerance ") + buf;
}

PLYFIT_SENTENCE(text_file_not_readable, "cannot be opened for reading");

PLYFIT_SENTENCE(text_file_number_not_finite, "the number {t0} is not finite");

std::string text_file_number_too_large(const Values& x) {
  return "the number " + x.text(0) + " is beyond " + limit(x, 1) +
         " in magnitude (no mold is that large)";
}

std::string text_step_word_for_number(const Values& x) {
  return x.text(0).insert(0, 1, '\'') + "' is no STEP value (a number was expected)";
}

PLYFIT_SENTENCE(text_step_nesting_too_deep,
                "parentheses nested more than {n0} deep (a STEP entity nests a few)");

PLYFIT_SENTENCE(text_step_reference_cycle, "refers to itself through a cycle of references ({t0})");

PLYFIT_SENTENCE(text_step_references_too_deep, "references chained more than {n0} deep below it");

PLYFIT_SENTENCE(text_face_geometry_not_finite, "{t0}: {t1} is not finite");

std::string text_face_geometry_too_large(const Values& x) {
  return x.text(0) + ": " + x.text(1) + " is " + x.brief(2) + x.text(3) + ", beyond " +
         limit(x, 4) + " (no mold is that large)";
}

PLYFIT_SENTENCE(text_face_weight_not_positive, "{t0}: {t1} is not a positive finite number");

PLYFIT_SENTENCE(text_face_tolerance_invalid, "{t0}: {t1} is not a finite length");

PLYFIT_SENTENCE(text_face_scale_invalid, "{t0}: {t1}'s scale is not a finite non-zero number");

PLYFIT_SENTENCE(text_face_area_not_measured, "area not measured ({t0}): an invalid face");

}  // namespace plyfit::exporters::render
