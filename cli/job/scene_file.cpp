#include "job/scene_file.hpp"

#include "job/ini.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace plyfit::cli {

namespace {

const OptionSpec* find_key(const std::string& key) {
  for (const auto& s : drape_options())
    if (s.key == key) return &s;
  return nullptr;
}

}  // namespace

Status add_scene_key(const IniLine& l, const std::string& path, const std::string& dir,
                     RawOptions& raw, const std::string& origin) {
  const std::string dotted = l.section.empty() ? l.key : l.section + "." + l.key;
  const auto dot = dotted.rfind('.');
  const std::string section = dot == std::string::npos ? "" : dotted.substr(0, dot);
  const std::string key = dot == std::string::npos ? dotted : dotted.substr(dot + 1);
  const OptionSpec* s = find_key(key);
  if (!s) {
    Error e{ErrorCode::kUnknownKey, "", {key, section}};
    e.where = ini_place(path, l.line);
    return e;
  }
  auto& vals = raw.values[key];
  if (!s->repeatable && !vals.empty()) return Error{ErrorCode::kOptionRepeated, key};
  vals.push_back(l.value);
  raw.dirs[key] = dir;
  raw.origins[key] = origin.empty() ? path : origin;
  return ok_status();
}

namespace {

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}
std::string fmt(const Vec2& v) {
  return fmt(v.x()) + "," + fmt(v.y());
}
std::string fmt(const Vec3& v) {
  return fmt(v.x()) + "," + fmt(v.y()) + "," + fmt(v.z());
}

using SceneValues = std::map<std::string, std::vector<std::string>>;

// The mold and ply keys of a job.
void mold_and_ply_values(const DrapeJob& job, SceneValues& v) {
  const auto& p = job.problem;
  v["mold"] = {job.mold};
  if (job.connected_faces) {
    v["faces"] = {"connected"};
    v["max-crease"] = {fmt(job.max_crease_deg)};
    if (job.faces_at) v["faces-at"] = {fmt(*job.faces_at)};
  } else if (job.all_faces) {
    v["faces"] = {"all"};
  } else if (!job.faces.empty()) {
    std::string list;
    for (int f : job.faces) {
      if (!list.empty()) list += ',';
      list += std::to_string(f);
    }
    v["faces"] = {list};
  } else if (job.faces_at) {
    v["faces-at"] = {fmt(*job.faces_at)};
  } else {
    v["face"] = {std::to_string(job.face)};
  }
  if (!job.format.empty()) v["format"] = {job.format};
  v["flip-normal"] = {job.flip_normal ? "true" : "false"};
  if (p.ply.d_weft == p.ply.d_warp) {
    v["spacing"] = {fmt(p.ply.d_weft)};
  } else {
    v["spacing-weft"] = {fmt(p.ply.d_weft)};
    v["spacing-warp"] = {fmt(p.ply.d_warp)};
  }
  if (p.ply.rect) v["ply"] = {fmt(*p.ply.rect)};
  v["start2d"] = {fmt(p.ply.start)};
  if (job.rosette_given) v["rosette"] = {fmt(job.rosette)};  // else the start keys' own 0 deg
  v["seed-curve"] = {job.seed_curve_file ? to_string(*job.seed_curve_file)
                                         : std::string(to_string(p.seed_curve))};
  if (job.boundary) v["boundary"] = {to_string(*job.boundary)};
  if (job.boundary_offset != 0.0) v["boundary-offset"] = {fmt(job.boundary_offset)};
  for (const auto& dart : job.darts) v["dart"].push_back(to_string(dart));
  if (job.darts_auto) v["darts"] = {"auto"};
  if (job.seed) {  // the directions follow from the seed on the mold
    v["seed"] = {fmt(*job.seed)};
    return;
  }
  v["base2d"] = {fmt(p.ply.base_dir)};
  for (const auto& w : p.ply.sweeps) v["sweep2d"].push_back(fmt(w));
  v["start3d"] = {fmt(p.start)};
  v["base-normal"] = {fmt(p.base_normal)};
  for (const auto& w : p.sweeps) v["sweep3d"].push_back(fmt(w));
}

// The material, numerics and output keys of a job.
void material_and_output_values(const DrapeJob& job, SceneValues& v) {
  v["material"] = {job.material};
  if (!job.exports.materials_file.empty()) v["materials"] = {job.exports.materials_file};
  v["lock-angle"] = {fmt(job.lock_angle_deg)};
  v["warn-angle"] = {fmt(job.warn_angle_deg)};
  v["ply-name"] = {job.ply_name};
  v["ply-angle"] = {fmt(job.ply_angle_deg)};
  v["tolerance"] = {fmt(job.tolerance_rel)};
  v["max-iterations"] = {std::to_string(job.max_iterations)};
  v["guess"] = {to_string(job.drape.guess)};
  v["max-nodes"] = {std::to_string(job.drape.max_nodes)};
  if (!job.outdir.empty()) v["output"] = {job.outdir};
  std::string outs;
  for (const auto& o : job.outputs) outs += (outs.empty() ? "" : ",") + o;
  v["outputs"] = {outs};
  v["curve-degree"] = {std::to_string(job.exports.curve_degree)};
  v["view"] = {fmt(job.exports.view)};
  v["dxf-threads"] = {job.exports.dxf_threads ? "true" : "false"};
  // The effective value: the one given, or the default the flat pattern takes.
  v["min-width"] = {fmt(FlatPatternOptions{job.min_width}.width_for(job.problem.ply))};
}

}  // namespace

Result<std::vector<IniLine>> read_scene_lines(const std::string& path) {
  const auto text = exporters::read_file(path);
  if (!text) {
    Error e{ErrorCode::kSceneCannotOpen};
    e.where = path;
    return e;
  }
  return read_ini(*text, path);
}

Result<RawOptions> raw_from_scene(const std::string& path) {
  auto lines = read_scene_lines(path);
  if (!lines) return lines.error();
  RawOptions raw;
  raw.origin = path;
  const std::string dir = fs::absolute(fs::path(path)).parent_path().string();
  for (const IniLine& l : *lines)
    if (!l.is_section)
      if (auto st = add_scene_key(l, path, dir, raw); !st) return st.error();
  return raw;
}

exporters::InputNamer scene_namer(const std::string& path) {
  RawOptions raw;
  raw.origin = path;
  return input_namer(raw, drape_options());
}

std::string dump_scene(const DrapeJob& job) {
  SceneValues v;
  mold_and_ply_values(job, v);
  material_and_output_values(job, v);
  std::ostringstream os;
  os << "# plyfit scene (plyfit drape --dump-scene)\n";
  std::string section;
  for (const auto& s : drape_options()) {
    auto it = v.find(s.key);
    if (it == v.end()) continue;
    if (s.section != section) {
      section = s.section;
      os << "\n[" << section << "]\n";
    }
    for (const auto& x : it->second) os << s.key << " = " << x << "\n";
  }
  return os.str();
}

}  // namespace plyfit::cli
