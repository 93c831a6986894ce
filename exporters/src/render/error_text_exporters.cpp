// The text of the writers' errors (exporters/: atomic files, the registry, net.step's curves,
// the mold writer's forwarding). The file or folder they blame is the error's input.
#include "render/message_text.hpp"

namespace plyfit::exporters::render {

PLYFIT_SENTENCE(text_file_not_created, "cannot create the file (folder missing or not writable?)");

PLYFIT_SENTENCE(text_file_already_closed, "file already closed");

PLYFIT_SENTENCE(text_file_write_failed, "write failed (disk full?)");

PLYFIT_SENTENCE(text_file_not_renamed, "cannot rename the finished file into place: {t0}");

PLYFIT_SENTENCE(text_output_folder_not_created, "cannot create the output folder: {t0}");

PLYFIT_SENTENCE(text_unknown_output, "unknown output '{t0}' (known: {t1})");

PLYFIT_SENTENCE(text_curve_rational, "rational curves are not written");

PLYFIT_SENTENCE(text_curve_invalid, "invalid curve");

PLYFIT_SENTENCE(text_curve_set_not_built, "cannot build a curve set");

PLYFIT_SENTENCE(text_thread_curve_not_built, "cannot build a {t0} curve");

PLYFIT_SENTENCE(
    text_boundary_loop_too_small,
    "cannot build the {t0} curve: the loop has fewer than 3 distinct points on the mold");

PLYFIT_SENTENCE(text_mold_writer_other_build,
                "plyfit's OpenCASCADE module {t0} is from another build of plyfit");

}  // namespace plyfit::exporters::render
