#include "drape_cases.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include "bench.hpp"
#include "memory.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace plyfit::bench {

void print_error(const std::string& what, const Error& e) {
  std::fprintf(stderr, "plyfit-bench: %s: %s\n", what.c_str(), exporters::describe(e).c_str());
}

namespace {
// Samples per direction when looking for the middle of a face.
constexpr int kMiddleSamples = 33;
}  // namespace

std::string shared_dir() {
  if (const char* env = std::getenv("PLYFIT_SHARED")) return env;
  return PLYFIT_SHARED_DIR;
}

Result<FacePtr> builtin_face(const std::string& name, const std::map<std::string, double>& params) {
  auto fd = builtin_mold(name, params);
  if (!fd) return fd.error();
  auto f = Face::create(std::move(fd).value());
  if (!f) return f.error();
  return FacePtr(std::make_shared<const Face>(std::move(f).value()));
}

Result<FacePtr> cad_face(const std::string& file, int index) {
  auto f = importers::load_face(shared_dir() + "/cad/" + file, index);
  if (!f) return f.error();
  return FacePtr(std::make_shared<const Face>(dynamic_cast<const Face&>(f->impl())));
}

Result<FacePtr> data_face(NurbsSurfaceData surface, std::vector<TrimLoop> loops) {
  FaceData fd;
  fd.surface = std::move(surface);
  fd.loops = std::move(loops);
  auto f = Face::create(std::move(fd));
  if (!f) return f.error();
  return FacePtr(std::make_shared<const Face>(std::move(f).value()));
}

Result<DrapeProblem> middle_problem(const Face& f, double d, bool both_sides) {
  const auto samples = sample_face(f, kMiddleSamples);
  if (samples.empty())
    return Error{
        ErrorCode::kInternal, {}, {std::string("no sample of the face lies inside its trims")}};
  Vec2 mean = Vec2::Zero();
  for (const auto& s : samples) mean += s.first;
  mean /= static_cast<double>(samples.size());
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  const Vec2 w(f.domain().width_u(), f.domain().width_v());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double dist = (samples[k].first - mean).cwiseQuotient(w).norm();
    if (dist < best_d) {
      best_d = dist;
      best = k;
    }
  }
  const Vec2 uv = samples[best].first;
  const SurfaceEval1 e = f.eval1(uv);
  const Vec3 n = f.normal(uv).n;
  const Vec3 t = (e.du - e.du.dot(n) * n).normalized();
  const Vec3 bn = n.cross(t);
  if (!bn.allFinite() || !(bn.norm() > 0.5))
    return Error{ErrorCode::kInternal, {}, {std::string("no tangent direction at the middle")}};
  if (both_sides)
    return problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, e.p, bn, {bn, -bn});
  return problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, e.p, bn, {bn});
}

double spacing_for_nodes(const Face& f, double nodes) {
  return std::sqrt(f.area() / nodes);
}

Result<DrapeRun> run_drape(const Face& f, const DrapeProblem& pb, const DrapeOptions& opt,
                           bool cold) {
  DrapeRun run;
  if (cold) release_drape_scratch();
  const bool rss = memory::reset_rss_peak();
  const long rss0 = memory::rss_kb();
  memory::reset_peak();
  const std::size_t heap0 = memory::live_bytes();
  const auto t0 = std::chrono::steady_clock::now();
  auto r = drape(f, pb, opt);
  const auto t1 = std::chrono::steady_clock::now();
  run.peak_heap = memory::peak_bytes() - heap0;
  const long rss1 = memory::rss_peak_kb();
  if (!r) return r.error();
  run.result = std::move(r).value();
  run.seconds = std::chrono::duration<double>(t1 - t0).count();
  if (rss && rss0 >= 0 && rss1 >= 0) run.peak_rss_bytes = 1024.0 * static_cast<double>(rss1 - rss0);
  return run;
}

Result<double> median_drape_time(const Face& f, const DrapeProblem& pb, const DrapeOptions& opt,
                                 int runs, DrapeRun* first) {
  std::vector<double> t;
  for (int k = 0; k < std::max(runs, kMinRuns); ++k) {
    auto r = run_drape(f, pb, opt, k == 0);
    if (!r) return r.error();
    t.push_back(r->seconds);
    if (k == 0 && first) *first = std::move(r).value();
  }
  return median(t);
}

NetErrors net_errors(const DrapeResult& r,
                     const std::function<double(const Vec3&, const Vec2&)>& distance) {
  NetErrors e;
  const double d = r.ply->d();
  for (const DrapeLink& l : r.links()) {
    const double len = (r.nodes[l.a].point - r.nodes[l.b].point).norm();
    e.link_rel = std::max(e.link_rel, std::abs(len - l.rest) / d);
  }
  for (std::uint32_t k : r.base_path)
    e.base_plane_rel = std::max(e.base_plane_rel,
                                std::abs(r.base_normal.dot(r.nodes[k].point - r.start_point)) / d);
  for (const DrapeNode& n : r.nodes)
    if (n.has(DrapeNode::kHasAngle))
      e.max_shear = std::max(e.max_shear, std::abs(kPi / 2 - n.thread_angle));
  if (distance) {
    e.surface_rel = 0.0;
    for (const DrapeNode& n : r.nodes)
      if (n.mapped()) e.surface_rel = std::max(e.surface_rel, distance(n.point, n.uv) / d);
  }
  return e;
}

std::string drape_status(const DrapeResult& r) {
  if (!r.partial) return "complete";
  return "partial (" + exporters::messages(r.warnings) + ")";
}

}  // namespace plyfit::bench
