// The text of the kernel's geometry errors (kernel/src/geometry: NURBS surfaces and curves),
// surface errors (kernel/src/surface: faces and shells) and built-in molds' errors
// (kernel/src/molds).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

// NURBS: x.text(0) names the direction ("u", "v" or "curve").

PLYFIT_SENTENCE(text_degree_range, "degree in {t0} is {n1}, must be 1..{n2}");

PLYFIT_SENTENCE(text_too_few_poles, "need at least degree + 1 = {n1} poles in {t0}, got {n2}");

PLYFIT_SENTENCE(text_knot_count, "knot count in {t0} is {n1}, must be poles + degree + 1 = {n2}");

PLYFIT_SENTENCE(text_knot_not_finite, "knot {n1} in {t0} is not finite");

PLYFIT_SENTENCE(text_knots_decrease, "knots in {t0} decrease at index {n1}");

PLYFIT_SENTENCE(text_knot_multiplicity,
                "knot multiplicity in {t0} exceeds degree + 1 at index {n1}");

PLYFIT_SENTENCE(text_empty_domain, "empty parameter domain in {t0}");

PLYFIT_SENTENCE(text_pole_count, "pole count is {n0}, must be {n1} x {n2}");

PLYFIT_SENTENCE(text_weight_count, "weight count is {n0}, must be {n1}");

PLYFIT_SENTENCE(text_pole_not_finite, "pole {n0} is not finite");

PLYFIT_SENTENCE(text_weight_not_positive, "weight {n0} is not a positive finite number");

PLYFIT_SENTENCE(text_curve_weight_count, "curve weight count is {n0}, must be {n1}");

PLYFIT_SENTENCE(text_curve_pole_not_finite, "curve pole {n0} is not finite");

PLYFIT_SENTENCE(text_curve_weight_not_positive,
                "curve weight {n0} is not a positive finite number");

PLYFIT_SENTENCE(text_polyline_too_few_points, "a polyline curve needs at least two points");

PLYFIT_SENTENCE(text_interpolation_too_few_points, "interpolation needs at least two points");

PLYFIT_SENTENCE(text_interpolation_points_coincide, "interpolation points {n0} and {n1} coincide");

PLYFIT_SENTENCE(text_interpolation_singular, "singular interpolation matrix");

// Faces and shells (a shell's face errors carry the face: "face N: " precedes them).

PLYFIT_SENTENCE(text_trim_loop_edge_tags, "trim loop {n0} has {n1} edge tags for {n2} segments");

PLYFIT_SENTENCE(text_trim_loop_too_few_points, "trim loop {n0} has fewer than 3 points");

PLYFIT_SENTENCE(text_trim_loop_not_finite, "trim loop {n0} has a non-finite point");

PLYFIT_SENTENCE(text_face_empty, "no point of the face lies inside its trim loops");

PLYFIT_SENTENCE(text_face_zero_size, "the face has zero size");

PLYFIT_SENTENCE(text_shell_no_faces, "the shell has no faces");

PLYFIT_SENTENCE(text_shell_too_many_faces, "the shell has {n0} faces; at most {n1} are supported");

PLYFIT_SENTENCE(text_shell_face_indices, "the shell's face indices do not match its faces");

PLYFIT_SENTENCE(text_shell_edge_count_negative, "the shell's edge count is negative");

PLYFIT_SENTENCE(text_shared_edge_range, "shared edge {n0} out of range");

PLYFIT_SENTENCE(text_shared_edge_uses,
                "shared edge {n0} is used by {n1} faces (a shared edge joins two faces)");

PLYFIT_SENTENCE(text_shared_edge_not_evaluated, "shared edge {n0}: cannot evaluate it");

PLYFIT_SENTENCE(text_shell_not_sewn,
                "the two sides of a shared edge are {f0} apart (more than {b1}% of the shell's "
                "size): the faces were not sewn");

PLYFIT_SENTENCE(text_shell_orientation,
                "the faces cannot be oriented consistently (face {n0} and its neighbours)");

// Built-in molds and shells: x.text(0) is the parameter and x.text(1) the built-in where an
// error concerns one parameter.

PLYFIT_SENTENCE(text_unknown_builtin, "unknown built-in {t0} '{t1}' (known: {t2})");

PLYFIT_SENTENCE(text_builtin_no_parameter,
                "built-in {t0} '{t1}' has no parameter '{t2}' (its parameters: {t3})");

PLYFIT_SENTENCE(text_builtin_parameter_not_finite,
                "parameter '{t0}' of '{t1}' is not a finite number");

PLYFIT_SENTENCE(text_builtin_parameter_not_positive, "parameter '{t0}' of '{t1}' must be positive");

PLYFIT_SENTENCE(text_builtin_angle_range, "parameter '{t0}' of '{t1}' must be in (0, 360]");

PLYFIT_SENTENCE(text_builtin_parameter_range, "parameter '{t0}' of '{t1}' must be in [{b2}, {b3}]");

PLYFIT_SENTENCE(text_builtin_integer_range,
                "parameter '{t0}' of '{t1}' must be an integer from {n2} to {n3}");

PLYFIT_SENTENCE(
    text_builtin_cylinder_window,
    "the window of 'cylinder' needs 0 < window_angle < angle and 0 < window_height < H");

PLYFIT_SENTENCE(text_builtin_cone_radii, "radii r0, r1 of 'cone' must be >= 0 and not both 0");

PLYFIT_SENTENCE(text_builtin_plate_hole,
                "the hole of 'plate' (hole_r, hole_x, hole_y) must lie inside the plate");

PLYFIT_SENTENCE(text_builtin_dish_hole, "the hole radius hole_r of 'dish' must be in [0, R)");

PLYFIT_SENTENCE(text_builtin_torus_tube, "tube radius r of 'torus' must be smaller than R");

PLYFIT_SENTENCE(text_builtin_torus_angles, "tube angles of 'torus' need t0 < t1 <= t0 + 360");

PLYFIT_SENTENCE(text_builtin_trim_curve, "invalid trim curve");

PLYFIT_SENTENCE(text_builtin_mold, "built-in mold '{t0}'");

PLYFIT_SENTENCE(text_builtin_name_missing, "built-in mold name missing in 'builtin:{t0}'");

PLYFIT_SENTENCE(text_builtin_parameter_syntax, "built-in mold parameter '{t0}' is not key=value");

PLYFIT_SENTENCE(text_builtin_parameter_value,
                "built-in mold parameter '{t0}' has a malformed value '{t1}'");

}  // namespace plyfit::exporters::render
