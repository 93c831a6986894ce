// The text of the general error codes and warnings.
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

PLYFIT_SENTENCE(text_internal, "internal error: {t0}");

PLYFIT_SENTENCE(text_cancelled, "cancelled");

PLYFIT_SENTENCE(warning_note, "{t0}");

}  // namespace plyfit::exporters::render
