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

// "(Standard_DomainError: message)": OpenCASCADE's exception type and message at values[k].
std::string exception(const Values& x, std::size_t k) {
  std::string s(1, '(');
  s.append(x.text(k));
  const std::string msg = x.text(k + 1);
  if (!msg.empty()) s.append(": ").append(msg);
  s.push_back(')');
  return s;
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

// Values: OpenCASCADE's exception: its type and its message (may be empty).
std::string text_occt_failed(const Values& x) {
  return "OpenCASCADE failed " + exception(x, 0);
}

PLYFIT_SENTENCE(text_out_of_memory, "out of memory");

PLYFIT_SENTENCE(text_unexpected_exception, "unexpected exception ({t0})");

PLYFIT_SENTENCE(text_face_not_described, "could not be described");

PLYFIT_SENTENCE(text_face_not_measured, "could not be measured");

// Values: the format ("STEP", "IGES"), 1 when its parser found nothing to read.
std::string text_file_not_parsed(const Values& x) {
  return "not a readable " + x.text(0) + " file (the " + x.text(0) + " parser failed" +
         (x.count(1) == 1 ? ": nothing to read" : "") + ")";
}

PLYFIT_SENTENCE(text_iges_no_model, "not a readable IGES file (no model)");

PLYFIT_SENTENCE(text_occt_module_missing,
                "STEP and IGES files need plyfit's OpenCASCADE module {t0}, which is neither next "
                "to the plyfit executable in {t1} nor in {t2}");

PLYFIT_SENTENCE(text_occt_module_not_loaded,
                "plyfit's OpenCASCADE module {t0} could not be loaded ({t1})");

PLYFIT_SENTENCE(text_occt_module_no_entry,
                "plyfit's OpenCASCADE module lacks the entry point {t0} ({t1})");

PLYFIT_SENTENCE(text_occt_module_other_build,
                "plyfit's OpenCASCADE module {t0} is from another build of plyfit (interface "
                "{n1}, expected {n2})");

PLYFIT_SENTENCE(text_occt_no_reader, "plyfit's OpenCASCADE module has no reader {q0}");

PLYFIT_SENTENCE(text_curves_no_extent, "the file's curves have no extent");

PLYFIT_SENTENCE(text_curve_not_discretised,
                "curve {n0}: an edge does not discretise (OpenCASCADE's deflection sampler "
                "failed)");

PLYFIT_SENTENCE(text_edge_no_pcurve, "an edge has no curve on the face");

PLYFIT_SENTENCE(text_trim_point_budget,
                "trim polylines exceed the point budget ({n0} points for a face)");

PLYFIT_SENTENCE(text_face_no_trim_loop, "the face has no usable trim loop");

PLYFIT_SENTENCE(text_face_no_surface, "the face has no surface");

PLYFIT_SENTENCE(text_nurbs_conversion_failed, "conversion of the {t0} surface to NURBS failed");

PLYFIT_SENTENCE(text_nurbs_conversion_no_face,
                "conversion of the {t0} surface to NURBS gave no face");

PLYFIT_SENTENCE(text_nurbs_conversion_type, "conversion of the {t0} surface to NURBS gave a {t1}");

PLYFIT_SENTENCE(text_face_surface_invalid, "invalid NURBS surface");

PLYFIT_SENTENCE(text_sewing_time_limit, "sewing took longer than the time limit ({n0} s)");

PLYFIT_SENTENCE(text_sewing_no_shape, "the sewing gave no shape");

PLYFIT_SENTENCE(text_sewing_removed_face,
                "the sewing removed it (smaller than the sewing tolerance, {b0} mm?)");

PLYFIT_SENTENCE(text_sewing_zero_size, "the faces have zero size");

std::string text_writer_value_too_large(const Values& x) {
  return "a pole, weight or knot is " + limit(x, 0) + " or larger: not written";
}

PLYFIT_SENTENCE(text_writer_surface_invalid, "invalid surface");

PLYFIT_SENTENCE(text_writer_loop_count, "{n0} exact trim loops for {n1} trim polylines");

PLYFIT_SENTENCE(text_writer_loop_too_few_points, "trim loop {n0} has fewer than three points");

PLYFIT_SENTENCE(text_writer_trim_curve_invalid, "invalid trim curve in loop {n0}");

PLYFIT_SENTENCE(text_writer_loop_off_domain,
                "trim loop {n0} leaves the surface's parameter domain");

PLYFIT_SENTENCE(text_writer_edge_tags, "a loop has {n0} edge tags for {n1} segments");

PLYFIT_SENTENCE(text_writer_edge_not_built, "could not build an edge on a trim curve");

PLYFIT_SENTENCE(text_writer_loop_not_joined, "the trim curves of a loop do not join end to end");

PLYFIT_SENTENCE(text_writer_face_not_built, "could not build a face on the surface");

PLYFIT_SENTENCE(text_writer_face_not_inside_trim, "could not build a face inside the outer trim");

PLYFIT_SENTENCE(text_writer_holes_not_added, "could not add the holes to the face");

PLYFIT_SENTENCE(text_writer_trim_curve_3d, "could not build the 3D curve of a trim");

PLYFIT_SENTENCE(text_writer_not_transferred, "the {t0} writer could not transfer the shape");

// Values: the format ("STEP": a face, "IGES": a surface), the face's name.
std::string text_writer_no_face(const Values& x) {
  return "the " + x.text(0) + " writer made no " + (x.text(0) == "IGES" ? "surface" : "face") +
         " of '" + x.text(1) + "'";
}

PLYFIT_SENTENCE(text_writer_no_protocol, "no STEP protocol");

PLYFIT_SENTENCE(text_writer_failed, "the {t0} writer failed");

std::string text_writer_occt_failed(const Values& x) {
  return "OpenCASCADE failed writing the file " + exception(x, 0);
}

}  // namespace plyfit::exporters::render
