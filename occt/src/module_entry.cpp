// The importers' entry point of the OpenCASCADE module: the readers by importer key.

#include <plyfit/occt/module.hpp>

#include <plyfit/occt/importer_api.hpp>
#include "readers.hpp"

namespace plyfit::importers {

namespace {

using OpenFunction = Result<std::unique_ptr<MoldFile>> (*)(const std::string& path,
                                                           const ImportOptions& options);

// One line per format (its registry entry, with the extensions, is in registry.cpp).
constexpr std::pair<const char*, OpenFunction> kReaders[] = {
    {"step", &open_step},
    {"iges", &open_iges},
};

Result<std::unique_ptr<MoldFile>> open(const std::string& key, const std::string& path,
                                       const ImportOptions& options) {
  for (const auto& [k, f] : kReaders)
    if (key == k) return f(path, options);
  return Error{path + ": plyfit's OpenCASCADE module has no reader '" + key + "'"};
}

const OcctImporterApi kApi{plyfit::occt::kOcctModuleAbi, &open};

}  // namespace

}  // namespace plyfit::importers

PLYFIT_OCCT_EXPORT const plyfit::importers::OcctImporterApi* plyfit_occt_importers() {
  return &plyfit::importers::kApi;
}
