#include "report/drape_report.hpp"

#include <ostream>
#include <sstream>

namespace plyfit::cli {

std::string drape_summary(const JobOutcome& out, const std::string& outdir) {
  const auto& m = out.metrics;
  std::ostringstream os;
  os << "plyfit: " << out.status << ": " << m.nodes.mapped << " nodes mapped (" << m.nodes.auxiliary
     << " auxiliary base-path points), " << m.nodes.outside << " outside, " << m.nodes.off_ply
     << " off the ply, " << m.nodes.shear_limit << " at the shear limit, " << m.nodes.failed
     << " failed, " << m.nodes.overlap << " overlapping, " << m.nodes.conflict << " in conflict"
     << (m.nodes.path_end ? ", base path ended early" : "") << "; max shear " << out.shear_max_deg
     << " deg; " << static_cast<long>(out.total_ms) << " ms -> " << outdir << "\n";
  return os.str();
}

void scene_keys_markdown(std::ostream& os) {
  os << "| key (flag `--key`) | section | value | default | meaning |\n|---|---|---|---|---|\n";
  for (const auto& s : drape_options()) {
    std::string value = s.value.empty() ? "true/false" : s.value;
    for (std::size_t p = 0; (p = value.find('|', p)) != std::string::npos; p += 2)
      value.replace(p, 1, "\\|");
    os << "| `" << s.key << "`" << (s.short_name ? std::string(" (`-") + s.short_name + "`)" : "")
       << " | " << s.section << " | `" << value << "` | "
       << (s.def.empty() ? "" : "`" + s.def + "`") << " | " << s.help
       << (s.repeatable ? " (repeatable)" : "") << " |\n";
  }
}

}  // namespace plyfit::cli
