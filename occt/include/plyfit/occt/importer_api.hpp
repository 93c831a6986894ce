#pragma once
// The importers' entry point of the OpenCASCADE module (occt_module.hpp): a table of plain
// function pointers, filled in the module (occt_module_entry.cpp) and looked up by the registry
// (registry.cpp) under kImportersEntry. Private to plyfit's importers and the module.

#include <plyfit/importers/importers.hpp>

#include <memory>
#include <string>
#include <vector>

namespace plyfit::importers {

/// Name of the module's function returning its OcctImporterApi (extern "C").
constexpr const char* kImportersEntry = "plyfit_occt_importers";

/// The module's importers.
struct OcctImporterApi {
  int abi;  ///< kOcctModuleAbi of the module's build
  /// Opens `path` with the reader of importer `key` ("step", "iges").
  Result<std::unique_ptr<MoldFile>> (*open)(const std::string& key, const std::string& path,
                                            const ImportOptions& options);
  /// Reads the curves of `path` with the reader of importer `key`.
  Result<std::vector<FileCurve>> (*curves)(const std::string& key, const std::string& path,
                                           const ImportOptions& options);
};

/// The signature of the entry point.
using OcctImporterEntry = const OcctImporterApi* (*)();

}  // namespace plyfit::importers

/// Marks the module's entry points as exported (the module hides everything else).
#define PLYFIT_OCCT_EXPORT extern "C" __attribute__((visibility("default")))
