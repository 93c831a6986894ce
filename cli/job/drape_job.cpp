// make_job: a drape job from raw values, read step by step (the mold, the ply, the start, the
// material, the numerics, the outputs), each value checked where it is read so that an error
// blames its key.

#include "job/drape_job.hpp"

#include "job/materials.hpp"

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/ply.hpp>
#include <plyfit/kernel/splice.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>
#include <tuple>

namespace fs = std::filesystem;

namespace plyfit::cli {

namespace {

// Without --warn-angle, cells are flagged at least this far (degrees) below the lock angle.
constexpr double kWarnBelowLockDeg = 5.0;
// Largest face index accepted (a file with more faces does not exist).
constexpr long kMaxFace = 1L << 30;

// A path value relative to the folder of where it came from (the scene file's, or the
// working directory for a flag); built-in molds and absolute paths as they are.
std::string resolve(const Options& o, const std::string& key, const std::string& p) {
  const auto d = o.raw().dirs.find(key);
  if (p.rfind("builtin:", 0) == 0 || fs::path(p).is_absolute() || d == o.raw().dirs.end() ||
      d->second.empty())
    return p;
  return (fs::path(d->second) / p).lexically_normal().string();
}

// The start keys of the paper, which a seed replaces (start2d stays: the seed's place in the
// ply).
constexpr const char* kPaperStartKeys[] = {"base2d", "sweep2d", "start3d", "base-normal",
                                           "sweep3d"};

Status required_keys(const Options& o, bool need_output) {
  if (o.given("seed")) {
    for (const char* k : kPaperStartKeys)
      if (o.given(k)) return Error{ErrorCode::kOptionsExclusive, k, {"seed", std::string(k)}};
    if (!o.given("mold")) return o.missing("mold");
  } else {
    for (const char* k :
         {"mold", "start2d", "base2d", "sweep2d", "start3d", "base-normal", "sweep3d"})
      if (!o.given(k)) return o.missing(k);
  }
  if (need_output && !o.given("output")) return o.missing("output");
  return ok_status();
}

// --faces: "all" or a list of distinct indices.
Status read_faces(const Options& o, DrapeJob& job) {
  if (o.given("face")) return Error{ErrorCode::kOptionsExclusive, "faces", {"face", "faces"}};
  const std::string list = *o.text("faces");
  if (list == "all") {
    job.all_faces = true;
    return ok_status();
  }
  if (list == "connected") {
    job.connected_faces = true;
    if (!o.given("seed") && !o.given("faces-at"))
      return Error{ErrorCode::kConnectedNeedsPoint, "faces"};
    auto crease = o.number_in("max-crease", {0, 180, true, false, "degrees"});
    if (!crease) return crease.error();
    job.max_crease_deg = *crease;
    return ok_status();
  }
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    auto f = parse_integer(item, "faces", 0, kMaxFace);
    if (!f) return f.error();
    if (std::find(job.faces.begin(), job.faces.end(), *f) != job.faces.end())
      return Error{ErrorCode::kListedTwice, "faces", {item}};
    job.faces.push_back(static_cast<int>(*f));
  }
  if (job.faces.empty()) return Error{ErrorCode::kEmptyList, "faces", {list}};
  return ok_status();
}

Status read_mold(const Options& o, DrapeJob& job) {
  job.mold = resolve(o, "mold", *o.text("mold"));
  if (o.given("faces"))
    if (auto st = read_faces(o, job); !st) return st;
  if (o.given("max-crease") && !job.connected_faces)
    return Error{ErrorCode::kOptionWithout, "max-crease", {"max-crease", "faces = connected"}};
  if (o.given("faces-at")) {
    for (const char* k : {"face", "faces"})
      if (o.given(k) && !job.connected_faces)
        return Error{ErrorCode::kOptionsExclusive, k, {"faces-at", std::string(k)}};
    auto p = o.vec3("faces-at");
    if (!p) return p.error();
    job.faces_at = *p;
  }
  auto face = o.integer("face", 0, kMaxFace);
  if (!face) return face.error();
  job.face = static_cast<int>(*face);
  job.format = o.text("format").value_or("");
  auto flip = o.flag("flip-normal");
  if (!flip) return flip.error();
  job.flip_normal = *flip;
  return ok_status();
}

// The thread spacings: --spacing for both, or --spacing-weft and --spacing-warp.
Status read_spacing(const Options& o, PlySpec& ply) {
  const bool sp = o.given("spacing"), sw = o.given("spacing-weft"), sv = o.given("spacing-warp");
  if (!sp && !(sw && sv)) return o.missing("spacing");
  double d = 0;
  if (sp) {
    auto x = o.number("spacing");
    if (!x) return x.error();
    d = *x;
  }
  ply.d_weft = ply.d_warp = d;
  for (auto [key, given, to] :
       {std::tuple{"spacing-weft", sw, &ply.d_weft}, std::tuple{"spacing-warp", sv, &ply.d_warp}}) {
    if (!given) continue;
    auto x = o.number(key);
    if (!x) return x.error();
    *to = *x;
  }
  for (const auto& [key, which, v] : {std::tuple{"spacing", "thread", sp ? d : 1.0},
                                      std::tuple{"spacing-weft", "weft", ply.d_weft},
                                      std::tuple{"spacing-warp", "warp", ply.d_warp}})
    if (!(v > 0.0)) return Error{ErrorCode::kSpacingNotPositive, key, {std::string(which), v}};
  return ok_status();
}

// The ply rectangle and the 2D initial conditions (start, base path, sweeps).
Status read_ply(const Options& o, PlySpec& ply) {
  if (o.given("ply")) {
    auto v = o.vec2("ply");
    if (!v) return v.error();
    if (!(v->x() > 0 && v->y() > 0)) return Error{ErrorCode::kPlySizeNotPositive, "ply"};
    ply.rect = *v;
  }
  if (o.given("start2d")) {
    auto start = o.vec2("start2d");
    if (!start) return start.error();
    ply.start = *start;
  }
  if (o.given("seed")) return ok_status();  // directions follow from the seed on the mold
  auto base = o.vec2("base2d");
  if (!base) return base.error();
  if (!(base->norm() > 0)) return Error{ErrorCode::kBaseDirZero, "base2d"};
  ply.base_dir = *base;
  for (const auto& s : o.all("sweep2d")) {
    auto v = parse_vec2(s, "sweep2d");
    if (!v) return v.error();
    ply.sweeps.push_back(*v);
  }
  return ok_status();
}

// The 3D initial conditions, and the sweeps checked as Ply::create checks them (drape() would
// refuse them later, after the import).
Status read_start(const Options& o, DrapeJob& job) {
  auto rosette = o.vec3("rosette");
  if (!rosette) return rosette.error();
  if (!(rosette->norm() > 0)) return Error{ErrorCode::kRosetteZero, "rosette"};
  job.rosette = *rosette;
  job.rosette_given = o.given("rosette");
  const std::string curve = *o.text("seed-curve");
  if (curve == "geodesic") {
    job.problem.seed_curve = SeedCurve::kGeodesic;
  } else if (curve != "plane") {
    CurveFileSpec spec = parse_curve_spec(curve);
    if (std::filesystem::path(spec.path).extension().empty())
      return Error{
          ErrorCode::kUnknownValue, "seed-curve", {curve, std::string("plane, geodesic, FILE")}};
    spec.path = resolve(o, "seed-curve", spec.path);
    job.seed_curve_file = spec;
    job.problem.seed_curve = SeedCurve::kCurve;
  }
  if (o.given("seed")) {
    auto seed = o.vec3("seed");
    if (!seed) return seed.error();
    job.seed = *seed;
    return ok_status();
  }
  auto start = o.vec3("start3d");
  if (!start) return start.error();
  job.problem.start = *start;
  auto normal = o.vec3("base-normal");
  if (!normal) return normal.error();
  job.problem.base_normal = *normal;
  for (const auto& s : o.all("sweep3d")) {
    auto v = parse_vec3(s, "sweep3d");
    if (!v) return v.error();
    job.problem.sweeps.push_back(*v);
  }
  const auto& ply = job.problem.ply;
  if (ply.sweeps.size() > 2) return Error{ErrorCode::kTooManySweeps, "sweep2d"};
  if (ply.sweeps.size() != job.problem.sweeps.size())
    return Error{ErrorCode::kSweepCountMismatch,
                 "sweep3d",
                 {static_cast<std::int64_t>(ply.sweeps.size()),
                  static_cast<std::int64_t>(job.problem.sweeps.size())}};
  for (std::size_t k = 0; k < ply.sweeps.size(); ++k)
    if (auto st = check_sweep_direction(ply.base_dir, ply.sweeps[k], k, job.drape.tol); !st)
      return st;
  return ok_status();
}

// The ply's boundary: its curve file (relative to the scene file) and offset; the darts' files.
Status read_boundary(const Options& o, DrapeJob& job) {
  if (auto f = o.text("boundary"); f && !f->empty()) {
    CurveFileSpec spec = parse_curve_spec(*f);
    spec.path = resolve(o, "boundary", spec.path);
    job.boundary = spec;
  }
  for (const auto& f : o.all("dart")) {
    CurveFileSpec spec = parse_curve_spec(f);
    spec.path = resolve(o, "dart", spec.path);
    job.darts.push_back(spec);
  }
  if (const std::optional<std::string> automatic = o.text("darts"); automatic) {
    job.darts_auto = automatic->compare("auto") == 0;
    if (!job.darts_auto && automatic->compare("none") != 0)
      return Error{ErrorCode::kUnknownValue, "darts", {*automatic, std::string("auto, none")}};
  }
  auto offset = o.number("boundary-offset");
  if (!offset) return offset.error();
  job.boundary_offset = *offset;
  return ok_status();
}

// The material: its warning and limit angles are the defaults of --warn-angle and
// --lock-angle.
Status read_material(const Options& o, DrapeJob& job) {
  if (auto f = o.text("materials")) job.exports.materials_file = resolve(o, "materials", *f);
  auto table = job.exports.materials_file.empty() ? builtin_materials()
                                                  : load_materials(job.exports.materials_file);
  if (!table) {
    Error e = table.error();
    if (!job.exports.materials_file.empty()) e.in("materials");
    return e;
  }
  job.material = *o.text("material");
  auto material = find_material(*table, job.material);
  if (!material) return Error(material.error()).in("material");
  job.exports.material_label = material->label;
  if (material->roll_width > 0.0) job.roll_width = material->roll_width;
  job.lock_angle_deg = material->limit_deg;
  if (o.given("lock-angle")) {
    auto x = o.number("lock-angle");
    if (!x) return x.error();
    job.lock_angle_deg = *x;
  }
  if (!(job.lock_angle_deg > 0 && job.lock_angle_deg <= 90))
    return Error{ErrorCode::kLockAngleRange, "lock-angle"};
  job.drape.lock_angle = job.lock_angle_deg * kDegToRad;
  job.warn_angle_deg =
      std::min(material->warning_deg, std::max(0.0, job.lock_angle_deg - kWarnBelowLockDeg));
  if (o.given("warn-angle")) {
    auto x = o.number_in("warn-angle", {0, 90, false, false, "degrees"});
    if (!x) return x.error();
    job.warn_angle_deg = *x;
  }
  job.ply_name = *o.text("ply-name");
  auto angle = o.number_in("ply-angle", {-180, 180, false, false, "degrees"});
  if (!angle) return angle.error();
  job.ply_angle_deg = *angle;
  return ok_status();
}

// The splices: --roll-width (over the material's) and --splice-overlap, checked against the
// spacing now rather than after the drape.
Status read_splices(const Options& o, DrapeJob& job) {
  if (o.given("roll-width")) {
    auto w = o.number("roll-width");
    if (!w) return w.error();
    job.roll_width = *w;
  }
  auto overlap = o.number("splice-overlap");
  if (!overlap) return overlap.error();
  job.splice_overlap = *overlap;
  if (!job.roll_width) return ok_status();
  SpliceOptions so;
  so.roll_width = *job.roll_width;
  so.overlap = job.splice_overlap;
  return check_splice_options(so, job.problem.ply.d_weft);
}

Status read_numerics(const Options& o, DrapeJob& job) {
  auto tol = o.number_in("tolerance", {0, 1, true, true, ""});
  if (!tol) return tol.error();
  job.tolerance_rel = *tol;
  job.drape.tol.newton_residual_rel = job.tolerance_rel;
  auto its = o.integer("max-iterations", 1, 10000);
  if (!its) return its.error();
  job.max_iterations = static_cast<int>(*its);
  job.drape.tol.newton_max_iterations = job.max_iterations;
  const std::string g = *o.text("guess");
  bool known = false;
  for (GuessRule r : {GuessRule::kExtrapolated, GuessRule::kPaper, GuessRule::kParallelogram})
    if (g == to_string(r)) {
      job.drape.guess = r;
      known = true;
    }
  if (!known)
    return Error{
        ErrorCode::kUnknownValue, "guess", {g, std::string("extrapolated, paper, parallelogram")}};
  auto nodes = o.number("max-nodes");
  if (!nodes) return nodes.error();
  if (!(*nodes >= 1 && *nodes == std::floor(*nodes)))
    return Error{ErrorCode::kNotAnInteger, "max-nodes", {*o.text("max-nodes"), std::int64_t{1}}};
  job.drape.max_nodes = static_cast<std::uint64_t>(*nodes);
  return ok_status();
}

Status read_outputs(const Options& o, DrapeJob& job) {
  if (auto out = o.text("output")) job.outdir = resolve(o, "output", *out);
  std::string all;
  for (const auto& e : exporters::registry()) all += (all.empty() ? "" : ",") + e.key;
  for (const auto& item : split_list(o.text("outputs").value_or(all))) {
    if (!exporters::find_exporter(item))
      return Error{ErrorCode::kUnknownValue, "outputs", {item, exporters::supported_keys()}};
    job.outputs.push_back(item);
  }
  auto degree = o.integer("curve-degree", 1, 3);
  if (!degree) return degree.error();
  if (*degree == 2)
    return Error{ErrorCode::kUnknownValue, "curve-degree", {*o.text("curve-degree"), "1, 3"}};
  job.exports.curve_degree = static_cast<int>(*degree);
  auto view = o.vec3("view");
  if (!view) return view.error();
  if (!(view->norm() > 0)) return Error{ErrorCode::kZeroVector, "view", {*o.text("view")}};
  job.exports.view = *view;
  auto threads = o.flag("dxf-threads");
  if (!threads) return threads.error();
  job.exports.dxf_threads = *threads;
  if (o.given("min-width")) {
    auto w =
        o.number_in("min-width", {0, std::numeric_limits<double>::infinity(), false, false, ""});
    if (!w) return w.error();
    job.min_width = *w;
  }
  return ok_status();
}

}  // namespace

Result<DrapeJob> make_job(const RawOptions& raw, bool need_output) {
  const Options o(raw, drape_options());
  DrapeJob job;
  job.name_input = input_namer(raw, drape_options());
  const std::function<Status()> steps[] = {
      [&] { return required_keys(o, need_output); },
      [&] { return read_mold(o, job); },
      [&] { return read_spacing(o, job.problem.ply); },
      [&] { return read_ply(o, job.problem.ply); },
      [&] { return read_start(o, job); },
      [&] { return read_boundary(o, job); },
      [&] { return read_material(o, job); },
      [&] { return read_splices(o, job); },
      [&] { return read_numerics(o, job); },
      [&] { return read_outputs(o, job); },
  };
  for (const auto& step : steps)
    if (auto st = step(); !st) return st.error();
  job.scene = raw.origin == kCommandLine ? "" : raw.origin;
  return job;
}

}  // namespace plyfit::cli
