#include <plyfit/exporters/exporters.hpp>

#include "plugins.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace plyfit::exporters {

const std::vector<Exporter>& registry() {
  // One registration line per format.
  static const std::vector<Exporter> list = {
      make_dxf_exporter(), make_step_exporter(), make_json_exporter(),
      make_svg_exporter(), make_vtk_exporter(),
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

Status write_outputs(const ExportContext& ctx, const std::string& outdir,
                     const std::vector<std::string>& keys) {
  std::error_code ec;
  std::filesystem::create_directories(outdir, ec);
  if (ec) return Error{outdir + ": cannot create the output folder: " + ec.message()};
  for (const auto& k : keys) {
    const Exporter* e = find_exporter(k);
    if (!e) return Error{"unknown output '" + k + "' (known: " + supported_keys() + ")"};
    if (auto s = e->write(ctx, outdir); !s) return s;
  }
  return ok_status();
}

}  // namespace plyfit::exporters
