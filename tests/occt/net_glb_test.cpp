// net.glb read back by a GLB reader of the test's own (the container's header and chunks, the
// accessors' bounds) and compared with the drape: one vertex per mapped node at its position in
// metres, every index in range, the triangles and lines the cells and links make, colours that
// follow the shear.

#include <plyfit/exporters/exporters.hpp>

#include "export_cases.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>

using namespace plyfit;
using namespace plyfit::test;  // export_cases.hpp: Case, cases(), fresh_dir(), slurp()

namespace {

using nlohmann::json;

constexpr double kMetresPerMm = 1e-3;
constexpr float kFloat32Eps = 1.1920929e-7f;  // 2^-23

// A GLB file's JSON and BIN chunks, and its accessors read as numbers.
struct Glb {
  json doc;
  std::string bin;

  std::uint32_t u32(std::size_t at) const {
    std::uint32_t u = 0;
    for (int k = 3; k >= 0; --k)
      u = (u << 8) | static_cast<unsigned char>(bin[at + static_cast<std::size_t>(k)]);
    return u;
  }
  // The accessor's values, component after component; checks that it lies in its buffer view
  // and the view in the buffer.
  std::vector<double> values(int index) const {
    const json& a = doc.at("accessors").at(static_cast<std::size_t>(index));
    const json& v = doc.at("bufferViews").at(a.at("bufferView").get<std::size_t>());
    const std::size_t comps = a.at("type") == "VEC3" ? 3 : 1;
    const std::size_t count = a.at("count");
    REQUIRE(count > 0);
    REQUIRE((a.at("componentType") == 5126 || a.at("componentType") == 5125));
    const std::size_t offset = v.value("byteOffset", 0) + a.value("byteOffset", 0);
    REQUIRE(v.at("buffer") == 0);
    REQUIRE(a.value("byteOffset", 0) + count * comps * 4 <= v.at("byteLength").get<std::size_t>());
    REQUIRE(v.value("byteOffset", 0) + v.at("byteLength").get<std::size_t>() <=
            doc.at("buffers").at(0).at("byteLength").get<std::size_t>());
    REQUIRE(offset % 4 == 0);
    std::vector<double> out;
    for (std::size_t k = 0; k < count * comps; ++k) {
      const std::uint32_t u = u32(offset + 4 * k);
      float f = 0;
      std::memcpy(&f, &u, sizeof f);
      out.push_back(a.at("componentType") == 5126 ? static_cast<double>(f) : u);
    }
    return out;
  }
};

std::uint32_t le32(const std::string& s, std::size_t at) {
  std::uint32_t u = 0;
  for (int k = 3; k >= 0; --k)
    u = (u << 8) | static_cast<unsigned char>(s[at + static_cast<std::size_t>(k)]);
  return u;
}

// The container: a 12-byte header ("glTF", version 2, the file's length), a JSON chunk padded
// with spaces and a BIN chunk padded with zeros, each a multiple of 4 bytes.
Glb read_glb(const std::string& file) {
  REQUIRE(file.size() >= 20);
  CHECK(file.substr(0, 4) == "glTF");
  CHECK(le32(file, 4) == 2);
  CHECK(le32(file, 8) == file.size());
  const std::size_t json_len = le32(file, 12);
  CHECK(file.substr(16, 4) == "JSON");
  CHECK(json_len % 4 == 0);
  REQUIRE(20 + json_len <= file.size());
  Glb g;
  g.doc = json::parse(file.substr(20, json_len));
  const std::size_t at = 20 + json_len;
  if (at < file.size()) {
    REQUIRE(at + 8 <= file.size());
    const std::size_t bin_len = le32(file, at);
    CHECK(file.substr(at + 4, 4) == std::string("BIN\0", 4));
    CHECK(bin_len % 4 == 0);
    REQUIRE(at + 8 + bin_len == file.size());
    g.bin = file.substr(at + 8, bin_len);
    CHECK(g.doc.at("buffers").at(0).at("byteLength").get<std::size_t>() <= bin_len);
  }
  return g;
}

Glb write_and_read(const Case& c) {
  const fs::path dir = fresh_dir("glb");
  REQUIRE(exporters::find_exporter("glb")->write(c.ctx(), dir.string()).ok());
  return read_glb(slurp(dir / "net.glb"));
}

const json& primitive(const Glb& g, int mode) {
  for (const json& p : g.doc.at("meshes").at(0).at("primitives"))
    if (p.at("mode") == mode) return p;
  FAIL("no primitive of mode " << mode);
  return g.doc;
}

// Per vertex, the three components of an attribute.
std::vector<Vec3> vec3s(const std::vector<double>& v) {
  std::vector<Vec3> out;
  for (std::size_t k = 0; k + 2 < v.size(); k += 3) out.emplace_back(v[k], v[k + 1], v[k + 2]);
  return out;
}

std::unique_ptr<Case> plate_case() {
  return make_case("plate", {{"W", 100}, {"H", 60}},
                   problem(2, {0, 0}, {1, 0}, {{0, 1}, {0, -1}}, {20, 10, 0}, {0, 1, 0},
                           {{0, 1, 0}, {0, -1, 0}}));
}

std::unique_ptr<Case> hemisphere_case() {
  return make_case("hemisphere", {{"R", 20}},
                   problem(1, {0, 0}, {0, 1}, {{-1, 0}, {1, 0}}, {0, 0, 20}, {1, 0, 0},
                           {{1, 0, 0}, {-1, 0, 0}}));
}

// The vertex colours of a case's net.glb and the node of each vertex (the mapped nodes in order,
// pointers into the case).
std::vector<Vec3> colours_of(const Case& c, std::vector<const DrapeNode*>& nodes) {
  const Glb g = write_and_read(c);
  for (const DrapeNode& n : c.result.nodes)
    if (n.mapped()) nodes.push_back(&n);
  const auto colours = vec3s(g.values(primitive(g, 4).at("attributes").at("COLOR_0")));
  REQUIRE(colours.size() == nodes.size());
  return colours;
}

}  // namespace

TEST_CASE(
    "exporters: net.glb is a GLB whose accessors hold the drape, in metres, every index in range") {
  auto all = cases();
  all.push_back(hemisphere_case());
  for (const auto& c : all) {
    INFO(c->name);
    const Glb g = write_and_read(*c);
    const DrapeResult& r = c->result;
    CHECK(g.doc.at("asset").at("version") == "2.0");
    CHECK(g.doc.at("asset").at("generator") == "plyfit");
    const json& tri = primitive(g, 4);
    const json& lines = primitive(g, 1);
    const int pos = tri.at("attributes").at("POSITION");
    CHECK(lines.at("attributes").at("POSITION") == pos);
    // Positions: the mapped nodes in the drape's order, in metres, as float32; min and max
    // are the data's own.
    const auto points = vec3s(g.values(pos));
    std::vector<Vec3> want;
    for (const DrapeNode& n : r.nodes)
      if (n.mapped()) want.push_back(n.point * kMetresPerMm);
    REQUIRE(points.size() == want.size());
    REQUIRE(want.size() == r.metrics.nodes.mapped + r.metrics.nodes.auxiliary);
    for (std::size_t k = 0; k < want.size(); ++k)
      CHECK(points[k] == want[k].cast<float>().cast<double>());
    const json& acc = g.doc.at("accessors").at(static_cast<std::size_t>(pos));
    for (int a = 0; a < 3; ++a) {
      double lo = points[0][a], hi = lo;
      for (const Vec3& p : points) {
        lo = std::min(lo, p[a]);
        hi = std::max(hi, p[a]);
      }
      CHECK(acc.at("min").at(static_cast<std::size_t>(a)).get<double>() == lo);
      CHECK(acc.at("max").at(static_cast<std::size_t>(a)).get<double>() == hi);
    }
    // Indices in range; as many triangles as the cells' corners make, a line per link.
    const auto ti = g.values(tri.at("indices"));
    const auto li = g.values(lines.at("indices"));
    for (const double i : ti) CHECK(i < static_cast<double>(points.size()));
    for (const double i : li) CHECK(i < static_cast<double>(points.size()));
    std::size_t triangles = 0;
    for (const auto& cell : plyfit::mapped_cells(r)) triangles += cell.nodes.size() - 2;
    CHECK(ti.size() == 3 * triangles);
    CHECK(li.size() == 2 * r.links().size());
    // Normals are unit vectors; each triangle is wound counter-clockwise seen from them.
    const auto normals = vec3s(g.values(tri.at("attributes").at("NORMAL")));
    REQUIRE(normals.size() == points.size());
    for (const Vec3& n : normals) CHECK(std::abs(n.norm() - 1) <= 4 * kFloat32Eps);
    for (std::size_t k = 0; k + 2 < ti.size(); k += 3) {
      const auto v = [&](std::size_t m) { return static_cast<std::size_t>(ti[k + m]); };
      const Vec3 n = (want[v(1)] - want[v(0)]).cross(want[v(2)] - want[v(0)]);
      CHECK(n.dot(normals[v(0)] + normals[v(1)] + normals[v(2)]) > 0);
    }
  }
}

TEST_CASE("exporters: net.glb's vertex colours follow the shear: one colour on a plate") {
  const auto c = plate_case();
  std::vector<const DrapeNode*> nodes;
  const auto colours = colours_of(*c, nodes);
  REQUIRE(colours.size() > 100);
  for (const Vec3& col : colours) CHECK((col - colours.front()).norm() <= 4 * kFloat32Eps);
  // The scale's low end: viridis' dark violet (more blue than green).
  CHECK(colours.front().z() > colours.front().y());
}

TEST_CASE(
    "exporters: net.glb's vertex colours follow the shear: green grows with it on a hemisphere") {
  const auto c = hemisphere_case();
  std::vector<const DrapeNode*> nodes;
  const auto colours = colours_of(*c, nodes);
  // The ramp's green rises from 0.005 to 0.906 (sRGB): sorted by shear, the nodes with a
  // thread angle have non-decreasing green, and the colours differ.
  std::vector<std::pair<double, double>> shear_green;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k]->has(DrapeNode::kHasAngle))
      shear_green.emplace_back(std::abs(kPi / 2 - nodes[k]->thread_angle), colours[k].y());
  REQUIRE(shear_green.size() > 100);
  std::sort(shear_green.begin(), shear_green.end());
  for (std::size_t k = 1; k < shear_green.size(); ++k)
    CHECK(shear_green[k].second >= shear_green[k - 1].second);
  CHECK(shear_green.back().first > 20 * kDegToRad);
  CHECK(shear_green.back().second > 10 * shear_green.front().second);
}
