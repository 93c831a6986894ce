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

std::string text_unknown_command(const Values& x) {
  return "unknown command " + quoted(x, 0) + " (try plyfit --help)";
}

std::string text_unknown_option(const Values& x) {
  return "unknown option " + x.text(0);
}

std::string text_bad_command_line(const Values& x) {
  return x.text(0);
}

std::string text_option_needs_value(const Values& x) {
  return "needs a value (" + x.text(0) + ")";
}

std::string text_unexpected_argument(const Values& x) {
  return "unexpected argument " + quoted(x, 0) + note(x, 1);
}

std::string text_missing_argument(const Values& x) {
  return "missing " + x.text(0) + " (" + x.text(1) + ")";
}

std::string text_option_repeated(const Values&) {
  return "given more than once";
}

std::string text_options_exclusive(const Values& x) {
  return "give either " + x.text(0) + " or " + x.text(1) + ", not both";
}

std::string text_missing_option(const Values& x) {
  return x.count(1) ? "missing required key " + quoted(x, 0)
                    : "missing required option --" + x.text(0);
}

std::string text_empty_value(const Values&) {
  return "empty value, expected a number";
}

std::string text_not_a_number(const Values& x) {
  return quoted(x, 0) + " is not a number";
}

std::string text_not_finite(const Values& x) {
  return quoted(x, 0) + " is not a finite number";
}

std::string text_vector_size(const Values& x) {
  return quoted(x, 0) + " must be " + x.n(1) + " comma-separated numbers";
}

std::string text_not_an_integer(const Values& x) {
  if (x.v.size() < 3) return quoted(x, 0) + " must be an integer >= " + x.n(1);
  return quoted(x, 0) + " must be an integer from " + x.n(1) + " to " + x.n(2);
}

std::string text_not_a_bool(const Values& x) {
  return quoted(x, 0) + " must be true or false";
}

std::string text_out_of_range(const Values& x) {
  const bool lo_open = x.count(3) != 0, hi_open = x.count(4) != 0;
  const std::string unit = x.text(5) == "?" || x.text(5).empty() ? "" : " " + x.text(5);
  if (std::isinf(x.number(2)))
    return quoted(x, 0) + " must be " + (lo_open ? "> " : ">= ") + x.brief(1) + unit;
  return quoted(x, 0) + " must be in " + (lo_open ? "(" : "[") + x.brief(1) + ", " + x.brief(2) +
         (hi_open ? ")" : "]") + unit;
}

std::string text_zero_vector(const Values& x) {
  return quoted(x, 0) + " must be a non-zero direction";
}

std::string text_unknown_value(const Values& x) {
  return "unknown value " + quoted(x, 0) + " (known: " + x.text(1) + ")";
}

std::string text_empty_list(const Values& x) {
  return quoted(x, 0) + " lists nothing" + (x.v.size() > 1 ? " (a list of " + x.text(1) + ")" : "");
}

std::string text_listed_twice(const Values& x) {
  return quoted(x, 0) + " is listed twice";
}

// ---- scene files and the materials table ----

std::string text_scene_cannot_open(const Values&) {
  return "cannot open the scene file";
}

std::string text_ini_syntax(const Values& x) {
  return "expected [section] or key = value, got " + quoted(x, 0);
}

std::string text_unknown_key(const Values& x) {
  const std::string section = x.v.size() > 1 ? x.text(1) : std::string();
  return "unknown key " + quoted(x, 0) + (section.empty() ? "" : " in section [" + section + "]") +
         (x.v.size() > 2 ? " (known: " + x.text(2) + ")" : "");
}

std::string text_materials_cannot_open(const Values&) {
  return "cannot open the materials file";
}

std::string text_materials_cannot_read(const Values&) {
  return "cannot read the materials file";
}

std::string text_no_materials(const Values&) {
  return "no [material] section";
}

std::string text_key_outside_material(const Values& x) {
  return "key " + quoted(x, 0) + " before the first [material] section";
}

std::string text_material_name_invalid(const Values& x) {
  return "material name " + quoted(x, 0) + " must be letters, digits, '-' or '_'";
}

std::string text_material_repeated(const Values& x) {
  return "material " + quoted(x, 0) + " given twice";
}

std::string text_material_label_empty(const Values& x) {
  return "material " + quoted(x, 0) + ": label is empty";
}

std::string text_material_angle_not_a_number(const Values& x) {
  return "material " + quoted(x, 0) + ": " + x.text(1) + ": " + quoted(x, 2) + " is not a number" +
         (x.text(1) == "limit" ? " or none" : "");
}

std::string text_material_roll_width(const Values& x) {
  return "material " + quoted(x, 0) + ": roll-width: " + quoted(x, 1) +
         " is not a positive number of millimetres";
}

std::string text_material_angle_range(const Values& x) {
  return "material " + quoted(x, 0) + ": " + x.text(1) + ": " + x.text(2) +
         " is not in [0, 90] degrees";
}

std::string text_material_angle_missing(const Values& x) {
  return "material " + quoted(x, 0) + " needs a " + x.text(1) + " angle";
}

std::string text_warning_above_limit(const Values& x) {
  return "material " + quoted(x, 0) + ": the warning angle is above the limit angle";
}

std::string text_limit_not_positive(const Values& x) {
  return "material " + quoted(x, 0) + ": the limit angle must be positive";
}

std::string text_unknown_material(const Values& x) {
  return "no material " + quoted(x, 0) + " (known: " + x.text(1) + ")";
}

// ---- jobs and commands ----

std::string text_no_face_at_point(const Values& x) {
  return "no face of the mold could be converted to find the face under the point (" + x.text(0) +
         ")";
}

std::string text_connected_needs_point(const Values&) {
  return "connected faces start from the face under the seed or faces-at point: give one";
}

std::string text_option_without(const Values& x) {
  return x.text(0) + " has no effect without " + x.text(1);
}

std::string text_builtin_face_given(const Values&) {
  return "a built-in mold is draped whole (no --face or --faces list)";
}

std::string text_interrupted(const Values&) {
  return "interrupted: nothing written";
}

std::string text_unknown_mold_format(const Values& x) {
  return "unknown mold format " + quoted(x, 0) +
         " (use a .step, .stp, .iges or .igs file, or --format step|iges)";
}

std::string text_bad_shard(const Values& x) {
  return quoted(x, 0) + " must be K/N with 0 <= K < N (e.g. 0/4)";
}

std::string text_cannot_create_folder(const Values& x) {
  return "cannot create the folder: " + x.text(0);
}

std::string text_folder_holds_other_files(const Values&) {
  return "exists and holds other files: not replaced";
}

std::string text_cannot_move_outputs(const Values& x) {
  return "cannot move the outputs into place: " + x.text(0);
}

std::string text_cannot_start_drape(const Values& x) {
  return "cannot start plyfit drape: " + x.text(0);
}

std::string text_drape_crashed(const Values& x) {
  return "plyfit drape was killed by signal " + x.n(0) + note(x, 1);
}

std::string text_drape_no_outcome(const Values& x) {
  const std::string last = x.v.size() > 1 ? x.text(1) : std::string();
  return "plyfit drape exited with code " + x.n(0) + " and left no outcome" +
         (last.empty() ? "" : "; its last line: " + last);
}

std::string text_outcome_unreadable(const Values& x) {
  return "unreadable job outcome: " + x.text(0);
}

std::string text_different_molds(const Values& x) {
  return "scenes on different molds: " + x.text(0) + " drapes " + x.text(1) + ", but " + x.text(2) +
         " drapes " + x.text(3) + " (--force compares them anyway)";
}

std::string text_optimize_shell(const Values&) {
  return "the scene drapes several faces (--faces); plyfit optimize searches one face";
}

std::string text_no_feasible_drape(const Values& x) {
  return "no drape is feasible (the scene's: " + x.text(0) + ")";
}

std::string text_option_needs_vary(const Values& x) {
  return "has no effect: --vary has no " + x.text(0);
}

std::string text_curve_file_cannot_open(const Values&) {
  return "cannot open the curve file";
}

std::string text_curve_file_syntax(const Values& x) {
  return "line " + x.n(0) + ": '" + x.text(1) + "' is not a point X,Y,Z (three numbers)";
}

std::string text_curve_file_format(const Values& x) {
  return "unknown curve file type '" + x.text(0) +
         "': give a .csv of points, or a STEP or IGES file";
}

std::string text_curve_not_found(const Values& x) {
  return "no curve '" + x.text(0) + "' in the file (it holds " + x.n(1) +
         " curves: plyfit info FILE --curves lists them)";
}

std::string text_curve_file_unreadable(const Values&) {
  return "cannot read the curves of the file";
}

std::string text_curve_file_no_curves(const Values&) {
  return "the file holds no curve (no free curve, wire or face edge)";
}

std::string text_seed_curve_one_curve(const Values& x) {
  return "a seed curve is one curve, the file gives " + x.n(0) +
         " (pick one: FILE:NAME or FILE:INDEX)";
}

// ---- laminates ----

std::string text_laminate_section(const Values& x) {
  const std::string s = x.text(0);
  return s.empty() || s == "?"
             ? "a key outside the sections (a laminate file has [laminate] and [ply NAME])"
             : "unknown section [" + s + "] ([laminate] first, then [ply NAME] sections)";
}

std::string text_laminate_no_plies(const Values&) {
  return "the laminate has no [ply NAME] section";
}

std::string text_ply_name_invalid(const Values& x) {
  return "ply name " + quoted(x, 0) +
         " is not 1 to 64 letters, digits, '-', '_' or '.' (not first)";
}

std::string text_ply_repeated(const Values& x) {
  return "ply " + quoted(x, 0) + " is defined twice (first at line " + x.n(1) + ")";
}

std::string text_sequence_repeated(const Values& x) {
  return "sequence " + x.n(0) + " is taken by another ply";
}

std::string text_key_not_in_laminate(const Values& x) {
  return "key " + quoted(x, 0) +
         " is not taken here (roll-width in [laminate], sequence in [ply NAME]; a ply's name, "
         "angle and output folder are its section name, `angle` and -o)";
}

std::string text_ply_exception(const Values& x) {
  return "the ply stopped on an unexpected exception: " + x.text(0);
}

std::string text_piece_wider_than_roll(const Values& x) {
  return "the cut outline is " + x.brief(0) + " mm wide, wider than the roll (" + x.brief(1) +
         " mm): left out of cut.dxf";
}

}  // namespace plyfit::exporters::render
