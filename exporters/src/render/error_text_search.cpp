// The text of the search's errors (kernel/src/search: optimize, face_start).
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

PLYFIT_SENTENCE(text_start_needs_one_face, "a start is suggested for one face, not a shell");

PLYFIT_SENTENCE(text_start_face_no_boundary, "the face has no boundary");

PLYFIT_SENTENCE(text_start_face_no_inside_point, "no point of the face found inside its trims");

PLYFIT_SENTENCE(text_start_face_no_tangent, "the face has no tangent plane at its middle");

PLYFIT_SENTENCE(text_search_needs_one_face,
                "the search of initial conditions drapes one face, not a shell");

PLYFIT_SENTENCE(text_search_path_normal_at_seed,
                "the scene's base-path direction is normal to the face at the seed");

}  // namespace plyfit::exporters::render
