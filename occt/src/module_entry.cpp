// The importers' entry point of the OpenCASCADE module: the readers by importer key.

#include <plyfit/occt/module.hpp>

#include <plyfit/occt/importer_api.hpp>
#include "readers.hpp"

namespace plyfit::importers {

namespace {

using ReadFileFunction = Result<occt::ReadOutput> (*)(const std::string& path,
                                                      occt::Deadline& deadline);

struct Reader {
  const char* key;
  ReadFileFunction read;
};

// One line per format (its registry entry, with the extensions, is in registry.cpp).
constexpr Reader kReaders[] = {
    {"step", &read_step},
    {"iges", &read_iges},
};

Result<const Reader*> reader(const std::string& key, const std::string& path) {
  for (const Reader& r : kReaders)
    if (key == r.key) return &r;
  return Error{ErrorCode::kOcctNoReader, path, {key}};
}

Result<std::unique_ptr<MoldFile>> open(const std::string& key, const std::string& path,
                                       const ImportOptions& options) {
  auto r = reader(key, path);
  if (!r) return r.error();
  return occt::open_with(path, (*r)->key, options, (*r)->read);
}

Result<std::vector<FileCurve>> curves(const std::string& key, const std::string& path,
                                      const ImportOptions& options) {
  auto r = reader(key, path);
  if (!r) return r.error();
  return occt::curves_with(path, (*r)->key, options, (*r)->read);
}

const OcctImporterApi kApi{plyfit::occt::kOcctModuleAbi, &open, &curves};

}  // namespace

}  // namespace plyfit::importers

PLYFIT_OCCT_EXPORT const plyfit::importers::OcctImporterApi* plyfit_occt_importers() {
  return &plyfit::importers::kApi;
}
