// net.vtk: the draped net as legacy VTK polydata ("# vtk DataFile Version 3.0"), BINARY (the
// legacy format's big-endian IEEE doubles and 32-bit integers), for ParaView. Binary, because
// VTK's legacy ASCII reader cannot read NaN (it reads numbers with operator>>, which rejects
// "nan": VTK 9.1 stops at "Unsupported point attribute type: nan"). Points: every node with a 3D
// position (mapped nodes, and outside nodes whose solution lies on the surface extended past the
// face), in the drape's resolution order. Cells, in VTK's polydata order:
//   VERTICES  one per node beyond the face (status 1), so that they show as points
//   LINES     every link between two mapped nodes (DrapeResult::links())
//   POLYGONS  every mapped cell part (plyfit::for_each_mapped_cell: the quadrangles of four
//             mapped crossings, and the parts of the cells the base path splits), counter-
//             clockwise in ply coordinates: the draped surface, to colour by shear
//
// Point data (angles in degrees; NaN where undefined, which ParaView leaves out of ranges and
// draws in its NaN colour):
//   thread_angle_deg  gamma between weft and warp at mapped regular nodes; NaN at path-only
//                     nodes, outside nodes and nodes lacking a thread neighbour
//   shear_deg         |90 - gamma|; NaN where thread_angle_deg is
//   status            0 mapped, 1 beyond the face (a position on the surface extended past
//                     it); the other node states have no position and are not written
//   on_path           1 for nodes on the base path (auxiliary points and crossings), else 0
// Cell data:
//   cell_kind         0 weft link, 1 warp link, 2 base-path link, 3 mapped cell, 4 node
//                     beyond the face (vertex)
//   shear_deg         a cell's shear (the largest |90 - gamma| over its corners that have a
//                     thread angle); NaN for links, vertices and cells without one
//
// Every double is written exactly (NaN as the quiet NaN 0x7ff8000000000000): equal inputs give
// equal bytes.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>

#include "net_util.hpp"
#include "plugins.hpp"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>

namespace plyfit::exporters {

namespace {

constexpr std::uint32_t kNotWritten = std::numeric_limits<std::uint32_t>::max();
constexpr int kStatusMapped = 0, kStatusBeyondFace = 1;
constexpr int kCellKindMappedCell = 3, kCellKindBeyondFace = 4;

int link_code(LinkKind k) {
  switch (k) {
    case LinkKind::kWeft:
      return 0;
    case LinkKind::kWarp:
      return 1;
    case LinkKind::kBase:
      return 2;
  }
  return 2;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A value in degrees, NaN for a negative (undefined) angle.
double degrees_or_nan(double rad) {
  return rad < 0 ? kNaN : rad * detail::kRadToDeg;
}

// The legacy format's binary data: big-endian, each block followed by a newline.
class BinaryWriter {
 public:
  void line(const std::string& s) { out_ += s + "\n"; }
  void int32(std::int64_t v) {
    const auto u = static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
    for (int sh = 24; sh >= 0; sh -= 8) out_ += static_cast<char>((u >> sh) & 0xFF);
  }
  void float64(double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, sizeof u);
    for (int sh = 56; sh >= 0; sh -= 8) out_ += static_cast<char>((u >> sh) & 0xFF);
  }
  void end_block() { out_ += "\n"; }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

std::string build_vtk(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  std::vector<std::uint32_t> slot(r.nodes.size(), kNotWritten);
  std::vector<std::uint32_t> written, beyond;
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    const bool outside = n.status == NodeStatus::kOutside && n.has(DrapeNode::kExtended);
    if (n.mapped() || outside) {
      slot[k] = static_cast<std::uint32_t>(written.size());
      if (outside) beyond.push_back(slot[k]);
      written.push_back(k);
    }
  }
  const auto links = r.links();
  const auto cells = detail::mapped_cells(r);
  std::size_t poly_size = 0;
  for (const auto& c : cells) poly_size += 1 + c.nodes.size();
  auto n = [](std::size_t x) { return std::to_string(x); };

  BinaryWriter o;
  o.line("# vtk DataFile Version 3.0");
  o.line("plyfit draped net (mm, degrees)");
  o.line("BINARY");
  o.line("DATASET POLYDATA");
  o.line("POINTS " + n(written.size()) + " double");
  for (const std::uint32_t k : written)
    for (int a = 0; a < 3; ++a) o.float64(r.nodes[k].point[a]);
  o.end_block();
  o.line("VERTICES " + n(beyond.size()) + " " + n(2 * beyond.size()));
  for (const std::uint32_t s : beyond) {
    o.int32(1);
    o.int32(s);
  }
  o.end_block();
  o.line("LINES " + n(links.size()) + " " + n(3 * links.size()));
  for (const DrapeLink& l : links) {
    o.int32(2);
    o.int32(slot[l.a]);
    o.int32(slot[l.b]);
  }
  o.end_block();
  o.line("POLYGONS " + n(cells.size()) + " " + n(poly_size));
  for (const auto& c : cells) {
    o.int32(static_cast<std::int64_t>(c.nodes.size()));
    for (const std::uint32_t k : c.nodes) o.int32(slot[k]);
  }
  o.end_block();

  o.line("CELL_DATA " + n(beyond.size() + links.size() + cells.size()));
  o.line("SCALARS cell_kind int 1");
  o.line("LOOKUP_TABLE default");
  for (std::size_t k = 0; k < beyond.size(); ++k) o.int32(kCellKindBeyondFace);
  for (const DrapeLink& l : links) o.int32(link_code(l.kind));
  for (std::size_t k = 0; k < cells.size(); ++k) o.int32(kCellKindMappedCell);
  o.end_block();
  o.line("SCALARS shear_deg double 1");
  o.line("LOOKUP_TABLE default");
  for (std::size_t k = 0; k < beyond.size() + links.size(); ++k) o.float64(kNaN);
  for (const auto& c : cells) o.float64(degrees_or_nan(c.shear));
  o.end_block();

  o.line("POINT_DATA " + n(written.size()));
  o.line("SCALARS thread_angle_deg double 1");
  o.line("LOOKUP_TABLE default");
  for (const std::uint32_t k : written) {
    const DrapeNode& nd = r.nodes[k];
    o.float64(degrees_or_nan(nd.mapped() && nd.has(DrapeNode::kHasAngle) ? nd.thread_angle : -1.0));
  }
  o.end_block();
  o.line("SCALARS shear_deg double 1");
  o.line("LOOKUP_TABLE default");
  for (const std::uint32_t k : written) o.float64(degrees_or_nan(detail::node_shear(r.nodes[k])));
  o.end_block();
  o.line("SCALARS status int 1");
  o.line("LOOKUP_TABLE default");
  for (const std::uint32_t k : written)
    o.int32(r.nodes[k].mapped() ? kStatusMapped : kStatusBeyondFace);
  o.end_block();
  o.line("SCALARS on_path int 1");
  o.line("LOOKUP_TABLE default");
  for (const std::uint32_t k : written) o.int32(r.nodes[k].has(DrapeNode::kOnPath) ? 1 : 0);
  o.end_block();
  return std::move(o.out());
}

}  // namespace

Exporter make_vtk_exporter() {
  return {
      "vtk",
      {"net.vtk"},
      "net.vtk: draped net (legacy VTK polydata): links, mapped cells, thread angle, shear, status",
      [](const ExportContext& ctx, const std::string& outdir) {
        return write_file_atomic((std::filesystem::path(outdir) / "net.vtk").string(),
                                 build_vtk(ctx));
      }};
}

}  // namespace plyfit::exporters
