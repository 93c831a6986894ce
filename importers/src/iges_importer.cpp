// IGES: read by the OpenCASCADE module (occt/src/iges_reader.cpp).
#include "formats.hpp"

namespace plyfit::importers {

Importer iges_importer() {
  return occt_importer("iges", {"iges", "igs"},
                       "IGES (5.x: 128/114 surfaces, 144 trimmed surfaces, 186/514/510 solids) "
                       "via OpenCASCADE");
}

}  // namespace plyfit::importers
