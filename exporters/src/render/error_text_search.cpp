// The text of the search's errors (kernel/src/search: optimize, face_start).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_start_needs_one_face(const Values&) {
  return "a start is suggested for one face, not a shell";
}

std::string text_start_face_no_boundary(const Values&) {
  return "the face has no boundary";
}

std::string text_start_face_no_inside_point(const Values&) {
  return "no point of the face found inside its trims";
}

std::string text_start_face_no_tangent(const Values&) {
  return "the face has no tangent plane at its middle";
}

std::string text_search_needs_one_face(const Values&) {
  return "the search of initial conditions drapes one face, not a shell";
}

std::string text_search_path_normal_at_seed(const Values&) {
  return "the scene's base-path direction is normal to the face at the seed";
}

}  // namespace plyfit::exporters::render
