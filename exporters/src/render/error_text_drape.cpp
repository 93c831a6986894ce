// The text of the drape's input errors (kernel/src/drape: the problem and the ply).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_sweep_count_mismatch(const Values& x) {
  return "give as many 3D sweep directions as 2D ones (" + x.n(0) + " 2D, " + x.n(1) + " 3D)";
}

std::string text_start_not_finite(const Values&) {
  return "the 3D start point must be finite";
}

std::string text_base_normal_zero(const Values&) {
  return "the base-plane normal must be a non-zero vector";
}

std::string text_lock_angle_range(const Values&) {
  return "the lock angle must be in (0, 90] degrees";
}

std::string text_start_not_projected(const Values&) {
  return "cannot project the start point onto the face";
}

std::string text_start_no_normal(const Values&) {
  return "no surface normal at the start point";
}

std::string text_base_normal_tangent(const Values&) {
  return "the base plane does not cut the face near the start (it is tangent to the surface "
         "there); choose a base-plane normal along the surface";
}

std::string text_sweep3d_zero(const Values& x) {
  return "3D sweep direction " + x.n(0) + " must be a non-zero vector";
}

std::string text_sweep3d_along_path(const Values& x) {
  return "3D sweep direction " + x.n(0) +
         " is parallel to the base path or normal to the surface at the start: it lies " +
         x.brief(1) + " deg from the plane of the two (at least " + x.brief(2) +
         " deg needed); it must point to one side of the path";
}

std::string text_sweeps3d_same_side(const Values&) {
  return "the two 3D sweep directions must lie on the two sides of the base path, as the 2D "
         "ones do";
}

std::string text_sweep_zero(const Values& x) {
  return "sweep direction " + x.n(0) + " must be a non-zero vector";
}

std::string text_sweep_along_path(const Values& x) {
  return "sweep direction " + x.n(0) + " is parallel to the base path: it makes " + x.brief(1) +
         " deg with it (at least " + x.brief(2) +
         " deg needed); it must point into one side of "
         "the path";
}

std::string text_spacing_not_positive(const Values& x) {
  return x.text(0) + " spacing must be a positive number, got " + x.fixed(1);
}

std::string text_ply_size_not_positive(const Values&) {
  return "ply size must be two positive numbers W,H";
}

std::string text_start2d_not_finite(const Values&) {
  return "start point must be finite";
}

std::string text_base_dir_zero(const Values&) {
  return "base path direction must be a non-zero vector";
}

std::string text_no_sweep(const Values&) {
  return "at least one sweep direction is needed";
}

std::string text_too_many_sweeps(const Values&) {
  return "at most two sweep directions (one per half-plane)";
}

std::string text_sweeps_same_side(const Values&) {
  return "both sweep directions point into the same half-plane of the base path";
}

std::string text_start2d_off_ply(const Values&) {
  return "the 2D start point lies outside the ply rectangle";
}

}  // namespace plyfit::exporters::render
