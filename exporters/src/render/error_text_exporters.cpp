// The text of the writers' errors (exporters/: atomic files, the registry, net.step's curves,
// the mold writer's forwarding). The file or folder they blame is the error's input.
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

std::string text_file_not_created(const Values&) {
  return "cannot create the file (folder missing or not writable?)";
}

std::string text_file_already_closed(const Values&) {
  return "file already closed";
}

std::string text_file_write_failed(const Values&) {
  return "write failed (disk full?)";
}

std::string text_file_not_renamed(const Values& x) {
  return "cannot rename the finished file into place: " + x.text(0);
}

std::string text_output_folder_not_created(const Values& x) {
  return "cannot create the output folder: " + x.text(0);
}

std::string text_unknown_output(const Values& x) {
  return "unknown output '" + x.text(0) + "' (known: " + x.text(1) + ")";
}

std::string text_curve_rational(const Values&) {
  return "rational curves are not written";
}

std::string text_curve_invalid(const Values&) {
  return "invalid curve";
}

std::string text_curve_set_not_built(const Values&) {
  return "cannot build a curve set";
}

std::string text_thread_curve_not_built(const Values& x) {
  return "cannot build a " + x.text(0) + " curve";
}

std::string text_boundary_loop_too_small(const Values& x) {
  return "cannot build the " + x.text(0) +
         " curve: the loop has fewer than 3 distinct points on the mold";
}

std::string text_mold_writer_other_build(const Values& x) {
  return "plyfit's OpenCASCADE module " + x.text(0) + " is from another build of plyfit";
}

}  // namespace plyfit::exporters::render
