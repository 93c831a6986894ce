// The text of the drape's input errors (kernel/src/drape: the problem and the ply).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

PLYFIT_SENTENCE(text_sweep_count_mismatch,
                "give as many 3D sweep directions as 2D ones ({n0} 2D, {n1} 3D)");

PLYFIT_SENTENCE(text_start_not_finite, "the 3D start point must be finite");

PLYFIT_SENTENCE(text_base_normal_zero, "the base-plane normal must be a non-zero vector");

PLYFIT_SENTENCE(text_lock_angle_range, "the lock angle must be in (0, 90] degrees");

PLYFIT_SENTENCE(text_start_not_projected, "cannot project the start point onto the face");

PLYFIT_SENTENCE(text_start_no_normal, "no surface normal at the start point");

PLYFIT_SENTENCE(text_base_normal_tangent,
                "the base plane does not cut the face near the start (it is tangent to the surface "
                "there); choose a base-plane normal along the surface");

PLYFIT_SENTENCE(text_sweep3d_zero, "3D sweep direction {n0} must be a non-zero vector");

PLYFIT_SENTENCE(text_sweep3d_along_path,
                "3D sweep direction {n0} is parallel to the base path or normal to the surface at "
                "the start: it lies {b1} deg from the plane of the two (at least {b2} deg needed); "
                "it must point to one side of the path");

PLYFIT_SENTENCE(
    text_sweeps3d_same_side,
    "the two 3D sweep directions must lie on the two sides of the base path, as the 2D ones do");

PLYFIT_SENTENCE(text_sweep_zero, "sweep direction {n0} must be a non-zero vector");

PLYFIT_SENTENCE(text_sweep_along_path,
                "sweep direction {n0} is parallel to the base path: it makes {b1} deg with it (at "
                "least {b2} deg needed); it must point into one side of the path");

PLYFIT_SENTENCE(text_spacing_not_positive, "{t0} spacing must be a positive number, got {f1}");

PLYFIT_SENTENCE(text_ply_size_not_positive, "ply size must be two positive numbers W,H");

PLYFIT_SENTENCE(text_start2d_not_finite, "start point must be finite");

PLYFIT_SENTENCE(text_base_dir_zero, "base path direction must be a non-zero vector");

PLYFIT_SENTENCE(text_no_sweep, "at least one sweep direction is needed");

PLYFIT_SENTENCE(text_too_many_sweeps, "at most two sweep directions (one per half-plane)");

PLYFIT_SENTENCE(text_sweeps_same_side,
                "both sweep directions point into the same half-plane of the base path");

PLYFIT_SENTENCE(text_start2d_off_ply, "the 2D start point lies outside the ply rectangle");

}  // namespace plyfit::exporters::render
