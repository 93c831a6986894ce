// plyfit info FILE [--json] [--format F]: lists a mold file's faces without converting them.

#include "commands.hpp"

#include <plyfit/importers/importers.hpp>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <map>
#include <string>

namespace plyfit::cli {

namespace {

namespace po = boost::program_options;

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

std::string point(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

std::string pad(std::string s, size_t w) {
  if (s.size() < w) s.append(w - s.size(), ' ');
  return s;
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

void print_text(const Mold& m, std::ostream& os) {
  os << "file: " << m.source << "\n";
  os << pad("index", 7) << pad("name", 18) << pad("kind", 12) << pad("degree", 8)
     << pad("poles", 10) << pad("rational", 10) << pad("trimmed", 13) << pad("reversed", 10)
     << pad("area_mm2", 14) << "bbox_mm (min .. max)\n";
  for (const auto& f : m.faces) {
    const bool has_net = f.poles_u > 0;
    std::string trim = f.trimmed ? "yes" : "no";
    if (f.holes > 0) trim += " (" + std::to_string(f.holes) + (f.holes == 1 ? " hole)" : " holes)");
    os << pad(std::to_string(f.index), 7) << pad(f.name.empty() ? "-" : "'" + f.name + "'", 18)
       << pad(f.kind, 12)
       << pad(has_net ? std::to_string(f.degree_u) + "x" + std::to_string(f.degree_v) : "-", 8)
       << pad(has_net ? std::to_string(f.poles_u) + "x" + std::to_string(f.poles_v) : "-", 10)
       << pad(f.rational ? "yes" : "no", 10) << pad(trim, 13) << pad(f.reversed ? "yes" : "no", 10)
       << pad(fmt("%.6g", f.area), 14)
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
    for (const auto& w : m.warnings) os << "warning: " << w << "\n";
  }
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
              {"warnings", m.warnings}};
}

int run_info(const std::vector<std::string>& args) {
  po::options_description opts("plyfit info FILE [options]");
  opts.add_options()("help,h", "show this help")("json", "print the listing as JSON")(
      "format", po::value<std::string>(), "importer to use (step, iges), overriding the extension")(
      "file", po::value<std::string>(), "mold file (STEP or IGES)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("info: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    std::cout << "Lists a mold file's faces: index, name, surface kind, degrees, poles, rational,\n"
                 "trimmed (holes), reversed, area and bounding box (mm), then a summary.\n\n"
              << opts;
    return kExitOk;
  }
  if (!vm.count("file")) {
    print_error("info: missing the mold file (plyfit info FILE [--json] [--format F])");
    return kExitUsage;
  }
  importers::ImportOptions options;
  if (vm.count("format")) options.format = vm["format"].as<std::string>();
  auto file = importers::open_mold(vm["file"].as<std::string>(), options);
  if (!file) {
    print_error(file.error().message);
    return kExitFailure;
  }
  const Mold& m = (*file)->mold();
  if (vm.count("json"))
    std::cout << to_json(m).dump(2) << "\n";
  else
    print_text(m, std::cout);
  return kExitOk;
}

const CommandRegistrar kRegisterInfo{
    Command{"info", "list a mold file's faces (kind, degrees, trims, area, bbox)", 10, run_info}};

}  // namespace

}  // namespace plyfit::cli
