#pragma once
// The mold writer's entry point in the OpenCASCADE module (importers/occt_module.hpp): filled in
// the module (occt_mold_writer.cpp), looked up by mold_writer.cpp under kMoldWriterEntry.
// Private to the exporters and the module.

#include <plyfit/exporters/mold_writer.hpp>

#include <string>

namespace plyfit::exporters {

/// Name of the module's function returning its OcctMoldWriterApi (extern "C").
constexpr const char* kMoldWriterEntry = "plyfit_occt_mold_writer";

/// The module's mold writer: the three functions of mold_writer.hpp.
struct OcctMoldWriterApi {
  int abi;  ///< kOcctModuleAbi of the module's build
  /// write_mold(const BuiltinFace&, ...).
  Status (*write_builtin)(const BuiltinFace& face, const std::string& path,
                          const MoldWriteOptions& options);
  /// write_mold(const FaceData&, ...).
  Status (*write_face)(const FaceData& face, const std::string& path,
                       const MoldWriteOptions& options);
  /// write_shell().
  Status (*write_shell)(const ShellData& shell, const std::string& path,
                        const MoldWriteOptions& options);
};

/// The signature of the entry point.
using OcctMoldWriterEntry = const OcctMoldWriterApi* (*)();

}  // namespace plyfit::exporters
