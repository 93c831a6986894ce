// report.json: inputs echoed, status, node counts, areas, thread angles, shear energy, the
// paper's thread angles and energy (eq. 12), residuals, timings. nlohmann-json writes numbers in
// their shortest exact form, so equal inputs give equal bytes except for the timing_ms fields.

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/warnings_json.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/splice.hpp>

#include "net_util.hpp"
#include "plugins.hpp"
#include "render/text.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

namespace plyfit::exporters {

namespace {

using detail::kRadToDeg;

nlohmann::json vec(const Vec2& v) {
  return nlohmann::json::array({v.x(), v.y()});
}
nlohmann::json vec(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}
template <typename V>
nlohmann::json vecs(const std::vector<V>& vs) {
  nlohmann::json out = nlohmann::json::array();
  for (const V& v : vs) out.push_back(vec(v));
  return out;
}

// The file's unit in one spelling: the importers name it "millimetre" (STEP), "millimetre
// (MM)" (IGES: the name of its unit flag and the file's own text), built-in molds "mm";
// report.json says "millimetre" for all three. Other known units likewise: the name,
// lower-case, without the file's own text, abbreviations and American spellings written out.
// Anything else (e.g. "unspecified (millimetre assumed)") is kept, lower-case.
std::string unit_name(const std::string& given) {
  auto lower = [](std::string t) {
    std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
    return t;
  };
  const std::string u = lower(given.substr(0, given.find(" (")));
  static const std::pair<const char*, const char*> kSpellings[] = {{"mm", "millimetre"},
                                                                   {"millimeter", "millimetre"},
                                                                   {"millimetre", "millimetre"},
                                                                   {"cm", "centimetre"},
                                                                   {"centimeter", "centimetre"},
                                                                   {"centimetre", "centimetre"},
                                                                   {"m", "metre"},
                                                                   {"meter", "metre"},
                                                                   {"metre", "metre"},
                                                                   {"km", "kilometre"},
                                                                   {"kilometer", "kilometre"},
                                                                   {"kilometre", "kilometre"},
                                                                   {"in", "inch"},
                                                                   {"inches", "inch"},
                                                                   {"inch", "inch"},
                                                                   {"ft", "foot"},
                                                                   {"feet", "foot"},
                                                                   {"foot", "foot"},
                                                                   {"mile", "mile"},
                                                                   {"mil", "mil"},
                                                                   {"um", "micron"},
                                                                   {"micrometre", "micron"},
                                                                   {"micrometer", "micron"},
                                                                   {"micron", "micron"},
                                                                   {"microinch", "microinch"}};
  for (const auto& [from, to] : kSpellings)
    if (u == from) return to;
  return lower(given);
}

// A face by its index in the mold file: the k-th face draped.
int file_index(const ExportContext& ctx, std::size_t k) {
  return k < ctx.run.faces.size() ? ctx.run.faces[k] : static_cast<int>(k);
}

// The inputs of the run, echoed.
nlohmann::json inputs_json(const ExportContext& ctx) {
  using nlohmann::json;
  const DrapeProblem& p = ctx.problem;
  json in;
  in["mold"] = ctx.run.mold;
  if (ctx.surface.face_count() > 1)
    in["faces"] = ctx.run.faces;
  else
    in["face"] = ctx.run.faces.empty() ? 0 : ctx.run.faces.front();
  in["flip_normal"] = ctx.run.flip_normal;
  in["spacing_weft"] = p.ply.d_weft;
  in["spacing_warp"] = p.ply.d_warp;
  in["ply"] = p.ply.rect ? vec(*p.ply.rect) : json(nullptr);
  in["start2d"] = vec(p.ply.start);
  in["base2d"] = vec(p.ply.base_dir);
  in["sweep2d"] = vecs(p.ply.sweeps);
  in["start3d"] = vec(p.start);
  in["seed_curve"] = p.seed_curve == SeedCurve::kCurve ? "file" : to_string(p.seed_curve);
  if (p.seed_curve == SeedCurve::kCurve) in["seed_curve_file"] = ctx.run.seed_curve_file;
  in["base_normal"] = vec(p.base_normal);
  in["sweep3d"] = vecs(p.sweeps);
  in["lock_angle_deg"] = ctx.run.lock_angle_deg;
  in["tolerance"] = ctx.run.tolerance_rel;
  in["max_iterations"] = ctx.run.max_iterations;
  in["guess"] = ctx.run.guess;
  in["max_nodes"] = ctx.run.max_nodes;
  in["warn_angle_deg"] = ctx.run.warn_angle_deg;  // as given: not through radians and back
  in["ply_name"] = ctx.run.ply_name;
  in["ply_angle_deg"] = ctx.options.ply_angle_deg;
  in["material"] = ctx.run.material;
  in["material_label"] = render::material_label(ctx);
  in["materials"] = ctx.options.materials_file;
  in["curve_degree"] = ctx.options.curve_degree;
  in["view"] = vec(ctx.options.view);
  in["dxf_threads"] = ctx.options.dxf_threads;
  in["outputs"] = ctx.run.outputs;
  return in;
}

// The ply as laid: how it was defined (seed, rosette, angle, or the start keys) and its frame
// at the start, measured on the drape.
nlohmann::json boundary_json(const std::optional<BoundaryReport>& b) {
  using nlohmann::json;
  if (!b) return json(nullptr);
  json loops = json::array();
  for (std::size_t k = 0; k < b->loops.size(); ++k)
    loops.push_back({{"points", b->loops[k].size()}, {"length", b->lengths[k]}});
  return {{"source", b->source}, {"offset", b->offset}, {"area", b->area}, {"loops", loops}};
}

nlohmann::json ply_json(const PlyReport& p) {
  using nlohmann::json;
  return {{"defined_by", p.from_seed ? "seed" : "start"},
          {"seed", p.from_seed ? vec(p.seed) : json(nullptr)},
          {"rosette", vec(p.rosette)},
          {"angle_deg", p.angle_deg},
          {"laid_angle_deg", p.laid_angle_deg},
          {"seed_curve", p.seed_curve},
          {"point", vec(p.point)},
          {"normal", vec(p.normal)},
          {"zero_direction", vec(p.zero)},
          {"fibre_direction", vec(p.warp)},
          {"weft_direction", vec(p.weft)},
          {"boundary", boundary_json(p.boundary)}};
}

// The mold: its unit, the surface draped (one face, or a shell's faces together), then face by
// face, the largest crease angle and the import warnings.
nlohmann::json mold_json(const ExportContext& ctx) {
  using nlohmann::json;
  const DrapeMetrics& m = ctx.result.metrics;
  const bool shell = ctx.surface.face_count() > 1;
  json face;
  const FaceInfo none;
  const FaceInfo& first = ctx.run.faces_info.empty() ? none : ctx.run.faces_info.front();
  face["name"] = shell ? "" : first.name;
  face["kind"] = shell ? "shell" : first.kind;
  face["area"] = ctx.surface.area();
  const BBox3 box = ctx.surface.bbox();
  face["bbox"] = {{"min", vec(box.min)}, {"max", vec(box.max)}};
  json faces = json::array();
  for (std::size_t k = 0; k < m.faces.size(); ++k) {
    const FaceInfo& fi = k < ctx.run.faces_info.size() ? ctx.run.faces_info[k] : none;
    faces.push_back({{"index", file_index(ctx, k)},
                     {"name", fi.name},
                     {"kind", fi.kind},
                     {"area", m.faces[k].area},
                     {"nodes_mapped", m.faces[k].mapped},
                     {"rounding", ctx.surface.face_rounding(static_cast<std::int32_t>(k))},
                     {"covered_area", m.faces[k].covered_area}});
  }
  return {{"unit", unit_name(ctx.run.mold_unit)},
          {"face", face},
          {"faces", faces},
          {"crease_angle_max_deg", m.crease_angle_max * kRadToDeg},
          {"warnings", warnings_json(ctx.run.warnings)}};
}

// Node counts by status, with the reasons of the failed, conflicting, shear-limit and
// overlapping ones.
nlohmann::json nodes_json(const DrapeMetrics& m) {
  nlohmann::json nodes = {{"mapped", m.nodes.mapped},           {"auxiliary", m.nodes.auxiliary},
                          {"outside", m.nodes.outside},         {"off_ply", m.nodes.off_ply},
                          {"shear_limit", m.nodes.shear_limit}, {"overlap", m.nodes.overlap},
                          {"failed", m.nodes.failed},           {"conflict", m.nodes.conflict},
                          {"path_end", m.nodes.path_end},       {"with_angle", m.angles}};
  for (const auto& [key, reasons] : {std::pair{"failed_reasons", &m.nodes.failed_reasons},
                                     std::pair{"conflict_reasons", &m.nodes.conflict_reasons},
                                     std::pair{"shear_limit_reasons", &m.nodes.shear_limit_reasons},
                                     std::pair{"overlap_reasons", &m.nodes.overlap_reasons}}) {
    nodes[key] = nlohmann::json::object();
    for (const auto& [why, count] : *reasons) nodes[key][why] = count;
  }
  return nodes;
}

// Thread angles, shear, the paper's metrics (eq. 12), residuals (the Newton floor also relative
// to the spacing `d`) and solver effort.
void add_metrics(nlohmann::json& j, const DrapeMetrics& m, double d) {
  j["area_mesh_points"] = m.area_mesh_points;
  j["flat_area"] = m.flat_area;
  j["surface_area"] = m.surface_area;
  j["coverage"] = m.coverage;
  j["thread_angle"] = {{"min", m.gamma_min},
                       {"max", m.gamma_max},
                       {"min_deg", m.gamma_min * kRadToDeg},
                       {"max_deg", m.gamma_max * kRadToDeg}};
  j["shear_max_deg"] = m.shear_max * kRadToDeg;
  j["shear_energy"] = m.shear_energy;
  j["paper_metrics"] = {{"gamma_min", m.paper.gamma_min},
                        {"gamma_max", m.paper.gamma_max},
                        {"energy", m.paper.energy},
                        {"gamma_min_deg", m.paper.gamma_min * kRadToDeg},
                        {"gamma_max_deg", m.paper.gamma_max * kRadToDeg},
                        {"shear_max_deg", m.paper.shear_max * kRadToDeg},
                        {"with_angle", m.paper.angles},
                        {"oriented_gamma_min", m.paper.oriented_gamma_min},
                        {"oriented_gamma_max", m.paper.oriented_gamma_max},
                        {"oriented_gamma_min_deg", m.paper.oriented_gamma_min * kRadToDeg},
                        {"oriented_gamma_max_deg", m.paper.oriented_gamma_max * kRadToDeg}};
  j["residual"] = {{"edge_length_max_rel", m.edge_length_max_rel},
                   {"surface_distance_max", m.surface_distance_max},
                   {"base_plane_max_rel", m.base_plane_max_rel},
                   {"solve_max_rel", m.solve_residual_max_rel},
                   {"newton_floor", m.newton_floor},
                   {"newton_floor_rel", d > 0.0 ? m.newton_floor / d : 0.0}};
  j["solver"] = {{"solves", m.solves},
                 {"mean_iterations", m.solves ? double(m.iterations) / m.solves : 0.0},
                 {"mean_evaluations", m.solves ? double(m.evaluations) / m.solves : 0.0}};
}

nlohmann::json loops_json(const std::vector<OutlineLoop>& outline) {
  nlohmann::json loops = nlohmann::json::array();
  for (const auto& l : outline) {
    nlohmann::json pts = nlohmann::json::array();
    for (const auto& q : l.points) pts.push_back(vec(q));
    loops.push_back(
        {{"hole", l.hole}, {"area", l.area}, {"perimeter", l.perimeter}, {"points", pts}});
  }
  return loops;
}

// The cut outline (what flat.dxf's cutter cuts) and the exact outline it was made from.
void add_flat_outline(nlohmann::json& j, const FlatPattern& fp) {
  j["flat_outline"] = {{"area", fp.cut_area},
                       {"perimeter", fp.cut_perimeter},
                       {"min_width", fp.min_width},
                       {"removed_area", fp.cut_removed_area},
                       {"added_area", fp.cut_added_area},
                       {"slivers", fp.slivers},
                       {"laid_twice_area", fp.laid_twice_area},
                       {"loops", loops_json(fp.cut)}};
  j["flat_outline_exact"] = {
      {"area", fp.area}, {"perimeter", fp.perimeter}, {"loops", loops_json(fp.outline)}};
}

// The pieces of a pattern split for the roll, and the seams between them.
void add_splices(nlohmann::json& j, const SplicePlan& plan) {
  nlohmann::json pieces = nlohmann::json::array();
  for (std::size_t k = 0; k < plan.pieces.size(); ++k) {
    const SplicePiece& p = plan.pieces[k];
    nlohmann::json counts = nlohmann::json::array(), seams = nlohmann::json::array();
    for (const auto& l : p.loops) counts.push_back(l.points.size());
    if (k > 0) seams.push_back(plan.seams[k - 1].x);
    if (k < plan.seams.size()) seams.push_back(plan.seams[k].x);
    pieces.push_back({{"name", p.name},
                      {"area", p.area},
                      {"width", p.width()},
                      {"x_min", p.x_min},
                      {"x_max", p.x_max},
                      {"seams_x", seams},
                      {"loop_points", counts},
                      {"loops", loops_json(p.loops)}});
  }
  nlohmann::json seams = nlohmann::json::array();
  for (const Seam& s : plan.seams) {
    nlohmann::json lines = nlohmann::json::array();
    for (const auto& l : s.polylines) lines.push_back(vecs(l));
    seams.push_back(
        {{"x", s.x},
         {"length", s.length},
         {"length_3d", s.length3d},
         {"shear_max_deg", s.shear_max * kRadToDeg},
         {"shear_mean_deg", s.shear_mean * kRadToDeg},
         {"stagger_distance",
          s.stagger_distance < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.stagger_distance)},
         {"polylines", lines}});
  }
  j["pieces"] = pieces;
  j["splices"] = {{"roll_width", plan.roll_width},
                  {"overlap", plan.overlap},
                  {"stagger", plan.stagger},
                  {"stagger_met", plan.stagger_met},
                  {"pattern_width", plan.pattern_width},
                  {"seams", seams}};
}

// The darts as the drape laid them: where they came from and, per dart, its length and tip on
// the part, the cloth cut out between its cut lines or the gap they leave on the part.
nlohmann::json darts_json(const ExportContext& ctx) {
  nlohmann::json list = nlohmann::json::array();
  for (const DartResult& d : ctx.result.darts)
    list.push_back({{"length", d.length},
                    {"tip", vec(d.tip)},
                    {"removed_area", d.removed_area},
                    {"opening_area", d.opening_area},
                    {"width_max", d.width_max},
                    {"links_cut", d.links_cut},
                    {"nodes_cut_out", d.nodes_cut_out},
                    {"cut_line_points", d.line_left.size()},
                    {"seam", d.seam}});
  return {
      {"source", ctx.run.dart_files},
      {"auto", ctx.result.darts_auto},
      {"drapes", ctx.result.drapes},
      {"laid", ctx.result.metrics.nodes.conflict == 0 && ctx.result.metrics.nodes.shear_limit == 0},
      {"darts", list}};
}

}  // namespace

std::string report_json(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  nlohmann::json j;
  j["status"] = r.partial ? "partial" : "ok";
  j["warnings"] = warnings_json(r.warnings);
  j["inputs"] = inputs_json(ctx);
  j["mold"] = mold_json(ctx);
  j["start"] = {{"point", vec(r.start_point)},
                {"face", file_index(ctx, static_cast<std::size_t>(r.start_at.face))},
                {"uv", vec(r.start_at.uv)},
                {"moved", r.start_moved}};
  j["base_tangent"] = vec(r.base_tangent);
  if (ctx.options.ply) j["ply"] = ply_json(*ctx.options.ply);
  j["nodes"] = nodes_json(r.metrics);
  add_metrics(j, r.metrics, std::min(ctx.problem.ply.d_weft, ctx.problem.ply.d_warp));
  if (ctx.flat) add_flat_outline(j, *ctx.flat);
  if (ctx.splices) add_splices(j, *ctx.splices);
  if (!r.darts.empty() || r.darts_auto) j["darts"] = darts_json(ctx);
  j["memory_bytes_per_node"] = r.bytes_per_node();
  j["timing_ms"] = {
      {"import", ctx.run.import_ms}, {"drape", ctx.run.drape_ms}, {"total", ctx.run.total_ms}};
  return j.dump(2) + "\n";
}

Exporter make_json_exporter() {
  return file_exporter("json", "report.json: status, counts, areas, angles, residuals, timings",
                       {{"report.json", report_json}});
}

}  // namespace plyfit::exporters
