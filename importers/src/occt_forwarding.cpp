// Importers whose reader lives in the OpenCASCADE module (occt/), loaded on the first open.
#include "formats.hpp"

#include <plyfit/occt/importer_api.hpp>
#include <plyfit/occt/module.hpp>

namespace plyfit::importers {

namespace {

// The module's importers, loading the module on first use.
Result<const OcctImporterApi*> occt_importers() {
  auto entry = plyfit::occt::occt_module_symbol(kImportersEntry);
  if (!entry) return entry.error();
  const OcctImporterApi* api = reinterpret_cast<OcctImporterEntry>(*entry)();
  if (!api || api->abi != plyfit::occt::kOcctModuleAbi)
    return Error{ErrorCode::kOcctModuleOtherBuild,
                 {},
                 {std::string(plyfit::occt::kOcctModuleFile), std::int64_t{api ? api->abi : -1},
                  std::int64_t{plyfit::occt::kOcctModuleAbi}}};
  return api;
}

}  // namespace

Importer occt_importer(std::string key, std::vector<std::string> extensions,
                       std::string description) {
  Importer imp{key, std::move(extensions), std::move(description), {}, {}};
  imp.open = [key](const std::string& path,
                   const ImportOptions& options) -> Result<std::unique_ptr<MoldFile>> {
    auto api = occt_importers();
    if (!api) return Error(api.error()).in(path);
    return (*api)->open(key, path, options);
  };
  imp.curves = [key](const std::string& path,
                     const ImportOptions& options) -> Result<std::vector<FileCurve>> {
    auto api = occt_importers();
    if (!api) return Error(api.error()).in(path);
    return (*api)->curves(key, path, options);
  };
  return imp;
}

}  // namespace plyfit::importers
