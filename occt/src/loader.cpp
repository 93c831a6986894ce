// Finding and loading the OpenCASCADE module (occt_module.hpp). Part of plyfit_importers,
// without OpenCASCADE.

#include <plyfit/occt/module.hpp>

#include <dlfcn.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace plyfit::occt {

namespace {

std::atomic<bool> g_loaded{false};

struct Module {
  void* handle = nullptr;
  Error error;  // why it is not loaded
};

// The folder of the running executable ("" if unknown).
std::filesystem::path executable_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

Module load() {
  Module m;
  const std::filesystem::path dir = executable_dir();
  const std::filesystem::path candidates[] = {dir / kOcctModuleFile,
                                              dir.parent_path() / "lib" / kOcctModuleFile};
  for (const auto& path : candidates) {
    std::error_code ec;
    if (dir.empty() || !std::filesystem::is_regular_file(path, ec)) continue;
    m.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!m.handle) {
      const char* e = dlerror();
      m.error = Error{ErrorCode::kOcctModuleNotLoaded,
                      {},
                      {path.string(), std::string(e ? e : "unknown error")}};
    }
    return m;
  }
  m.error =
      Error{ErrorCode::kOcctModuleMissing,
            {},
            {std::string(kOcctModuleFile), dir.string(), (dir.parent_path() / "lib").string()}};
  return m;
}

const Module& module() {
  static const Module m = [] {
    Module loaded = load();
    g_loaded = loaded.handle != nullptr;
    return loaded;
  }();
  return m;
}

}  // namespace

Result<void*> occt_module_symbol(const char* name) {
  const Module& m = module();
  if (!m.handle) return m.error;
  dlerror();
  void* p = dlsym(m.handle, name);
  if (!p) {
    const char* e = dlerror();
    return Error{
        ErrorCode::kOcctModuleNoEntry, {}, {std::string(name), std::string(e ? e : "null")}};
  }
  return p;
}

bool occt_module_loaded() {
  return g_loaded;
}

}  // namespace plyfit::occt
