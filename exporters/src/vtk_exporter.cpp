// net.vtk: the draped net as legacy VTK polydata ("# vtk DataFile Version 3.0"), BINARY (the
// legacy format's big-endian IEEE doubles and 32-bit integers), for ParaView. Binary, because
// VTK's legacy ASCII reader cannot read NaN (docs/decisions/net-vtk-binary.md). Points: every node
// with a 3D position (mapped nodes, and outside nodes whose solution lies on the surface extended
// past the face), in the drape's resolution order. Cells, in VTK's polydata order:
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

#include <plyfit/exporters/exporters.hpp>

#include "net_util.hpp"
#include "plugins.hpp"

#include <cstdint>
#include <cstring>
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
  /// The head of a SCALARS array with the default lookup table.
  void scalars(const std::string& name, const std::string& type) {
    line("SCALARS " + name + " " + type + " 1");
    line("LOOKUP_TABLE default");
  }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

// The nodes written as points, in the drape's order: every node with a 3D position (mapped,
// or outside on the surface extended past the face), their slots, and the beyond-face ones.
struct Points {
  std::vector<std::uint32_t> slot;     ///< per node: its point, or kNotWritten
  std::vector<std::uint32_t> written;  ///< per point: its node
  std::vector<std::uint32_t> beyond;   ///< the points beyond the face
};
Points points_of(const DrapeResult& r) {
  Points p;
  p.slot.assign(r.nodes.size(), kNotWritten);
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k) {
    const DrapeNode& n = r.nodes[k];
    const bool outside = n.status == NodeStatus::kOutside && n.has(DrapeNode::kExtended);
    if (n.mapped() || outside) {
      p.slot[k] = static_cast<std::uint32_t>(p.written.size());
      if (outside) p.beyond.push_back(p.slot[k]);
      p.written.push_back(k);
    }
  }
  return p;
}

std::string count(std::size_t x) {
  return std::to_string(x);
}

// POINTS, then the cells: VERTICES (beyond the face), LINES (links), POLYGONS (mapped cells).
void write_geometry(BinaryWriter& o, const DrapeResult& r, const Points& p,
                    const std::vector<DrapeLink>& links,
                    const std::vector<detail::NetCell>& cells) {
  o.line("POINTS " + count(p.written.size()) + " double");
  for (const std::uint32_t k : p.written)
    for (int a = 0; a < 3; ++a) o.float64(r.nodes[k].point[a]);
  o.end_block();
  o.line("VERTICES " + count(p.beyond.size()) + " " + count(2 * p.beyond.size()));
  for (const std::uint32_t s : p.beyond) {
    o.int32(1);
    o.int32(s);
  }
  o.end_block();
  o.line("LINES " + count(links.size()) + " " + count(3 * links.size()));
  for (const DrapeLink& l : links) {
    o.int32(2);
    o.int32(p.slot[l.a]);
    o.int32(p.slot[l.b]);
  }
  o.end_block();
  std::size_t poly_size = 0;
  for (const auto& c : cells) poly_size += 1 + c.nodes.size();
  o.line("POLYGONS " + count(cells.size()) + " " + count(poly_size));
  for (const auto& c : cells) {
    o.int32(static_cast<std::int64_t>(c.nodes.size()));
    for (const std::uint32_t k : c.nodes) o.int32(p.slot[k]);
  }
  o.end_block();
}

// CELL_DATA in the cells' order (vertices, links, polygons): cell_kind, shear_deg.
void write_cell_data(BinaryWriter& o, const Points& p, const std::vector<DrapeLink>& links,
                     const std::vector<detail::NetCell>& cells) {
  o.line("CELL_DATA " + count(p.beyond.size() + links.size() + cells.size()));
  o.scalars("cell_kind", "int");
  for (std::size_t k = 0; k < p.beyond.size(); ++k) o.int32(kCellKindBeyondFace);
  for (const DrapeLink& l : links) o.int32(link_code(l.kind));
  for (std::size_t k = 0; k < cells.size(); ++k) o.int32(kCellKindMappedCell);
  o.end_block();
  o.scalars("shear_deg", "double");
  for (std::size_t k = 0; k < p.beyond.size() + links.size(); ++k) o.float64(kNaN);
  for (const auto& c : cells) o.float64(degrees_or_nan(c.shear));
  o.end_block();
}

// POINT_DATA: thread_angle_deg, shear_deg, status, on_path.
void write_point_data(BinaryWriter& o, const DrapeResult& r, const Points& p) {
  o.line("POINT_DATA " + count(p.written.size()));
  o.scalars("thread_angle_deg", "double");
  for (const std::uint32_t k : p.written) {
    const DrapeNode& nd = r.nodes[k];
    o.float64(degrees_or_nan(nd.mapped() && nd.has(DrapeNode::kHasAngle) ? nd.thread_angle : -1.0));
  }
  o.end_block();
  o.scalars("shear_deg", "double");
  for (const std::uint32_t k : p.written) o.float64(degrees_or_nan(detail::node_shear(r.nodes[k])));
  o.end_block();
  o.scalars("status", "int");
  for (const std::uint32_t k : p.written)
    o.int32(r.nodes[k].mapped() ? kStatusMapped : kStatusBeyondFace);
  o.end_block();
  o.scalars("on_path", "int");
  for (const std::uint32_t k : p.written) o.int32(r.nodes[k].has(DrapeNode::kOnPath) ? 1 : 0);
  o.end_block();
}

std::string build_vtk(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const Points p = points_of(r);
  const auto links = r.links();
  const auto cells = detail::mapped_cells(r);
  BinaryWriter o;
  o.line("# vtk DataFile Version 3.0");
  o.line("plyfit draped net (mm, degrees)");
  o.line("BINARY");
  o.line("DATASET POLYDATA");
  write_geometry(o, r, p, links, cells);
  write_cell_data(o, p, links, cells);
  write_point_data(o, r, p);
  return std::move(o.out());
}

}  // namespace

Exporter make_vtk_exporter() {
  return file_exporter(
      "vtk",
      "net.vtk: draped net (legacy VTK polydata): links, mapped cells, thread angle, shear, status",
      {{"net.vtk", build_vtk}});
}

}  // namespace plyfit::exporters
