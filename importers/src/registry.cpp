// The importer registry. The readers are in the OpenCASCADE module (occt_module.hpp), loaded
// by the first open(): listing the importers, finding one by extension or validating a --format
// does not load OpenCASCADE.

#include <plyfit/importers/importers.hpp>
#include <plyfit/importers/occt_module.hpp>

#include "occt_module_api.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <numeric>

namespace plyfit::importers {

namespace {
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The module's importers, loading the module on first use.
Result<const OcctImporterApi*> occt_importers() {
  auto entry = occt_module_symbol(kImportersEntry);
  if (!entry) return entry.error();
  const OcctImporterApi* api = reinterpret_cast<OcctImporterEntry>(*entry)();
  if (!api || api->abi != kOcctModuleAbi)
    return Error{std::string("plyfit's OpenCASCADE module ") + kOcctModuleFile +
                 " is from another build of plyfit (interface " +
                 std::to_string(api ? api->abi : -1) + ", expected " +
                 std::to_string(kOcctModuleAbi) + ")"};
  return api;
}

// An importer whose reader is in the OpenCASCADE module.
Importer occt_importer(std::string key, std::vector<std::string> extensions,
                       std::string description) {
  Importer imp{key, std::move(extensions), std::move(description), {}};
  imp.open = [key](const std::string& path,
                   const ImportOptions& options) -> Result<std::unique_ptr<MoldFile>> {
    auto api = occt_importers();
    if (!api) return Error{path + ": " + api.error().message};
    return (*api)->open(key, path, options);
  };
  return imp;
}
}  // namespace

const std::vector<Importer>& registry() {
  // One registration line per format (its reader: occt_module_entry.cpp).
  static const std::vector<Importer> list = {
      occt_importer("step", {"step", "stp"},
                    "STEP (ISO 10303-21: AP203, AP214, AP242) via OpenCASCADE"),
      occt_importer("iges", {"iges", "igs"},
                    "IGES (5.x: 128/114 surfaces, 144 trimmed surfaces, 186/514/510 solids) "
                    "via OpenCASCADE"),
  };
  return list;
}

const Importer* find_importer(const std::string& key_or_extension) {
  const std::string k = lower(key_or_extension);
  for (const auto& imp : registry()) {
    if (imp.key == k) return &imp;
    if (std::find(imp.extensions.begin(), imp.extensions.end(), k) != imp.extensions.end())
      return &imp;
  }
  return nullptr;
}

std::string supported_extensions() {
  std::string s;
  for (const auto& imp : registry())
    for (const auto& e : imp.extensions) s += (s.empty() ? "" : ", ") + e;
  return s;
}

Result<std::unique_ptr<MoldFile>> open_mold(const std::string& path, const ImportOptions& options) {
  const Importer* imp = nullptr;
  if (!options.format.empty()) {
    imp = find_importer(options.format);
    if (!imp)
      return Error{"unknown format '" + options.format + "' (supported: " + supported_extensions() +
                   ")"};
  } else {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    imp = find_importer(ext);
    if (!imp)
      return Error{path + ": unknown file extension '" + ext +
                   "' (supported: " + supported_extensions() + "; --format overrides)"};
  }
  return imp->open(path, options);
}

Result<Face> load_face(const std::string& path, int index, const ImportOptions& options) {
  auto file = open_mold(path, options);
  if (!file) return file.error();
  auto data = (*file)->convert_face(index);
  if (!data) return data.error();
  auto face = Face::create(std::move(data).value(), options.tolerances);
  if (!face) return Error{path + ": face " + std::to_string(index) + ": " + face.error().message};
  return face;
}

std::vector<int> MoldFile::all_faces() const {
  std::vector<int> all(static_cast<size_t>(face_count()));
  std::iota(all.begin(), all.end(), 0);
  return all;
}

Result<ShellData> load_shell(const std::string& path, const std::vector<int>& indices,
                             const ImportOptions& options, std::vector<std::string>* warnings) {
  auto file = open_mold(path, options);
  if (!file) return file.error();
  auto shell = (*file)->convert_shell(indices);
  if (warnings) *warnings = (*file)->summary().warnings;
  return shell;
}

}  // namespace plyfit::importers
