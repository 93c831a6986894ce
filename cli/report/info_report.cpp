#include "report/info_report.hpp"

#include "report/text_format.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/warnings_json.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <map>
#include <ostream>

namespace plyfit::cli {

namespace {

std::string point(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

struct Summary {
  std::map<std::string, int> kinds;
  int rational = 0, trimmed = 0, with_holes = 0, reversed = 0;
};

Summary summarise(const Mold& m) {
  Summary s;
  for (const auto& f : m.faces) {
    s.kinds[f.kind]++;
    s.rational += f.rational;
    s.trimmed += f.trimmed;
    s.with_holes += f.holes > 0;
    s.reversed += f.reversed;
  }
  return s;
}

nlohmann::json to_json(const Mold& m) {
  using nlohmann::json;
  json faces = json::array();
  for (const auto& f : m.faces) {
    json jf = {{"index", f.index},
               {"name", f.name},
               {"kind", f.kind},
               {"degree", {f.degree_u, f.degree_v}},
               {"poles", {f.poles_u, f.poles_v}},
               {"rational", f.rational},
               {"trimmed", f.trimmed},
               {"holes", f.holes},
               {"reversed", f.reversed},
               {"area_mm2", f.area}};
    if (!f.area_measured) jf["area_mm2"] = nullptr;
    if (f.free_edges >= 0) {
      jf["neighbours"] = f.neighbours;
      jf["free_edges"] = f.free_edges;
    }
    if (f.bbox.empty)
      jf["bbox_mm"] = nullptr;
    else
      jf["bbox_mm"] = {{"min", {f.bbox.min.x(), f.bbox.min.y(), f.bbox.min.z()}},
                       {"max", {f.bbox.max.x(), f.bbox.max.y(), f.bbox.max.z()}}};
    faces.push_back(std::move(jf));
  }
  const Summary s = summarise(m);
  return json{{"file", m.source},
              {"format", m.format},
              {"schema", m.schema},
              {"unit", m.unit},
              {"faces", std::move(faces)},
              {"summary",
               {{"faces", m.faces.size()},
                {"kinds", s.kinds},
                {"rational", s.rational},
                {"trimmed", s.trimmed},
                {"with_holes", s.with_holes},
                {"reversed", s.reversed}}},
              {"warnings", exporters::warnings_json(m.warnings)}};
}

std::string csv(const Vec3& v) {
  char buf[128];
  // + 0.0: no "-0".
  std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);
  return buf;
}

// The plyfit drape flags of a start.
std::string start_flags(const FaceStart& s, int index) {
  return "--face " + std::to_string(index) + " --start3d " + csv(s.point) + " --base-normal " +
         csv(s.base_normal) + " --sweep3d " + csv(s.base_normal) + " --sweep3d " +
         csv(-s.base_normal) + " --start2d 0,0 --base2d 1,0 --sweep2d 0,1 --sweep2d 0,-1";
}

// A face's neighbours in the file's topology as "1,4,6" ("-" for none or not read).
std::string neighbour_list(const FaceInfo& f) {
  std::string s;
  for (int g : f.neighbours) {
    if (!s.empty()) s += ',';
    s += std::to_string(g);
  }
  return s.empty() ? "-" : s;
}

}  // namespace

void print_listing(const Mold& m, std::ostream& os) {
  os << "file: " << m.source << "\n";
  os << pad("index", 7) << pad("name", 18) << pad("kind", 12) << pad("degree", 8)
     << pad("poles", 10) << pad("rational", 10) << pad("trimmed", 13) << pad("reversed", 10)
     << pad("area_mm2", 14) << pad("neighbours", 14) << pad("free", 6) << "bbox_mm (min .. max)\n";
  for (const auto& f : m.faces) {
    const bool has_net = f.poles_u > 0;
    std::string trim = f.trimmed ? "yes" : "no";
    if (f.holes > 0) trim += " (" + std::to_string(f.holes) + (f.holes == 1 ? " hole)" : " holes)");
    os << pad(std::to_string(f.index), 7) << pad(f.name.empty() ? "-" : "'" + f.name + "'", 18)
       << pad(f.kind, 12)
       << pad(has_net ? std::to_string(f.degree_u) + "x" + std::to_string(f.degree_v) : "-", 8)
       << pad(has_net ? std::to_string(f.poles_u) + "x" + std::to_string(f.poles_v) : "-", 10)
       << pad(f.rational ? "yes" : "no", 10) << pad(trim, 13) << pad(f.reversed ? "yes" : "no", 10)
       << pad(f.area_measured ? format("%.6g", f.area) : "invalid", 14)
       << pad(neighbour_list(f), 14)
       << pad(f.free_edges >= 0 ? std::to_string(f.free_edges) : "-", 6)
       << (f.bbox.empty ? "-" : point(f.bbox.min) + " .. " + point(f.bbox.max)) << "\n";
  }
  const Summary s = summarise(m);
  os << "summary: " << m.faces.size() << " faces (";
  bool first = true;
  for (const auto& [k, n] : s.kinds) {
    os << (first ? "" : ", ") << k << " " << n;
    first = false;
  }
  os << "), " << s.rational << " rational, " << s.trimmed << " trimmed (" << s.with_holes
     << " with holes), " << s.reversed << " reversed; unit: " << m.unit
     << " (values above in mm); format: " << m.format << "; schema: " << m.schema << "\n";
  if (m.warnings.empty()) {
    os << "warnings: none\n";
  } else {
    for (const auto& w : m.warnings) os << "warning: " << exporters::message(w) << "\n";
  }
}

std::string listing_json(const Mold& m) {
  return to_json(m).dump(2) + "\n";
}

void print_face_start(const std::string& path, int index, const FaceInfo& info, const FaceStart& s,
                      bool json, std::ostream& os) {
  auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  if (json) {
    const nlohmann::json j = {{"file", path},
                              {"face", index},
                              {"name", info.name},
                              {"kind", info.kind},
                              {"area_mm2", info.area},
                              {"uv", {s.uv.x(), s.uv.y()}},
                              {"point", vec(s.point)},
                              {"normal", vec(s.normal)},
                              {"base_tangent", vec(s.tangent)},
                              {"base_normal", vec(s.base_normal)},
                              {"sweep3d", {vec(s.base_normal), vec(-s.base_normal)}},
                              {"flags", start_flags(s, index)}};
    os << j.dump(2) << "\n";
    return;
  }
  os << "file: " << path << "\n"
     << "face " << index << ": " << (info.name.empty() ? "-" : "'" + info.name + "'") << ", "
     << info.kind << ", area " << format("%.6g", info.area) << " mm2\n"
     << "point near the middle: " << point(s.point) << " mm at (u, v) = ("
     << format("%.9g", s.uv.x()) << ", " << format("%.9g", s.uv.y()) << ")\n"
     << "outward normal: " << point(s.normal) << "\n"
     << "suggested base path: along the surface's u direction " << point(s.tangent)
     << "; base-plane normal and sweep directions +/- " << point(s.base_normal) << "\n"
     << "flags: " << start_flags(s, index) << "\n";
}

}  // namespace plyfit::cli
