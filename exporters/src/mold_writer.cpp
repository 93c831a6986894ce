// Mold files written by plyfit (mold_writer.hpp): the format and the data are checked here,
// without OpenCASCADE; the writing itself is in the OpenCASCADE module (occt_mold_writer.cpp),
// loaded by the first write.

#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/importers/occt_module.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>

#include "mold_writer_api.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

namespace plyfit::exporters {

namespace {
/// Magnitudes outside [kSmallestWritten, kLargestWritten] would need a three-digit exponent in
/// the writers' format (17 significant digits, %.16E): smaller ones are written as 0, larger
/// ones are refused.
constexpr double kSmallestWritten = 1e-99;
constexpr double kLargestWritten = 1e99;

// The module's mold writer, loading the module on first use.
Result<const OcctMoldWriterApi*> occt_mold_writer() {
  auto entry = importers::occt_module_symbol(kMoldWriterEntry);
  if (!entry) return entry.error();
  const OcctMoldWriterApi* api = reinterpret_cast<OcctMoldWriterEntry>(*entry)();
  if (!api || api->abi != importers::kOcctModuleAbi)
    return Error{std::string("plyfit's OpenCASCADE module ") + importers::kOcctModuleFile +
                 " is from another build of plyfit"};
  return api;
}
}  // namespace

std::vector<std::string> mold_formats() {
  return {"step", "iges"};
}

Status write_mold(const FaceData& face, const std::string& path, const MoldWriteOptions& options) {
  std::string format = options.format;
  if (format.empty()) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == "step" || ext == "stp") format = "step";
    if (ext == "iges" || ext == "igs") format = "iges";
    if (format.empty())
      return Error{path + ": unknown mold format '" + ext +
                   "' (supported extensions: step, stp, iges, igs)"};
  }
  if (format != "step" && format != "iges")
    return Error{path + ": unknown mold format '" + format + "' (supported: step, iges)"};
  if (!face.loops.empty())
    return Error{path + ": the mold writer writes untrimmed faces only (this face has " +
                 std::to_string(face.loops.size()) + " trim loops)"};
  // Validate with the kernel's own rules first: OpenCASCADE throws on bad data.
  NurbsSurfaceData data = face.surface;
  auto fits = [](double& x) {
    if (std::abs(x) < kSmallestWritten) x = 0.0;
    return std::abs(x) < kLargestWritten;
  };
  bool all_fit = true;
  for (auto& p : data.poles)
    for (int k = 0; k < 3; ++k) all_fit = fits(p[k]) && all_fit;
  for (auto* v : {&data.knots_u, &data.knots_v, &data.weights})
    for (double& x : *v) all_fit = fits(x) && all_fit;
  if (!all_fit) return Error{path + ": a pole, weight or knot is 1e99 or larger: not written"};
  auto surface = NurbsSurface::create(data);
  if (!surface) return Error{path + ": invalid surface: " + surface.error().message};

  auto api = occt_mold_writer();
  if (!api) return Error{path + ": " + api.error().message};
  return (*api)->write(*surface, face.reversed, format, path, options);
}

}  // namespace plyfit::exporters
