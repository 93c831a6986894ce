// net.glb: the draped ply as glTF 2.0 binary (GLB) for any glTF viewer (Blender, the three.js
// editor, Windows 3D Viewer). One mesh, two primitives sharing one vertex per mapped node (in the
// drape's order):
//   TRIANGLES  every mapped cell part (plyfit::mapped_cells) fanned from its first corner, each
//              triangle wound counter-clockwise seen from the mold's outward normal; NORMAL the
//              mold's unit outward normal at the node; COLOR_0 the shear in the pictures' colour
//              scale (render::shear_scale), in linear light as glTF defines vertex colours
//   LINES      every link between two mapped nodes (the threads and the base path), a material
//              of its own (the pictures' thread colour)
// Positions are float32 in metres (glTF's unit; the drape is in mm) in the mold's frame; the one
// node turns the mold's Z up into glTF's Y up. A node without a thread angle takes the largest
// shear of the cells it is a corner of. The JSON is written by nlohmann-json (sorted keys) and
// the numbers are fixed by the inputs: equal inputs give equal bytes.

#include <plyfit/exporters/exporters.hpp>

#include "net_util.hpp"
#include "plugins.hpp"
#include "render/colour_scale.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace plyfit::exporters {

namespace {

using nlohmann::json;

constexpr double kMetresPerMm = 1e-3;
constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();
// GLB container (glTF 2.0 spec, "Binary glTF Layout").
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kGlbVersion = 2;
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kModeLines = 1, kModeTriangles = 4;
// The threads' colour (drape.svg's threads, #262626).
constexpr double kThreadGrey = 0x26 / 255.0;

// The mesh as glTF wants it: float32 attributes, uint32 indices.
struct Mesh {
  std::vector<std::uint32_t> slot;  ///< per node: its vertex, or kNoVertex
  std::vector<std::uint32_t> node;  ///< per vertex: its node
  std::vector<Vec3> normals;        ///< per vertex, unit
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> lines;  ///< vertex pairs
};

// One vertex per mapped node, in the drape's order.
void add_vertices(Mesh& m, const DrapeResult& r) {
  m.slot.assign(r.nodes.size(), kNoVertex);
  for (std::uint32_t k = 0; k < r.nodes.size(); ++k)
    if (r.nodes[k].mapped()) {
      m.slot[k] = static_cast<std::uint32_t>(m.node.size());
      m.node.push_back(k);
    }
}

// The mold's outward normal at every vertex; a zero vector where the surface gives none.
void add_mold_normals(Mesh& m, const DrapeResult& r, const MoldSurface& surface) {
  m.normals.assign(m.node.size(), Vec3::Zero());
  for (std::size_t v = 0; v < m.node.size(); ++v) {
    const SurfaceNormal n = surface.normal(r.nodes[m.node[v]].at());
    if (n.ok && n.n.allFinite() && n.n.norm() > 0) m.normals[v] = n.n.normalized();
  }
}

Vec3 triangle_normal(const DrapeResult& r, const Mesh& m, const std::array<std::uint32_t, 3>& t) {
  const Vec3& a = r.nodes[m.node[t[0]]].point;
  return (r.nodes[m.node[t[1]]].point - a).cross(r.nodes[m.node[t[2]]].point - a);
}

// Each cell fanned from its first corner, wound counter-clockwise seen from the outward normal
// (the sum of the corners' mold normals).
void add_triangles(Mesh& m, const DrapeResult& r, const std::vector<detail::NetCell>& cells) {
  for (const auto& c : cells)
    for (std::size_t k = 1; k + 1 < c.nodes.size(); ++k) {
      std::array<std::uint32_t, 3> t = {m.slot[c.nodes[0]], m.slot[c.nodes[k]],
                                        m.slot[c.nodes[k + 1]]};
      const Vec3 outward = m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]];
      if (triangle_normal(r, m, t).dot(outward) < 0) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
    }
}

// Vertices the surface gave no normal: the mean of their triangles' normals, else +Z.
void fill_missing_normals(Mesh& m, const DrapeResult& r) {
  std::vector<Vec3> sum(m.node.size(), Vec3::Zero());
  for (const auto& t : m.triangles) {
    const Vec3 n = triangle_normal(r, m, t);
    for (const std::uint32_t v : t) sum[v] += n;
  }
  for (std::size_t v = 0; v < m.normals.size(); ++v) {
    if (m.normals[v].norm() > 0) continue;
    m.normals[v] = sum[v].norm() > 0 ? Vec3(sum[v].normalized()) : Vec3::UnitZ();
  }
}

Mesh build_mesh(const ExportContext& ctx, const std::vector<detail::NetCell>& cells) {
  const DrapeResult& r = ctx.result;
  Mesh m;
  add_vertices(m, r);
  add_mold_normals(m, r, ctx.surface);
  add_triangles(m, r, cells);
  fill_missing_normals(m, r);
  for (const DrapeLink& l : r.links()) {
    m.lines.push_back(m.slot[l.a]);
    m.lines.push_back(m.slot[l.b]);
  }
  return m;
}

// Per vertex: the node's shear, or the largest shear of its cells (negative: none).
std::vector<double> vertex_shear(const DrapeResult& r, const Mesh& m,
                                 const std::vector<detail::NetCell>& cells) {
  std::vector<double> s(m.node.size(), -1.0);
  for (const auto& c : cells)
    for (const std::uint32_t k : c.nodes) s[m.slot[k]] = std::max(s[m.slot[k]], c.shear);
  for (std::size_t v = 0; v < s.size(); ++v) {
    const double own = detail::node_shear(r.nodes[m.node[v]]);
    if (own >= 0) s[v] = own;
  }
  return s;
}

// The BIN chunk being filled (little-endian, as GLB is) and the JSON's buffer views and
// accessors that describe it.
class Binary {
 public:
  /// A float VEC3 (or SCALAR) array as a buffer view and accessor; returns the accessor.
  int floats(const std::vector<float>& v, int components, int target, bool min_max) {
    const std::size_t offset = bytes_.size();
    for (const float f : v) word(bits(f));
    json a = accessor(offset, kFloat, v.size() / components, components == 3 ? "VEC3" : "SCALAR",
                      target);
    if (min_max) {
      json lo = json::array(), hi = json::array();
      for (int c = 0; c < components; ++c) {
        float l = std::numeric_limits<float>::infinity(), h = -l;
        for (std::size_t k = c; k < v.size(); k += components) {
          l = std::min(l, v[k]);
          h = std::max(h, v[k]);
        }
        lo.push_back(static_cast<double>(l));
        hi.push_back(static_cast<double>(h));
      }
      a["min"] = lo;
      a["max"] = hi;
    }
    accessors_.push_back(std::move(a));
    return static_cast<int>(accessors_.size()) - 1;
  }
  /// Indices (uint32 SCALAR); returns the accessor.
  int indices(const std::vector<std::uint32_t>& v) {
    const std::size_t offset = bytes_.size();
    for (const std::uint32_t x : v) word(x);
    accessors_.push_back(accessor(offset, kUnsignedInt, v.size(), "SCALAR", kElementArrayBuffer));
    return static_cast<int>(accessors_.size()) - 1;
  }
  const std::string& bytes() const { return bytes_; }
  const json& views() const { return views_; }
  const json& accessors() const { return accessors_; }

 private:
  static std::uint32_t bits(float f) {
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    return u;
  }
  void word(std::uint32_t u) {
    for (int sh = 0; sh < 32; sh += 8) bytes_ += static_cast<char>((u >> sh) & 0xFF);
  }
  json accessor(std::size_t offset, int type, std::size_t count, const char* shape, int target) {
    views_.push_back({{"buffer", 0},
                      {"byteOffset", offset},
                      {"byteLength", bytes_.size() - offset},
                      {"target", target}});
    return {{"bufferView", views_.size() - 1},
            {"componentType", type},
            {"count", count},
            {"type", shape}};
  }
  std::string bytes_;
  json views_ = json::array(), accessors_ = json::array();
};

std::vector<float> vec3_floats(const std::vector<Vec3>& v, double scale) {
  std::vector<float> out;
  for (const Vec3& p : v)
    for (int a = 0; a < 3; ++a) out.push_back(static_cast<float>(p[a] * scale));
  return out;
}

json material(const std::string& name, const render::Rgb& base) {
  return {{"name", name},
          {"doubleSided", true},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {base.r, base.g, base.b, 1.0}},
            {"metallicFactor", 0.0},
            {"roughnessFactor", 1.0}}}};
}

// The primitives (those with something to draw) and their binary data.
json primitives(Binary& bin, const ExportContext& ctx, const Mesh& m,
                const std::vector<double>& shear) {
  const DrapeResult& r = ctx.result;
  const render::ShearScale scale = render::shear_scale(r);
  std::vector<Vec3> points, colours;
  for (std::size_t v = 0; v < m.node.size(); ++v) {
    points.push_back(r.nodes[m.node[v]].point);
    const render::Rgb c = scale.colour(shear[v]).linear();
    colours.emplace_back(c.r, c.g, c.b);
  }
  json prims = json::array();
  if (m.node.empty()) return prims;
  const int position = bin.floats(vec3_floats(points, kMetresPerMm), 3, kArrayBuffer, true);
  if (!m.triangles.empty()) {
    const int normal = bin.floats(vec3_floats(m.normals, 1.0), 3, kArrayBuffer, false);
    const int colour = bin.floats(vec3_floats(colours, 1.0), 3, kArrayBuffer, false);
    std::vector<std::uint32_t> idx;
    for (const auto& t : m.triangles) idx.insert(idx.end(), t.begin(), t.end());
    prims.push_back(
        {{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"COLOR_0", colour}}},
         {"indices", bin.indices(idx)},
         {"material", 0},
         {"mode", kModeTriangles}});
  }
  if (!m.lines.empty())
    prims.push_back({{"attributes", {{"POSITION", position}}},
                     {"indices", bin.indices(m.lines)},
                     {"material", 1},
                     {"mode", kModeLines}});
  return prims;
}

json gltf_json(const ExportContext& ctx, const Binary& bin, const json& prims) {
  const double top_deg = render::shear_scale(ctx.result).top * detail::kRadToDeg;
  const std::string name = ctx.run.ply_name.empty() ? "draped ply" : ctx.run.ply_name;
  json node = {{"name", name}, {"rotation", {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}}};
  json g = {{"asset",
             {{"version", "2.0"},
              {"generator", "plyfit"},
              {"extras", {{"unit", "m"}, {"shear_colour_top_deg", top_deg}}}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"materials",
             {material("shear", {1.0, 1.0, 1.0}),
              material("threads", render::Rgb{kThreadGrey, kThreadGrey, kThreadGrey}.linear())}}};
  if (!prims.empty()) {
    node["mesh"] = 0;
    g["meshes"] = {{{"name", name}, {"primitives", prims}}};
    g["accessors"] = bin.accessors();
    g["bufferViews"] = bin.views();
    g["buffers"] = {{{"byteLength", bin.bytes().size()}}};
  }
  g["nodes"] = {node};
  return g;
}

void put_u32(std::string& out, std::uint32_t u) {
  for (int sh = 0; sh < 32; sh += 8) out += static_cast<char>((u >> sh) & 0xFF);
}

// The GLB container: the header, the JSON chunk padded with spaces, the BIN chunk (if any)
// padded with zeros, each to 4 bytes.
std::string glb(std::string text, std::string bin) {
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  const std::size_t chunk_head = 8;
  const std::size_t total =
      12 + chunk_head + text.size() + (bin.empty() ? 0 : chunk_head + bin.size());
  std::string out;
  put_u32(out, kGlbMagic);
  put_u32(out, kGlbVersion);
  put_u32(out, static_cast<std::uint32_t>(total));
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  put_u32(out, kChunkJson);
  out += text;
  if (!bin.empty()) {
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, kChunkBin);
    out += bin;
  }
  return out;
}

std::string build_glb(const ExportContext& ctx) {
  const auto cells = detail::mapped_cells(ctx.result);
  const Mesh m = build_mesh(ctx, cells);
  Binary bin;
  const json prims = primitives(bin, ctx, m, vertex_shear(ctx.result, m, cells));
  // A name that is not UTF-8 (a Latin-1 ply name) gets U+FFFD where its bytes are invalid.
  const std::string text =
      gltf_json(ctx, bin, prims).dump(-1, ' ', false, json::error_handler_t::replace);
  return glb(text, bin.bytes());
}

}  // namespace

Exporter make_glb_exporter() {
  return file_exporter("glb",
                       "net.glb: draped ply (glTF 2.0 binary): triangles coloured by shear, "
                       "threads as lines, metres",
                       {{"net.glb", build_glb}});
}

}  // namespace plyfit::exporters
