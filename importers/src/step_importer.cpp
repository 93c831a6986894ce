// STEP: read by the OpenCASCADE module (occt/src/step_reader.cpp).
#include "formats.hpp"

namespace plyfit::importers {

Importer step_importer() {
  return occt_importer("step", {"step", "stp"},
                       "STEP (ISO 10303-21: AP203, AP214, AP242) via OpenCASCADE");
}

}  // namespace plyfit::importers
