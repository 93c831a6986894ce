// net.vtk: the draped net as legacy VTK polydata (ASCII, "# vtk DataFile Version 3.0"), for
// ParaView. Points: every node with a 3D position (mapped nodes, and outside nodes whose
// solution lies on the surface extended past the face), in the drape's resolution order.
// Lines: every link between two mapped nodes (DrapeResult::links()).
//
// Point data:
//   thread_angle  gamma between weft and warp (radians) at mapped regular nodes; -1 where
//                 undefined (path-only nodes, outside nodes, nodes lacking a thread neighbour)
//   shear         |pi/2 - gamma| (radians); -1 where thread_angle is undefined
//   status        0 mapped, 1 outside (position on the extended surface); the other node
//                 states (off_ply 2, shear_limit 3, failed 4, overlap 6) have no position and are
//                 not written
//   on_path       1 for nodes on the base path (auxiliary points and crossings), else 0
// Cell data:
//   link_kind     0 weft, 1 warp, 2 base path
//
// Numbers are written in their shortest exact decimal form: equal inputs give equal bytes.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>

#include "net_util.hpp"
#include "plugins.hpp"

#include <filesystem>
#include <limits>

namespace plyfit::exporters {

namespace {

constexpr double kUndefined = -1.0;
constexpr std::uint32_t kNotWritten = std::numeric_limits<std::uint32_t>::max();

int status_code(const DrapeNode& n) {
  switch (n.status) {
    case NodeStatus::kMapped:
      return 0;
    case NodeStatus::kOutside:
      return 1;
    case NodeStatus::kOffPly:
      return 2;
    case NodeStatus::kShearLimit:
      return 3;
    case NodeStatus::kFailed:
      return 4;
    case NodeStatus::kOverlap:
      return 6;
    case NodeStatus::kPending:
      break;
  }
  return 5;
}

int link_code(LinkKind k) {
  switch (k) {
    case LinkKind::kWeft:
      return 0;
    case LinkKind::kWarp:
      return 1;
    case LinkKind::kBase:
      return 2;
  }
  return 3;
}

std::string build_vtk(const ExportContext& ctx) {
  using detail::exact_text;
  const DrapeResult& r = ctx.result;
  std::vector<std::uint32_t> slot(r.nodes.size(), kNotWritten);
  std::vector<std::uint32_t> written;
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    if (n.mapped() || (n.status == NodeStatus::kOutside && n.has(DrapeNode::kExtended))) {
      slot[k] = static_cast<std::uint32_t>(written.size());
      written.push_back(k);
    }
  }
  const auto links = r.links();
  std::string o;
  o += "# vtk DataFile Version 3.0\n";
  o += "plyfit draped net (mm)\n";
  o += "ASCII\n";
  o += "DATASET POLYDATA\n";
  o += "POINTS " + std::to_string(written.size()) + " double\n";
  for (const std::uint32_t k : written) {
    const Vec3& p = r.nodes[k].point;
    o += exact_text(p.x()) + " " + exact_text(p.y()) + " " + exact_text(p.z()) + "\n";
  }
  o += "LINES " + std::to_string(links.size()) + " " + std::to_string(3 * links.size()) + "\n";
  for (const DrapeLink& l : links)
    o += "2 " + std::to_string(slot[l.a]) + " " + std::to_string(slot[l.b]) + "\n";
  o += "CELL_DATA " + std::to_string(links.size()) + "\n";
  o += "SCALARS link_kind int 1\nLOOKUP_TABLE default\n";
  for (const DrapeLink& l : links) o += std::to_string(link_code(l.kind)) + "\n";
  o += "POINT_DATA " + std::to_string(written.size()) + "\n";
  o += "SCALARS thread_angle double 1\nLOOKUP_TABLE default\n";
  for (const std::uint32_t k : written) {
    const DrapeNode& n = r.nodes[k];
    o += exact_text(n.mapped() && n.has(DrapeNode::kHasAngle) ? n.thread_angle : kUndefined) + "\n";
  }
  o += "SCALARS shear double 1\nLOOKUP_TABLE default\n";
  for (const std::uint32_t k : written) {
    const double s = detail::node_shear(r.nodes[k]);
    o += exact_text(s < 0 ? kUndefined : s) + "\n";
  }
  o += "SCALARS status int 1\nLOOKUP_TABLE default\n";
  for (const std::uint32_t k : written) o += std::to_string(status_code(r.nodes[k])) + "\n";
  o += "SCALARS on_path int 1\nLOOKUP_TABLE default\n";
  for (const std::uint32_t k : written)
    o += std::string(r.nodes[k].has(DrapeNode::kOnPath) ? "1" : "0") + "\n";
  return o;
}

}  // namespace

Exporter make_vtk_exporter() {
  return {"vtk",
          {"net.vtk"},
          "net.vtk: draped net (legacy VTK polydata) with thread angle, shear and status",
          [](const ExportContext& ctx, const std::string& outdir) {
            return write_file_atomic((std::filesystem::path(outdir) / "net.vtk").string(),
                                     build_vtk(ctx));
          }};
}

}  // namespace plyfit::exporters
