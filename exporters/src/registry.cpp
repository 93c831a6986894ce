#include <plyfit/exporters/exporters.hpp>

#include <plyfit/exporters/atomic_file.hpp>

#include "plugins.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace plyfit::exporters {

const std::vector<Exporter>& registry() {
  // One registration line per format.
  static const std::vector<Exporter> list = {
      make_dxf_exporter(), make_step_exporter(), make_json_exporter(),
      make_svg_exporter(), make_vtk_exporter(),  make_glb_exporter(),
  };
  return list;
}

const Exporter* find_exporter(const std::string& key) {
  std::string k = key;
  std::transform(k.begin(), k.end(), k.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const auto& e : registry())
    if (e.key == k) return &e;
  return nullptr;
}

std::string supported_keys() {
  std::string s;
  for (const auto& e : registry()) s += (s.empty() ? "" : ",") + e.key;
  return s;
}

Exporter file_exporter(std::string key, std::string description, std::vector<OutputFile> files) {
  Exporter e{std::move(key), {}, std::move(description), {}};
  for (const OutputFile& f : files) e.files.push_back(f.name);
  e.write = [files = std::move(files)](const ExportContext& ctx, const std::string& outdir) {
    for (const OutputFile& f : files) {
      const std::string path = (std::filesystem::path(outdir) / f.name).string();
      auto content = f.content(ctx);
      if (!content) return Status(Error(content.error()).in(path));
      if (auto s = write_file_atomic(path, *content); !s) return s;
    }
    return ok_status();
  };
  return e;
}

Status write_outputs(const ExportContext& ctx, const std::string& outdir,
                     const std::vector<std::string>& keys) {
  std::error_code ec;
  std::filesystem::create_directories(outdir, ec);
  if (ec) return Error{ErrorCode::kOutputFolderNotCreated, outdir, {ec.message()}};
  for (const auto& k : keys) {
    const Exporter* e = find_exporter(k);
    if (!e) return Error{ErrorCode::kUnknownOutput, {}, {k, supported_keys()}};
    if (auto s = e->write(ctx, outdir); !s) return s;
  }
  return ok_status();
}

}  // namespace plyfit::exporters
