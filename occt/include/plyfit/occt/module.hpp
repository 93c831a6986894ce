#pragma once
/// \file The OpenCASCADE module. Everything of plyfit that uses OpenCASCADE (the STEP and IGES
/// readers behind the importer registry, the mold writer of `plyfit sample`) is built as one
/// shared module, plyfit-occt.so, that is loaded when first needed: a job that reads no mold file
/// (a built-in mold, a batch child of a small scene) never loads OpenCASCADE's libraries. The
/// module is looked for next to the running executable, then in ../lib relative to it (the
/// build tree puts executables in build/bin and the module in build/lib).
///
/// The module's objects (MoldFile) are used through their virtual methods; plyfit and the module
/// must come from the same build (kOcctModuleAbi is checked on loading).

#include <plyfit/kernel/result.hpp>

namespace plyfit::occt {

/// File name of the OpenCASCADE module.
constexpr const char* kOcctModuleFile = "plyfit-occt.so";

/// Version of the interface between plyfit and the module (the entry points' tables, MoldFile,
/// ImportOptions, MoldWriteOptions): raise it whenever one of them changes.
constexpr int kOcctModuleAbi = 7;  // 6: the module's errors are codes with data; 7: FaceData::built

/// The address of the entry point `name` of the module, which is loaded on the first call.
/// Errors (one line, without a file name): the module is missing, cannot be loaded (its dlerror,
/// e.g. a missing OpenCASCADE library) or lacks the entry point.
Result<void*> occt_module_symbol(const char* name);

/// True once the module has been loaded into the process.
bool occt_module_loaded();

}  // namespace plyfit::occt
