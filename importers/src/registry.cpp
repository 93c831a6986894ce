// The importer registry. The readers are in the OpenCASCADE module (occt/), loaded
// by the first open(): listing the importers, finding one by extension or validating a --format
// does not load OpenCASCADE.

#include <plyfit/importers/importers.hpp>

#include "formats.hpp"

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

}  // namespace

const std::vector<Importer>& registry() {
  // One registration line per format (each format's file: *_importer.cpp).
  static const std::vector<Importer> list = {step_importer(), iges_importer()};
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

namespace {
// The importer of options.format, else of the file's extension.
Result<const Importer*> importer_for(const std::string& path, const ImportOptions& options) {
  const Importer* imp = nullptr;
  if (!options.format.empty()) {
    imp = find_importer(options.format);
    if (!imp)
      return Error{ErrorCode::kImportFormatUnknown, {}, {options.format, supported_extensions()}};
  } else {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    imp = find_importer(ext);
    if (!imp) return Error{ErrorCode::kFileExtensionUnknown, path, {ext, supported_extensions()}};
  }
  return imp;
}
}  // namespace

Result<std::unique_ptr<MoldFile>> open_mold(const std::string& path, const ImportOptions& options) {
  auto imp = importer_for(path, options);
  if (!imp) return imp.error();
  return (*imp)->open(path, options);
}

Result<std::vector<FileCurve>> read_curves(const std::string& path, const ImportOptions& options) {
  auto imp = importer_for(path, options);
  if (!imp) return imp.error();
  return (*imp)->curves(path, options);
}

Result<MoldSurface> load_face(const std::string& path, int index, const ImportOptions& options) {
  auto file = open_mold(path, options);
  if (!file) return file.error();
  auto data = (*file)->convert_face(index);
  if (!data) return data.error();
  auto face = MoldSurface::from_face(std::move(data).value(), options.tolerances);
  if (!face) return Error(face.error()).at_face(index).in(path);
  return face;
}

std::vector<int> MoldFile::all_faces() const {
  std::vector<int> all(static_cast<size_t>(face_count()));
  std::iota(all.begin(), all.end(), 0);
  return all;
}

Result<ShellData> load_shell(const std::string& path, const std::vector<int>& indices,
                             const ImportOptions& options, std::vector<Warning>* warnings) {
  auto file = open_mold(path, options);
  if (!file) return file.error();
  auto shell = (*file)->convert_shell(indices);
  if (warnings) *warnings = (*file)->summary().warnings;
  return shell;
}

}  // namespace plyfit::importers
