// The text of the command line's errors (cli/: the option parser, scene files, the materials
// table, the commands). The input an error blames (an option, a scene key, a file) is named by
// describe() before this text; values are listed with each code in docs/errors.md.
#include "render/message_text.hpp"

#include <cmath>

namespace plyfit::exporters::render {

namespace {
std::string quoted(const Values& x, std::size_t k) {
  std::string q(1, '\'');
  q += x.text(k);
  q += '\'';
  return q;
}
// " (note)" when the value is not empty.
std::string note(const Values& x, std::size_t k) {
  const std::string s = k < x.v.size() ? x.text(k) : std::string();
  return s.empty() || s == "?" ? std::string() : " (" + s + ")";
}
}  // namespace

// ---- the command line ----

PLYFIT_SENTENCE(text_unknown_command, "unknown command {q0} (try plyfit --help)");

PLYFIT_SENTENCE(text_unknown_option, "unknown option {t0}");

PLYFIT_SENTENCE(text_bad_command_line, "{t0}");

PLYFIT_SENTENCE(text_option_needs_value, "needs a value ({t0})");

std::string text_unexpected_argument(const Values& x) {
  return "unexpected argument " + quoted(x, 0) + note(x, 1);
}

PLYFIT_SENTENCE(text_missing_argument, "missing {t0} ({t1})");

PLYFIT_SENTENCE(text_option_repeated, "given more than once");

PLYFIT_SENTENCE(text_options_exclusive, "give either {t0} or {t1}, not both");

std::string text_missing_option(const Values& x) {
  return x.count(1) ? "missing required key " + quoted(x, 0)
                    : "missing required option --" + x.text(0);
}

PLYFIT_SENTENCE(text_empty_value, "empty value, expected a number");

PLYFIT_SENTENCE(text_not_a_number, "{q0} is not a number");

PLYFIT_SENTENCE(text_not_finite, "{q0} is not a finite number");

PLYFIT_SENTENCE(text_vector_size, "{q0} must be {n1} comma-separated numbers");

std::string text_not_an_integer(const Values& x) {
  if (x.v.size() < 3) return quoted(x, 0) + " must be an integer >= " + x.n(1);
  return quoted(x, 0) + " must be an integer from " + x.n(1) + " to " + x.n(2);
}

PLYFIT_SENTENCE(text_not_a_bool, "{q0} must be true or false");

std::string text_out_of_range(const Values& x) {
  const bool lo_open = x.count(3) != 0, hi_open = x.count(4) != 0;
  const std::string given = x.text(5);
  const std::string unit = given == "?" || given.empty() ? std::string() : " " + given;
  if (std::isinf(x.number(2)))
    return quoted(x, 0) + " must be " + (lo_open ? "> " : ">= ") + x.brief(1) + unit;
  return quoted(x, 0) + " must be in " + (lo_open ? "(" : "[") + x.brief(1) + ", " + x.brief(2) +
         (hi_open ? ")" : "]") + unit;
}

PLYFIT_SENTENCE(text_zero_vector, "{q0} must be a non-zero direction");

PLYFIT_SENTENCE(text_unknown_value, "unknown value {q0} (known: {t1})");

std::string text_empty_list(const Values& x) {
  return quoted(x, 0) + " lists nothing" + (x.v.size() > 1 ? " (a list of " + x.text(1) + ")" : "");
}

PLYFIT_SENTENCE(text_listed_twice, "{q0} is listed twice");

// ---- scene files and the materials table ----

PLYFIT_SENTENCE(text_scene_cannot_open, "cannot open the scene file");

PLYFIT_SENTENCE(text_ini_syntax, "expected [section] or key = value, got {q0}");

std::string text_unknown_key(const Values& x) {
  const std::string section = x.v.size() > 1 ? x.text(1) : std::string();
  return "unknown key " + quoted(x, 0) + (section.empty() ? "" : " in section [" + section + "]") +
         (x.v.size() > 2 ? " (known: " + x.text(2) + ")" : "");
}

PLYFIT_SENTENCE(text_materials_cannot_open, "cannot open the materials file");

PLYFIT_SENTENCE(text_materials_cannot_read, "cannot read the materials file");

PLYFIT_SENTENCE(text_no_materials, "no [material] section");

PLYFIT_SENTENCE(text_key_outside_material, "key {q0} before the first [material] section");

PLYFIT_SENTENCE(text_material_name_invalid,
                "material name {q0} must be letters, digits, '-' or '_'");

PLYFIT_SENTENCE(text_material_repeated, "material {q0} given twice");

PLYFIT_SENTENCE(text_material_label_empty, "material {q0}: label is empty");

std::string text_material_angle_not_a_number(const Values& x) {
  return "material " + quoted(x, 0) + ": " + x.text(1) + ": " + quoted(x, 2) + " is not a number" +
         (x.text(1) == "limit" ? " or none" : "");
}

PLYFIT_SENTENCE(text_material_angle_range, "material {q0}: {t1}: {t2} is not in [0, 90] degrees");

std::string text_material_roll_width(const Values& x) {
  return "material " + quoted(x, 0) + ": roll-width: " + quoted(x, 1) +
         " is not a positive number of millimetres";
}

PLYFIT_SENTENCE(text_material_angle_missing, "material {q0} needs a {t1} angle");

PLYFIT_SENTENCE(text_warning_above_limit,
                "material {q0}: the warning angle is above the limit angle");

PLYFIT_SENTENCE(text_limit_not_positive, "material {q0}: the limit angle must be positive");

PLYFIT_SENTENCE(text_unknown_material, "no material {q0} (known: {t1})");

// ---- jobs and commands ----

PLYFIT_SENTENCE(text_no_face_at_point,
                "no face of the mold could be converted to find the face under the point ({t0})");

PLYFIT_SENTENCE(text_connected_needs_point,
                "connected faces start from the face under the seed or faces-at point: give one");

PLYFIT_SENTENCE(text_option_without, "{t0} has no effect without {t1}");

PLYFIT_SENTENCE(text_builtin_face_given,
                "a built-in mold is draped whole (no --face or --faces list)");

PLYFIT_SENTENCE(text_interrupted, "interrupted: nothing written");

PLYFIT_SENTENCE(
    text_unknown_mold_format,
    "unknown mold format {q0} (use a .step, .stp, .iges or .igs file, or --format step|iges)");

PLYFIT_SENTENCE(text_bad_shard, "{q0} must be K/N with 0 <= K < N (e.g. 0/4)");

PLYFIT_SENTENCE(text_cannot_create_folder, "cannot create the folder: {t0}");

PLYFIT_SENTENCE(text_folder_holds_other_files, "exists and holds other files: not replaced");

PLYFIT_SENTENCE(text_cannot_move_outputs, "cannot move the outputs into place: {t0}");

PLYFIT_SENTENCE(text_cannot_start_drape, "cannot start plyfit drape: {t0}");

std::string text_drape_crashed(const Values& x) {
  return "plyfit drape was killed by signal " + x.n(0) + note(x, 1);
}

std::string text_drape_no_outcome(const Values& x) {
  const std::string last = x.v.size() > 1 ? x.text(1) : std::string();
  return "plyfit drape exited with code " + x.n(0) + " and left no outcome" +
         (last.empty() ? "" : "; its last line: " + last);
}

PLYFIT_SENTENCE(text_outcome_unreadable, "unreadable job outcome: {t0}");

PLYFIT_SENTENCE(text_different_molds,
                "scenes on different molds: {t0} drapes {t1}, but {t2} drapes {t3} (--force "
                "compares them anyway)");

PLYFIT_SENTENCE(text_optimize_shell,
                "the scene drapes several faces (--faces); plyfit optimize searches one face");

PLYFIT_SENTENCE(text_no_feasible_drape, "no drape is feasible (the scene's: {t0})");

PLYFIT_SENTENCE(text_option_needs_vary, "has no effect: --vary has no {t0}");

PLYFIT_SENTENCE(text_curve_file_cannot_open, "cannot open the curve file");

PLYFIT_SENTENCE(text_curve_file_syntax, "line {n0}: '{t1}' is not a point X,Y,Z (three numbers)");

PLYFIT_SENTENCE(text_curve_file_format,
                "unknown curve file type '{t0}': give a .csv of points, or a STEP or IGES file");

PLYFIT_SENTENCE(
    text_curve_not_found,
    "no curve '{t0}' in the file (it holds {n1} curves: plyfit info FILE --curves lists them)");

PLYFIT_SENTENCE(text_curve_file_unreadable, "cannot read the curves of the file");

PLYFIT_SENTENCE(text_curve_file_no_curves,
                "the file holds no curve (no free curve, wire or face edge)");

PLYFIT_SENTENCE(
    text_seed_curve_one_curve,
    "a seed curve is one curve, the file gives {n0} (pick one: FILE:NAME or FILE:INDEX)");

// ---- laminates ----

std::string text_laminate_section(const Values& x) {
  const std::string s = x.text(0);
  return s.empty() || s == "?"
             ? "a key outside the sections (a laminate file has [laminate] and [ply NAME])"
             : "unknown section [" + s + "] ([laminate] first, then [ply NAME] sections)";
}

PLYFIT_SENTENCE(text_laminate_no_plies, "the laminate has no [ply NAME] section");

PLYFIT_SENTENCE(text_ply_name_invalid,
                "ply name {q0} is not 1 to 64 letters, digits, '-', '_' or '.' (not first)");

PLYFIT_SENTENCE(text_ply_repeated, "ply {q0} is defined twice (first at line {n1})");

PLYFIT_SENTENCE(text_sequence_repeated, "sequence {n0} is taken by another ply");

PLYFIT_SENTENCE(text_key_not_in_laminate,
                "key {q0} is not taken here (roll-width in [laminate], sequence in [ply NAME]; a "
                "ply's name, angle and output folder are its section name, `angle` and -o)");

PLYFIT_SENTENCE(text_ply_exception, "the ply stopped on an unexpected exception: {t0}");

PLYFIT_SENTENCE(
    text_piece_wider_than_roll,
    "the cut outline is {b0} mm wide, wider than the roll ({b1} mm): left out of cut.dxf");

}  // namespace plyfit::exporters::render
