#pragma once
// The mold writer's entry point in the OpenCASCADE module (importers/occt_module.hpp): filled in
// the module (occt_mold_writer.cpp), looked up by write_mold() (mold_writer.cpp) under
// kMoldWriterEntry. Private to the exporters and the module.

#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>

#include <string>

namespace plyfit::exporters {

/// Name of the module's function returning its OcctMoldWriterApi (extern "C").
constexpr const char* kMoldWriterEntry = "plyfit_occt_mold_writer";

/// The module's mold writer.
struct OcctMoldWriterApi {
  int abi;  ///< kOcctModuleAbi of the module's build
  /// Writes `surface` (validated, every number within the written range) as a one-face mold
  /// of `format` ("step" or "iges") at `path`, reversed when `reversed`.
  Status (*write)(const NurbsSurface& surface, bool reversed, const std::string& format,
                  const std::string& path, const MoldWriteOptions& options);
};

/// The signature of the entry point.
using OcctMoldWriterEntry = const OcctMoldWriterApi* (*)();

}  // namespace plyfit::exporters
