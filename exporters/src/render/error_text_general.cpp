// The text of the general error codes and warnings.
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_internal(const Values& x) {
  return "internal error: " + x.text(0);
}

std::string text_cancelled(const Values&) {
  return "cancelled";
}

std::string text_text(const Values& x) {
  return x.text(0);
}

std::string warning_note(const Values& x) {
  return x.text(0);
}

}  // namespace plyfit::exporters::render
