// Mold files written by plyfit (mold_writer.hpp): forwarded to the OpenCASCADE module
// (occt_mold_writer.cpp), loaded by the first write; without OpenCASCADE here.

#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/occt/module.hpp>

#include <plyfit/occt/mold_writer_api.hpp>

namespace plyfit::exporters {

namespace {

// The module's mold writer, loading the module on first use; errors name `path`.
Result<const OcctMoldWriterApi*> occt_mold_writer(const std::string& path) {
  auto entry = plyfit::occt::occt_module_symbol(kMoldWriterEntry);
  if (!entry) return Error(entry.error()).in(path);
  const OcctMoldWriterApi* api = reinterpret_cast<OcctMoldWriterEntry>(*entry)();
  if (!api || api->abi != plyfit::occt::kOcctModuleAbi)
    return Error{ErrorCode::kMoldWriterOtherBuild, path, {plyfit::occt::kOcctModuleFile}};
  return api;
}

}  // namespace

std::vector<std::string> mold_formats() {
  return {"step", "iges"};
}

Status write_mold(const BuiltinFace& face, const std::string& path,
                  const MoldWriteOptions& options) {
  auto api = occt_mold_writer(path);
  if (!api) return api.error();
  return (*api)->write_builtin(face, path, options);
}

Status write_mold(const FaceData& face, const std::string& path, const MoldWriteOptions& options) {
  auto api = occt_mold_writer(path);
  if (!api) return api.error();
  return (*api)->write_face(face, path, options);
}

Status write_shell(const ShellData& shell, const std::string& path,
                   const MoldWriteOptions& options) {
  auto api = occt_mold_writer(path);
  if (!api) return api.error();
  return (*api)->write_shell(shell, path, options);
}

}  // namespace plyfit::exporters
