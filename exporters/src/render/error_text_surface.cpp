// The text of the kernel's geometry errors (kernel/src/geometry: NURBS surfaces and curves),
// surface errors (kernel/src/surface: faces and shells) and built-in molds' errors
// (kernel/src/molds).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

// NURBS: x.text(0) names the direction ("u", "v" or "curve").

std::string text_degree_range(const Values& x) {
  return "degree in " + x.text(0) + " is " + x.n(1) + ", must be 1.." + x.n(2);
}

std::string text_too_few_poles(const Values& x) {
  return "need at least degree + 1 = " + x.n(1) + " poles in " + x.text(0) + ", got " + x.n(2);
}

std::string text_knot_count(const Values& x) {
  return "knot count in " + x.text(0) + " is " + x.n(1) +
         ", must be poles + degree + 1 = " + x.n(2);
}

std::string text_knot_not_finite(const Values& x) {
  return "knot " + x.n(1) + " in " + x.text(0) + " is not finite";
}

std::string text_knots_decrease(const Values& x) {
  return "knots in " + x.text(0) + " decrease at index " + x.n(1);
}

std::string text_knot_multiplicity(const Values& x) {
  return "knot multiplicity in " + x.text(0) + " exceeds degree + 1 at index " + x.n(1);
}

std::string text_empty_domain(const Values& x) {
  return "empty parameter domain in " + x.text(0);
}

std::string text_pole_count(const Values& x) {
  return "pole count is " + x.n(0) + ", must be " + x.n(1) + " x " + x.n(2);
}

std::string text_weight_count(const Values& x) {
  return "weight count is " + x.n(0) + ", must be " + x.n(1);
}

std::string text_pole_not_finite(const Values& x) {
  return "pole " + x.n(0) + " is not finite";
}

std::string text_weight_not_positive(const Values& x) {
  return "weight " + x.n(0) + " is not a positive finite number";
}

std::string text_curve_weight_count(const Values& x) {
  return "curve weight count is " + x.n(0) + ", must be " + x.n(1);
}

std::string text_curve_pole_not_finite(const Values& x) {
  return "curve pole " + x.n(0) + " is not finite";
}

std::string text_curve_weight_not_positive(const Values& x) {
  return "curve weight " + x.n(0) + " is not a positive finite number";
}

std::string text_polyline_too_few_points(const Values&) {
  return "a polyline curve needs at least two points";
}

std::string text_interpolation_too_few_points(const Values&) {
  return "interpolation needs at least two points";
}

std::string text_interpolation_points_coincide(const Values& x) {
  return "interpolation points " + x.n(0) + " and " + x.n(1) + " coincide";
}

std::string text_interpolation_singular(const Values&) {
  return "singular interpolation matrix";
}

// Faces and shells (a shell's face errors carry the face: "face N: " precedes them).

std::string text_trim_loop_edge_tags(const Values& x) {
  return "trim loop " + x.n(0) + " has " + x.n(1) + " edge tags for " + x.n(2) + " segments";
}

std::string text_trim_loop_too_few_points(const Values& x) {
  return "trim loop " + x.n(0) + " has fewer than 3 points";
}

std::string text_trim_loop_not_finite(const Values& x) {
  return "trim loop " + x.n(0) + " has a non-finite point";
}

std::string text_face_empty(const Values&) {
  return "no point of the face lies inside its trim loops";
}

std::string text_face_zero_size(const Values&) {
  return "the face has zero size";
}

std::string text_shell_no_faces(const Values&) {
  return "the shell has no faces";
}

std::string text_shell_too_many_faces(const Values& x) {
  return "the shell has " + x.n(0) + " faces; at most " + x.n(1) + " are supported";
}

std::string text_shell_face_indices(const Values&) {
  return "the shell's face indices do not match its faces";
}

std::string text_shell_edge_count_negative(const Values&) {
  return "the shell's edge count is negative";
}

std::string text_shared_edge_range(const Values& x) {
  return "shared edge " + x.n(0) + " out of range";
}

std::string text_shared_edge_uses(const Values& x) {
  return "shared edge " + x.n(0) + " is used by " + x.n(1) +
         " faces (a shared edge joins two faces)";
}

std::string text_shared_edge_not_evaluated(const Values& x) {
  return "shared edge " + x.n(0) + ": cannot evaluate it";
}

std::string text_shell_not_sewn(const Values& x) {
  return "the two sides of a shared edge are " + x.fixed(0) + " apart (more than " + x.brief(1) +
         "% of the shell's size): the faces were not sewn";
}

std::string text_shell_orientation(const Values& x) {
  return "the faces cannot be oriented consistently (face " + x.n(0) + " and its neighbours)";
}

// Built-in molds and shells: x.text(0) is the parameter and x.text(1) the built-in where an
// error concerns one parameter.

std::string text_unknown_builtin(const Values& x) {
  return "unknown built-in " + x.text(0) + " '" + x.text(1) + "' (known: " + x.text(2) + ")";
}

std::string text_builtin_no_parameter(const Values& x) {
  return "built-in " + x.text(0) + " '" + x.text(1) + "' has no parameter '" + x.text(2) +
         "' (its parameters: " + x.text(3) + ")";
}

std::string text_builtin_parameter_not_finite(const Values& x) {
  return "parameter '" + x.text(0) + "' of '" + x.text(1) + "' is not a finite number";
}

std::string text_builtin_parameter_not_positive(const Values& x) {
  return "parameter '" + x.text(0) + "' of '" + x.text(1) + "' must be positive";
}

std::string text_builtin_angle_range(const Values& x) {
  return "parameter '" + x.text(0) + "' of '" + x.text(1) + "' must be in (0, 360]";
}

std::string text_builtin_parameter_range(const Values& x) {
  return "parameter '" + x.text(0) + "' of '" + x.text(1) + "' must be in [" + x.brief(2) + ", " +
         x.brief(3) + "]";
}

std::string text_builtin_integer_range(const Values& x) {
  return "parameter '" + x.text(0) + "' of '" + x.text(1) + "' must be an integer from " + x.n(2) +
         " to " + x.n(3);
}

std::string text_builtin_cylinder_window(const Values&) {
  return "the window of 'cylinder' needs 0 < window_angle < angle and 0 < window_height < H";
}

std::string text_builtin_cone_radii(const Values&) {
  return "radii r0, r1 of 'cone' must be >= 0 and not both 0";
}

std::string text_builtin_plate_hole(const Values&) {
  return "the hole of 'plate' (hole_r, hole_x, hole_y) must lie inside the plate";
}

std::string text_builtin_dish_hole(const Values&) {
  return "the hole radius hole_r of 'dish' must be in [0, R)";
}

std::string text_builtin_torus_tube(const Values&) {
  return "tube radius r of 'torus' must be smaller than R";
}

std::string text_builtin_torus_angles(const Values&) {
  return "tube angles of 'torus' need t0 < t1 <= t0 + 360";
}

std::string text_builtin_trim_curve(const Values&) {
  return "invalid trim curve";
}

std::string text_builtin_mold(const Values& x) {
  return "built-in mold '" + x.text(0) + "'";
}

std::string text_builtin_name_missing(const Values& x) {
  return "built-in mold name missing in 'builtin:" + x.text(0) + "'";
}

std::string text_builtin_parameter_syntax(const Values& x) {
  return "built-in mold parameter '" + x.text(0) + "' is not key=value";
}

std::string text_builtin_parameter_value(const Values& x) {
  return "built-in mold parameter '" + x.text(0) + "' has a malformed value '" + x.text(1) + "'";
}

}  // namespace plyfit::exporters::render
