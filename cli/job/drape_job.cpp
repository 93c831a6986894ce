#include "job/drape_job.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/optimize.hpp>
#include "job/materials.hpp"

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include <boost/program_options.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace plyfit::cli {

namespace {

// Without --warn-angle, cells are flagged at least this far (degrees) below the lock angle.
constexpr double kWarnBelowLockDeg = 5.0;

std::string all_outputs() {
  std::string s;
  for (const auto& e : exporters::registry()) s += (s.empty() ? "" : ",") + e.key;
  return s;
}

}  // namespace

const std::vector<OptionSpec>& drape_options() {
  static const std::vector<OptionSpec> list = {
      {"mold", "FILE|builtin:NAME[:k=v,...]", "", "mold file (STEP, IGES) or a built-in mold",
       false, "mold"},
      {"face", "N", "0", "face index in the mold file (see plyfit info)", false, "mold"},
      {"faces", "LIST|all", "",
       "faces to drape as one shell (comma-separated indices, or all), sewn along their shared "
       "edges; instead of --face",
       false, "mold"},
      {"format", "KEY", "", "importer to use instead of the file extension (step, iges)", false,
       "mold"},
      {"flip-normal", "", "false", "drape on the other side of the surface", false, "mold"},
      {"spacing", "D", "", "thread spacing d (both directions), model units", false, "ply"},
      {"spacing-weft", "D", "", "weft link length (spacing of the warp threads, along x)", false,
       "ply"},
      {"spacing-warp", "D", "", "warp link length (spacing of the weft threads, along y)", false,
       "ply"},
      {"ply", "W,H", "", "cloth rectangle [0,W] x [0,H] (default: unbounded)", false, "ply"},
      {"start2d", "X,Y", "", "start point of the base path in ply coordinates", false, "start"},
      {"base2d", "DX,DY", "", "base path direction in ply coordinates", false, "start"},
      {"sweep2d", "DX,DY", "", "sweep direction in ply coordinates (one per half-plane)", true,
       "start"},
      {"start3d", "X,Y,Z", "", "start point on the mold (projected onto the face)", false, "start"},
      {"base-normal", "NX,NY,NZ", "", "normal of the base plane (through the 3D start)", false,
       "start"},
      {"sweep3d", "DX,DY,DZ", "", "3D sweep direction, paired in order with --sweep2d", true,
       "start"},
      {"material", "NAME", kDefaultMaterial,
       "material from the materials table: its label, warning and limit angles", false, "material"},
      {"materials", "FILE", "", "materials table to use instead of plyfit's (data/materials.ini)",
       false, "material"},
      {"lock-angle", "DEG", "",
       "largest shear (90 - thread angle) the cloth takes (default: the material's limit); 90 = "
       "no limit",
       false, "material"},
      {"warn-angle", "DEG", "",
       "shear above which cells are flagged (default: the material's warning angle, at most "
       "lock angle - 5)",
       false, "material"},
      {"ply-name", "TEXT", "ply", "ply name for labels", false, "material"},
      {"ply-angle", "DEG", "0",
       "ply angle: the fibre (warp) direction on the part, as in the layup, for labels", false,
       "material"},
      {"tolerance", "T", "1e-14", "Newton tolerance relative to the spacing (eq. 9)", false,
       "numerics"},
      {"max-iterations", "N", "40", "Newton iteration cap per node", false, "numerics"},
      {"guess", "extrapolated|paper|parallelogram", "extrapolated",
       "initial guess of the two-sphere solver (paper: eqs. 10-11)", false, "numerics"},
      {"max-nodes", "N", "50000000", "stop after reaching this many nodes", false, "numerics"},
      {"output", "DIR", "", "output folder (-o)", false, "output"},
      {"outputs", "LIST", "", "outputs to write, comma-separated (default: all)", false, "output"},
      {"curve-degree", "1|3", "1", "degree of the thread curves in net.step", false, "output"},
      {"view", "X,Y,Z", "1,1,1", "view direction of drape.svg (towards the viewer)", false,
       "output"},
      {"dxf-threads", "true|false", "false",
       "THREADS layer (thread grid) in flat.dxf (a cutter would cut it)", false, "output"},
      {"min-width", "W", "",
       "cut outline: slivers of cloth and notches narrower than W are cut off or closed, "
       "model units (default: half the spacing; 0: the exact outline)",
       false, "output"},
  };
  return list;
}

Result<double> parse_number(const std::string& text, const std::string& what) {
  std::string t = text;
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
  std::size_t b = 0;
  while (b < t.size() && std::isspace(static_cast<unsigned char>(t[b]))) ++b;
  t = t.substr(b);
  if (t.empty()) return Error{what + ": empty value, expected a number"};
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size()) return Error{what + ": '" + text + "' is not a number"};
  if (!std::isfinite(x) || errno == ERANGE)
    return Error{what + ": '" + text + "' is not a finite number"};
  return x;
}

namespace {

template <int N>
Result<Eigen::Matrix<double, N, 1>> parse_vec(const std::string& text, const std::string& what) {
  Eigen::Matrix<double, N, 1> v;
  std::stringstream ss(text);
  std::string part;
  int k = 0;
  while (std::getline(ss, part, ',')) {
    if (k >= N)
      return Error{what + ": '" + text + "' has more than " + std::to_string(N) + " numbers"};
    auto x = parse_number(part, what);
    if (!x) return x.error();
    v[k++] = *x;
  }
  if (k != N)
    return Error{what + ": '" + text + "' must be " + std::to_string(N) +
                 " comma-separated numbers"};
  return v;
}

Result<int> parse_int(const std::string& text, const std::string& what, long lo, long hi) {
  auto x = parse_number(text, what);
  if (!x) return x.error();
  if (*x != std::floor(*x) || *x < lo || *x > hi)
    return Error{what + ": '" + text + "' must be an integer from " + std::to_string(lo) + " to " +
                 std::to_string(hi)};
  return static_cast<int>(*x);
}

Result<bool> parse_bool(const std::string& text, const std::string& what) {
  if (text == "true" || text == "1" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "0" || text == "no" || text == "off") return false;
  return Error{what + ": '" + text + "' must be true or false"};
}

const OptionSpec* find_spec(const std::string& key) {
  for (const auto& s : drape_options())
    if (s.key == key) return &s;
  return nullptr;
}

}  // namespace

Result<RawOptions> raw_from_args(const std::vector<std::string>& args) {
  po::options_description desc;
  for (const auto& s : drape_options()) {
    const std::string name = s.key == "output" ? "output,o" : s.key;
    if (s.value.empty()) {
      desc.add_options()(
          name.c_str(),
          po::value<std::vector<std::string>>()->zero_tokens()->implicit_value({"true"}, "true"),
          s.help.c_str());
    } else {
      desc.add_options()(name.c_str(), po::value<std::vector<std::string>>()->composing(),
                         s.help.c_str());
    }
  }
  RawOptions raw;
  raw.origin = "command line";
  const std::string cwd = fs::current_path().string();
  try {
    const po::parsed_options parsed = po::command_line_parser(args).options(desc).run();
    for (const auto& o : parsed.options) {
      if (o.position_key >= 0)
        return Error{"unexpected argument '" + o.value.front() +
                     "' (a scene file must come first)"};
      const OptionSpec* s = find_spec(o.string_key);
      if (!s) return Error{"unknown option --" + o.string_key};
      auto& vals = raw.values[o.string_key];
      raw.dirs[o.string_key] = cwd;
      raw.origins[o.string_key] = raw.origin;
      if (!s->repeatable && !vals.empty())
        return Error{"--" + o.string_key + " given more than once"};
      if (s->value.empty()) {
        vals.push_back(o.value.empty() ? "true" : o.value.front());
      } else {
        if (o.value.empty())
          return Error{"--" + o.string_key + " needs a value (" + s->value + ")"};
        vals.insert(vals.end(), o.value.begin(), o.value.end());
      }
    }
  } catch (const po::error& e) {
    return Error{e.what()};
  }
  return raw;
}

Result<RawOptions> raw_from_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{path + ": cannot open the scene file"};
  RawOptions raw;
  raw.origin = path;
  const std::string dir = fs::absolute(fs::path(path)).parent_path().string();
  try {
    po::options_description none;
    const po::parsed_options parsed = po::parse_config_file(in, none, true);
    for (const auto& o : parsed.options) {
      // Sections are for grouping: "[ply] spacing = 1" is the key "spacing".
      std::string key = o.string_key;
      const auto dot = key.rfind('.');
      const std::string section = dot == std::string::npos ? "" : key.substr(0, dot);
      if (dot != std::string::npos) key = key.substr(dot + 1);
      const OptionSpec* s = find_spec(key);
      if (!s)
        return Error{path + ": unknown key '" + key + "'" +
                     (section.empty() ? "" : " in section [" + section + "]")};
      auto& vals = raw.values[key];
      raw.dirs[key] = dir;
      raw.origins[key] = path;
      if (!s->repeatable && !vals.empty())
        return Error{path + ": key '" + key + "' given more than once"};
      for (const auto& v : o.value) vals.push_back(v);
      if (o.value.empty()) return Error{path + ": key '" + key + "' has no value"};
    }
  } catch (const po::error& e) {
    return Error{path + ": " + e.what()};
  }
  return raw;
}

RawOptions merge(const RawOptions& base, const RawOptions& over) {
  RawOptions out = base;
  for (const auto& [k, v] : over.values) {
    out.values[k] = v;
    const auto d = over.dirs.find(k);
    if (d != over.dirs.end()) out.dirs[k] = d->second;
    const auto o = over.origins.find(k);
    out.origins[k] = o != over.origins.end() ? o->second : over.origin;
  }
  return out;
}

Result<DrapeJob> make_job(const RawOptions& raw, bool need_output) {
  const std::string where = raw.origin == "command line" ? "" : raw.origin + ": ";
  auto get = [&](const std::string& k) -> const std::vector<std::string>* {
    auto it = raw.values.find(k);
    return it == raw.values.end() || it->second.empty() ? nullptr : &it->second;
  };
  auto one = [&](const std::string& k) -> std::optional<std::string> {
    const auto* v = get(k);
    if (v) return v->front();
    const OptionSpec* s = find_spec(k);
    if (s && !s->def.empty()) return s->def;
    return std::nullopt;
  };
  // A key is named where its value came from: "--key" for a flag, "FILE: key 'key'" for a
  // scene file (a default is named like the job's origin).
  auto name = [&](const std::string& k) {
    const auto o = raw.origins.find(k);
    const std::string from = o != raw.origins.end() ? o->second : raw.origin;
    return from == "command line" || from.empty() ? "--" + k : from + ": key '" + k + "'";
  };
  auto dir_for = [&](const std::string& k) {
    const auto d = raw.dirs.find(k);
    return d == raw.dirs.end() ? std::string() : d->second;
  };
  auto resolve = [&](const std::string& k, const std::string& p) {
    if (p.rfind("builtin:", 0) == 0 || fs::path(p).is_absolute() || dir_for(k).empty()) return p;
    return (fs::path(dir_for(k)) / p).lexically_normal().string();
  };
  DrapeJob job;
  // Required keys.
  for (const char* k :
       {"mold", "start2d", "base2d", "sweep2d", "start3d", "base-normal", "sweep3d"})
    if (!get(k))
      return Error{where + "missing required " + (where.empty() ? "option --" : "key '") + k +
                   (where.empty() ? "" : "'")};
  if (need_output && !get("output"))
    return Error{where + "missing the output folder (" +
                 (where.empty() ? "-o DIR" : "key 'output'") + ")"};
  job.mold = resolve("mold", *one("mold"));
  if (get("faces")) {
    if (get("face"))
      return Error{name("faces") + ": give either " + name("face") + " or " + name("faces") +
                   ", not both"};
    const std::string list = *one("faces");
    if (list == "all") {
      job.all_faces = true;
    } else {
      std::stringstream ss(list);
      std::string item;
      while (std::getline(ss, item, ',')) {
        auto f = parse_int(item, name("faces"), 0, 1 << 30);
        if (!f) return f.error();
        if (std::find(job.faces.begin(), job.faces.end(), *f) != job.faces.end())
          return Error{name("faces") + ": face " + std::to_string(*f) + " is listed twice"};
        job.faces.push_back(*f);
      }
      if (job.faces.empty())
        return Error{name("faces") + ": '" + list + "' lists no face (indices, or all)"};
    }
  }
  if (auto f = parse_int(*one("face"), name("face"), 0, 1 << 30); f)
    job.face = *f;
  else
    return f.error();
  job.format = one("format").value_or("");
  if (auto b = parse_bool(*one("flip-normal"), name("flip-normal")); b)
    job.flip_normal = *b;
  else
    return b.error();

  auto& ply = job.problem.ply;
  const auto sp = one("spacing"), sw = one("spacing-weft"), sv = one("spacing-warp");
  if (!sp && !(sw && sv))
    return Error{where + "missing the spacing (" +
                 (where.empty() ? "--spacing D" : "key 'spacing'") + ")"};
  double d = 0;
  if (sp) {
    auto x = parse_number(*sp, name("spacing"));
    if (!x) return x.error();
    d = *x;
  }
  ply.d_weft = ply.d_warp = d;
  if (sw) {
    auto x = parse_number(*sw, name("spacing-weft"));
    if (!x) return x.error();
    ply.d_weft = *x;
  }
  if (sv) {
    auto x = parse_number(*sv, name("spacing-warp"));
    if (!x) return x.error();
    ply.d_warp = *x;
  }
  for (const auto& [k, v] : {std::pair{"spacing", sp ? d : 1.0},
                             {"spacing-weft", ply.d_weft},
                             {"spacing-warp", ply.d_warp}})
    if (!(v > 0.0)) return Error{name(k) + ": the spacing must be positive"};
  if (auto r = one("ply")) {
    auto v = parse_vec<2>(*r, name("ply"));
    if (!v) return v.error();
    if (!(v->x() > 0 && v->y() > 0)) return Error{name("ply") + ": W and H must be positive"};
    ply.rect = *v;
  }
  if (auto v = parse_vec<2>(*one("start2d"), name("start2d")); v)
    ply.start = *v;
  else
    return v.error();
  if (auto v = parse_vec<2>(*one("base2d"), name("base2d")); v)
    ply.base_dir = *v;
  else
    return v.error();
  if (!(ply.base_dir.norm() > 0)) return Error{name("base2d") + ": the direction must be non-zero"};
  for (const auto& s : *get("sweep2d")) {
    auto v = parse_vec<2>(s, name("sweep2d"));
    if (!v) return v.error();
    ply.sweeps.push_back(*v);
  }
  if (auto v = parse_vec<3>(*one("start3d"), name("start3d")); v)
    job.problem.start = *v;
  else
    return v.error();
  if (auto v = parse_vec<3>(*one("base-normal"), name("base-normal")); v)
    job.problem.base_normal = *v;
  else
    return v.error();
  for (const auto& s : *get("sweep3d")) {
    auto v = parse_vec<3>(s, name("sweep3d"));
    if (!v) return v.error();
    job.problem.sweeps.push_back(*v);
  }
  if (ply.sweeps.size() > 2) return Error{name("sweep2d") + ": at most two sweep directions"};
  if (ply.sweeps.size() != job.problem.sweeps.size())
    return Error{where + "give one 3D sweep direction per 2D sweep direction (" +
                 std::to_string(ply.sweeps.size()) + " 2D, " +
                 std::to_string(job.problem.sweeps.size()) + " 3D)"};
  // As Ply::create checks them (drape() would refuse them later, without the option's name).
  for (std::size_t k = 0; k < ply.sweeps.size(); ++k)
    if (auto st = check_sweep_direction(ply.base_dir, ply.sweeps[k], k, job.drape.tol); !st) {
      Error e = st.error();
      e.input = name("sweep2d");
      return e;
    }
  for (const char* k : {"start3d", "base-normal", "sweep3d", "sweep2d", "lock-angle"})
    job.input_names[k] = name(k);

  // The material: its warning and limit angles are the defaults of --warn-angle and
  // --lock-angle.
  if (auto f = one("materials")) job.materials_file = resolve("materials", *f);
  auto table =
      job.materials_file.empty() ? builtin_materials() : load_materials(job.materials_file);
  if (!table)
    return Error{(job.materials_file.empty() ? "" : name("materials") + ": ") +
                 exporters::describe(table.error())};
  job.material = *one("material");
  auto material = find_material(*table, job.material);
  if (!material) return Error{name("material")}.because(material.error());
  job.material_label = material->label;
  job.lock_angle_deg = material->limit_deg;
  if (auto l = one("lock-angle")) {
    auto x = parse_number(*l, name("lock-angle"));
    if (!x) return x.error();
    job.lock_angle_deg = *x;
  }
  if (!(job.lock_angle_deg > 0 && job.lock_angle_deg <= 90))
    return Error{name("lock-angle") + ": must be in (0, 90] degrees"};
  job.drape.lock_angle = job.lock_angle_deg * kDegToRad;
  job.warn_angle_deg =
      std::min(material->warning_deg, std::max(0.0, job.lock_angle_deg - kWarnBelowLockDeg));
  if (auto w = one("warn-angle")) {
    auto x = parse_number(*w, name("warn-angle"));
    if (!x) return x.error();
    if (!(*x >= 0 && *x <= 90)) return Error{name("warn-angle") + ": must be in [0, 90] degrees"};
    job.warn_angle_deg = *x;
  }
  job.ply_name = *one("ply-name");
  if (auto x = parse_number(*one("ply-angle"), name("ply-angle")); x) {
    if (!(*x >= -180 && *x <= 180))
      return Error{name("ply-angle") + ": must be in [-180, 180] degrees"};
    job.ply_angle_deg = *x;
  } else {
    return x.error();
  }
  if (auto x = parse_number(*one("tolerance"), name("tolerance")); x)
    job.tolerance_rel = *x;
  else
    return x.error();
  if (!(job.tolerance_rel > 0 && job.tolerance_rel < 1))
    return Error{name("tolerance") + ": must be in (0, 1)"};
  job.drape.tol.newton_residual_rel = job.tolerance_rel;
  if (auto x = parse_int(*one("max-iterations"), name("max-iterations"), 1, 10000); x)
    job.max_iterations = *x;
  else
    return x.error();
  job.drape.tol.newton_max_iterations = job.max_iterations;
  const std::string g = *one("guess");
  bool known = false;
  for (GuessRule r : {GuessRule::kExtrapolated, GuessRule::kPaper, GuessRule::kParallelogram})
    if (g == to_string(r)) {
      job.drape.guess = r;
      known = true;
    }
  if (!known)
    return Error{name("guess") + ": '" + g + "' must be extrapolated, paper or parallelogram"};
  if (auto x = parse_number(*one("max-nodes"), name("max-nodes")); x) {
    if (!(*x >= 1 && *x == std::floor(*x)))
      return Error{name("max-nodes") + ": must be a positive integer"};
    job.drape.max_nodes = static_cast<std::uint64_t>(*x);
  } else
    return x.error();
  if (auto o = one("output")) job.outdir = resolve("output", *o);
  const std::string outs = one("outputs").value_or(all_outputs());
  std::stringstream ss(outs);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    if (!exporters::find_exporter(item))
      return Error{name("outputs") + ": unknown output '" + item +
                   "' (known: " + exporters::supported_keys() + ")"};
    job.outputs.push_back(item);
  }
  if (auto x = parse_int(*one("curve-degree"), name("curve-degree"), 1, 3); x) {
    if (*x == 2) return Error{name("curve-degree") + ": must be 1 or 3"};
    job.curve_degree = *x;
  } else
    return x.error();
  if (auto v = parse_vec<3>(*one("view"), name("view")); v) {
    if (!(v->norm() > 0)) return Error{name("view") + ": the direction must be non-zero"};
    job.view = *v;
  } else
    return v.error();
  if (auto b = parse_bool(*one("dxf-threads"), name("dxf-threads")); b)
    job.dxf_threads = *b;
  else
    return b.error();
  if (auto m = one("min-width")) {
    auto x = parse_number(*m, name("min-width"));
    if (!x) return x.error();
    if (!(*x >= 0)) return Error{name("min-width") + ": must be >= 0 (0: the exact outline)"};
    job.min_width = *x;
  }
  job.scene = raw.origin == "command line" ? "" : raw.origin;
  return job;
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
}  // namespace

std::string dump_scene(const DrapeJob& job) {
  std::map<std::string, std::vector<std::string>> v;
  const auto& p = job.problem;
  v["mold"] = {job.mold};
  if (job.all_faces) {
    v["faces"] = {"all"};
  } else if (!job.faces.empty()) {
    std::string list;
    for (int f : job.faces) list += (list.empty() ? "" : ",") + std::to_string(f);
    v["faces"] = {list};
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
  v["base2d"] = {fmt(p.ply.base_dir)};
  for (const auto& w : p.ply.sweeps) v["sweep2d"].push_back(fmt(w));
  v["start3d"] = {fmt(p.start)};
  v["base-normal"] = {fmt(p.base_normal)};
  for (const auto& w : p.sweeps) v["sweep3d"].push_back(fmt(w));
  v["material"] = {job.material};
  if (!job.materials_file.empty()) v["materials"] = {job.materials_file};
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
  v["curve-degree"] = {std::to_string(job.curve_degree)};
  v["view"] = {fmt(job.view)};
  v["dxf-threads"] = {job.dxf_threads ? "true" : "false"};
  // The effective value: the one given, or the default the flat pattern takes.
  v["min-width"] = {fmt(FlatPatternOptions{job.min_width}.width_for(p.ply))};
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

Result<MoldSurface> load_surface(const DrapeJob& job, exporters::RunInfo* run_out) {
  exporters::RunInfo scratch;
  exporters::RunInfo& run = run_out ? *run_out : scratch;
  std::optional<MoldSurface> surface;
  const bool builtin = job.mold.rfind("builtin:", 0) == 0;
  std::optional<std::pair<std::string, std::map<std::string, double>>> spec;
  if (builtin) {
    auto sp = parse_builtin_spec(job.mold.substr(8));
    if (!sp) return sp.error();
    spec = std::move(sp).value();
    if (job.face != 0 || !job.faces.empty())
      return Error{job.mold + ": a built-in mold is draped whole (no --face or --faces list)"};
  }
  const bool shell =
      builtin ? is_builtin_shell(spec->first) : (job.all_faces || !job.faces.empty());
  if (shell) {
    ShellData data;
    if (builtin) {
      auto sd = builtin_shell(spec->first, spec->second);
      if (!sd) return sd.error();
      data = std::move(sd).value();
      run.mold_unit = "millimetre";
      for (std::size_t k = 0; k < data.faces.size(); ++k) {
        FaceInfo fi;
        fi.index = static_cast<int>(k);
        fi.name = data.faces[k].name;
        fi.kind = "builtin:" + spec->first;
        run.faces_info.push_back(fi);
      }
    } else {
      importers::ImportOptions io;
      io.format = job.format;
      io.tolerances = job.drape.tol;
      auto file = importers::open_mold(job.mold, io);
      if (!file) return file.error();
      const std::vector<int> indices = job.all_faces ? (*file)->all_faces() : job.faces;
      auto sd = (*file)->convert_shell(indices);
      if (!sd) return sd.error();
      data = std::move(sd).value();
      for (int i : indices) {
        auto info = (*file)->describe(i);
        if (!info) return info.error();
        run.faces_info.push_back(*info);
      }
      run.mold_unit = (*file)->summary().unit;
      run.warnings = (*file)->summary().warnings;
    }
    if (job.flip_normal)
      for (auto& f : data.faces) f.reversed = !f.reversed;
    const std::size_t n = data.faces.size();
    const std::vector<int> sources = data.source_faces;
    auto sh = MoldSurface::from_shell(std::move(data), job.drape.tol);
    if (!sh) return Error{job.mold}.because(sh.error());
    for (std::size_t k = 0; k < n; ++k)
      run.faces.push_back(run.faces_info.size() > k ? run.faces_info[k].index
                          : sources.empty()         ? static_cast<int>(k)
                                                    : sources[k]);
    surface = std::move(sh).value();
  } else {
    FaceData data;
    if (builtin) {
      auto fd = builtin_mold(spec->first, spec->second);
      if (!fd) return fd.error();
      data = std::move(fd).value();
      FaceInfo fi;
      fi.name = data.name;
      fi.kind = "builtin:" + spec->first;
      run.faces_info.push_back(fi);
      run.mold_unit = "millimetre";
    } else {
      importers::ImportOptions io;
      io.format = job.format;
      io.tolerances = job.drape.tol;
      auto file = importers::open_mold(job.mold, io);
      if (!file) return file.error();
      // Only this face is described and converted: the others are never listed.
      auto info = (*file)->describe(job.face);
      if (!info) return info.error();
      run.faces_info.push_back(*info);
      run.mold_unit = (*file)->summary().unit;
      run.warnings = (*file)->summary().warnings;
      auto fd = (*file)->convert_face(job.face);
      if (!fd) return fd.error();
      data = std::move(fd).value();
    }
    if (job.flip_normal) data.reversed = !data.reversed;
    auto face = MoldSurface::from_face(std::move(data), job.drape.tol);
    if (!face) return Error{job.mold + ": face " + std::to_string(job.face)}.because(face.error());
    run.faces.push_back(job.face);
    surface = std::move(face).value();
  }
  return std::move(*surface);
}

namespace {
// drape()'s input errors name the input by its scene key: as the option or the scene file's key
// its value came from ("--sweep3d", or "FILE: key 'sweep3d'").
Error with_input_name(const DrapeJob& job, Error e) {
  if (e.input.empty()) return e;
  const auto n = job.input_names.find(e.input);
  e.input = n != job.input_names.end() ? n->second : "--" + e.input;
  return e;
}
}  // namespace

Result<JobOutcome> run_job(const DrapeJob& job, const std::atomic<bool>* cancel, bool progress) {
  const auto t0 = std::chrono::steady_clock::now();
  auto ms_since = [](auto t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  exporters::RunInfo run;
  run.mold = job.mold;
  run.flip_normal = job.flip_normal;
  run.tolerance_rel = job.tolerance_rel;
  run.max_iterations = job.max_iterations;
  run.lock_angle_deg = job.lock_angle_deg;
  run.warn_angle_deg = job.warn_angle_deg;
  run.guess = to_string(job.drape.guess);
  run.max_nodes = job.drape.max_nodes;
  run.ply_name = job.ply_name;
  run.material = job.material;
  run.outputs = job.outputs;
  auto loaded = load_surface(job, &run);
  if (!loaded) return loaded.error();
  const MoldSurface surface = std::move(loaded).value();
  run.import_ms = ms_since(t0);

  DrapeOptions opt = job.drape;
  opt.cancel = cancel;
  const bool tty = progress && ::isatty(2);
  if (tty) {
    opt.progress = [](std::uint64_t n) {
      std::cerr << "\rplyfit: " << n << " nodes solved" << std::flush;
    };
  }
  auto res = drape(surface, job.problem, opt);
  if (tty) std::cerr << "\r\033[K" << std::flush;
  if (!res) return with_input_name(job, res.error());
  if (cancel && cancel->load()) return Error{"cancelled"};
  run.drape_ms = res->drape_ms;
  FlatPatternOptions fo;
  fo.min_width = job.min_width;
  const FlatPattern flat = flat_pattern(surface, *res, fo);
  exporters::ExportOptions eo;
  eo.warn_shear = job.warn_angle_deg * kDegToRad;
  eo.curve_degree = job.curve_degree;
  eo.view = job.view;
  eo.dxf_threads = job.dxf_threads;
  eo.ply_angle_deg = job.ply_angle_deg;
  eo.material_label = job.material_label;
  eo.materials_file = job.materials_file;
  run.total_ms = ms_since(t0);
  const exporters::ExportContext ctx{job.problem, *res, surface, &flat, run, eo};
  if (!job.outdir.empty()) {
    if (auto s = exporters::write_outputs(ctx, job.outdir, job.outputs); !s) return s.error();
  }
  JobOutcome out;
  out.status = res->partial ? "partial" : "ok";
  out.mapped = res->metrics.nodes.mapped;
  const auto& m = res->metrics;
  out.shear_max_deg = m.shear_max / kDegToRad;
  out.metrics = m;
  out.face_area = surface.area();
  out.flat_outline_area = flat.cut_area;
  out.outline_coverage = out.face_area > 0 ? outline_surface_area(*res, flat) / out.face_area : 0.0;
  out.warnings = res->warnings;
  out.mold_warnings = run.warnings;
  for (const auto& k : job.outputs)
    if (const auto* e = exporters::find_exporter(k))
      for (const auto& f : e->files) out.files.push_back(f);
  out.total_ms = ms_since(t0);
  return out;
}

}  // namespace plyfit::cli

namespace plyfit::cli {

SearchScene search_scene(const DrapeJob& job) {
  return {job.problem, job.drape, job.min_width};
}

DrapeJob candidate_job(const DrapeJob& scene, const MoldSurface& face, const OptimizeResult& r,
                       const Candidate& c) {
  DrapeJob job = scene;
  if (auto pb = candidate_problem(search_scene(scene), face, r, c)) job.problem = *pb;
  return job;
}

}  // namespace plyfit::cli
