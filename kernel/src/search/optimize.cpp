#include "drape/drape.hpp"
#include "named_values.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/face.hpp"

#include <plyfit/kernel/optimize.hpp>
#include <plyfit/kernel/ply_definition.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

namespace plyfit {

namespace {

/// Two ply angles closer than this (radians) are one lattice angle (rounding of the
/// directions' atan2).
constexpr double kAngleSame = 1e-12;
/// Share of the drape budget spent on the space-filling design; the rest refines.
constexpr double kDesignShare = 0.5;
/// Local searches per objective, started from the best design drapes that lie apart.
constexpr int kRefineStarts = 3;
/// The refinement stops when its steps would move the seed by less than this fraction of
/// the thread spacing (or turn the ply by less than what moves a node one face size away
/// that far): below it the figures change by which nodes fall inside the face, not by the
/// drape (moving the grid by d/4 changes the sphere octant's energy by up to 1.6%).
constexpr double kRefineResolution = 0.25;
/// Share of the design whose ply angles are lattice angles (see lattice_angles).
constexpr double kLatticeShare = 0.5;
/// Design seeds tried per planned design drape before the design stops short (seeds off a
/// trimmed face or beyond the radius are not draped).
constexpr int kDesignTriesPerDrape = 64;
/// Samples per parameter direction that find the box of the seeds' parameters.
constexpr int kSeedBoxSamples = 64;

/// Axes of the search: u and v of the seed, the ply's angle, the base path's angle.
constexpr int kAxes = 4;
/// A point of the search in unit coordinates, each axis mapped onto [0, 1].
using UnitPoint = std::array<double, kAxes>;

/// k-th term (k >= 1) of the van der Corput sequence in `base` (the Halton design's axes).
double radical_inverse(std::uint64_t k, std::uint64_t base) {
  double f = 1.0, r = 0.0;
  while (k > 0) {
    f /= static_cast<double>(base);
    r += f * static_cast<double>(k % base);
    k /= base;
  }
  return r;
}

Vec2 rotate(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

/// One axis: its range, whether it wraps (an angle over its whole period) and the smallest
/// step the refinement takes on it (unit coordinates).
struct Axis {
  double lo = 0.0, hi = 0.0;
  bool periodic = false;
  double min_step = 1.0;
  double at(double x) const { return lo + x * (hi - lo); }
  double unit(double v) const { return hi > lo ? (v - lo) / (hi - lo) : 0.5; }
};

/// The search space.
struct Space {
  const SearchScene* scene = nullptr;
  const Face* face = nullptr;
  Vec3 reference = Vec3::UnitX();
  Vec3 start0 = Vec3::Zero();
  std::optional<double> radius;
  Axis axis[kAxes];
  std::vector<int> dims;  ///< the axes that vary

  Candidate at(const UnitPoint& x) const {
    Candidate c;
    c.uv = Vec2(axis[0].at(x[0]), axis[1].at(x[1]));
    c.angle = axis[2].at(x[2]);
    c.path = axis[3].at(x[3]);
    return c;
  }
  /// `c` with axis `a` at unit coordinate `x`.
  Candidate with(Candidate c, int a, double x) const {
    const double v = axis[a].at(x);
    if (a == 0) c.uv.x() = v;
    if (a == 1) c.uv.y() = v;
    if (a == 2) c.angle = v;
    if (a == 3) c.path = v;
    return c;
  }
  UnitPoint unit(const Candidate& c) const {
    return {axis[0].unit(c.uv.x()), axis[1].unit(c.uv.y()), axis[2].unit(c.angle),
            axis[3].unit(c.path)};
  }
  /// A seed the search may drape: on the face and within the radius.
  bool admissible(const Candidate& c) const {
    if (!face->contains(c.uv)) return false;
    if (!radius) return true;
    const SurfaceEval1 e = face->eval1(c.uv);
    return e.ok && (e.p - start0).norm() <= *radius;
  }
};

/// Angles of the ply (from the scene's, about the normal) at which its base direction runs
/// along a thread or a diagonal of the cells, for a base path turned by `path`: the
/// scene's own angle (0) first, then the others within +-range, each once modulo the period.
/// There the base path passes through crossings, not between them (no short split links),
/// and the drape's figures jump: the sphere octant's energy from its centre is 7.0 with the
/// base path along a thread and 31.7 with it 0.6 degrees off. A continuous design would never
/// land on them.
std::vector<double> lattice_angles(const PlySpec& ply, double path, double range, double period) {
  const double beta = std::atan2(ply.base_dir.y(), ply.base_dir.x());
  const double diag = std::atan2(ply.d_warp, ply.d_weft);
  std::vector<double> out = {0.0};
  for (double s : {0.0, kPi / 2, kPi, 1.5 * kPi, diag, -diag, kPi + diag, kPi - diag}) {
    double a = beta + path - s;
    a -= period * std::floor((a + period / 2) / period);  // into [-period/2, period/2)
    if (std::abs(a) > range) continue;
    if (std::none_of(out.begin(), out.end(), [&](double b) {
          const double d = std::abs(a - b);
          return std::min(d, period - d) <= kAngleSame;
        }))
      out.push_back(a);
  }
  return out;
}

/// The drape problem of a candidate, or an error when the reference direction is normal to
/// the face at the seed.
Result<DrapeProblem> problem_at(const SearchScene& scene, const Face& face, const Vec3& reference,
                                const Candidate& c, Vec3* seed) {
  DrapeProblem pb = scene.problem;
  const SurfaceEval1 e = face.eval1(c.uv);
  const Vec3 n = face.normal(c.uv).n;
  if (seed) *seed = e.p;
  // The base path: the reference projected on the tangent plane, turned by `path`; the base
  // plane is the normal section along it (on a sphere, a great circle).
  auto zero = rosette_zero(reference, n, scene.drape.tol);  // as a ply rosette
  if (!zero) return Error{ErrorCode::kSearchPathNormalAtSeed};
  const Vec3 t = std::cos(c.path) * *zero + std::sin(c.path) * n.cross(*zero);
  pb.base_normal = t.cross(n);
  // In the ply the base direction turns by path - angle: the threads turn by `angle` on the
  // mold, the base path by `path`.
  auto& ply = pb.ply;
  const double turn = c.path - c.angle;
  // A direction turned onto a thread is set exactly along it: the ply model takes a base
  // path off a thread by a rounding error for one that crosses every thread at a grazing
  // angle (25 failed nodes on the sphere octant).
  auto turned = [&](const Vec2& v) {
    Vec2 w = rotate(v, turn);
    for (int k = 0; k < 2; ++k)
      if (std::abs(w[k]) <= kAngleSame * w.norm()) w[k] = 0.0;
    return w;
  };
  ply.base_dir = turned(scene.problem.ply.base_dir);
  for (Vec2& w : ply.sweeps) w = turned(w);
  // A seed inside the face needs cloth on both sides of the base path; on the face's edge the
  // second sweep leaves the face at once.
  if (ply.sweeps.size() == 1) ply.sweeps.push_back(-ply.sweeps.front());
  // A sweep on the left of the base direction in the ply goes left of t on the mold (n x t),
  // so that drape() maps the base direction onto t.
  const Vec3 left = n.cross(t);
  pb.sweeps.clear();
  for (const Vec2& w : ply.sweeps) pb.sweeps.push_back(cross2(ply.base_dir, w) > 0 ? left : -left);
  pb.start = e.p;
  return pb;
}

Figures figures_of(const Face& face, const DrapeResult& res, const SearchScene& scene) {
  FlatPatternOptions fo;
  fo.min_width = scene.min_width;  // the flat area is the cut outline's, as plyfit drape's
  const FlatPattern flat = flat_pattern(face, res, fo);
  const DrapeMetrics& m = res.metrics;
  Figures f;
  f.energy = m.shear_energy;
  f.max_shear_deg = m.shear_max * kRadToDeg;
  f.flat_area = flat.cut_area;
  f.mapped = m.nodes.mapped;
  f.shear_limit = m.nodes.shear_limit;
  f.overlap = m.nodes.overlap;
  f.off_ply = m.nodes.off_ply;
  if (face.area() > 0) {
    f.cell_coverage = m.coverage;
    f.coverage = outline_surface_area(res, flat) / face.area();
  }
  return f;
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f%%", 100.0 * fraction);
  return buf;
}

/// Drapes a problem and fills an evaluation's figures and status (not its feasibility).
void drape_into(const Face& face, const DrapeProblem& pb, const DrapeOptions& opt,
                const SearchScene& scene, Evaluation& ev) {
  try {
    auto res = drape(face, pb, opt);
    if (!res) {
      ev.status = "error";
      ev.error = res.error();
      return;
    }
    ev.status = res->partial ? "partial" : "ok";
    ev.warnings = res->warnings;
    ev.figures = figures_of(face, *res, scene);
  } catch (const std::exception& e) {
    ev.status = "error";
    ev.note = std::string("internal error: ") + e.what();
  }
}

/// True when a drape's outline covers more than the face can hold: cloth on cloth, or an
/// outline that does not match the drape.
bool over_covers(const Evaluation& ev) {
  return ev.figures.coverage > 1.0 + kCoverageSlack;
}

void judge(Evaluation& ev, double min_coverage) {
  ev.feasible = false;
  if (ev.status != "ok") return;
  ev.note.clear();
  if (ev.figures.mapped == 0) {
    ev.note = "no mapped node";
  } else if (over_covers(ev)) {
    ev.note = "the outline covers " + percent(ev.figures.coverage) +
              " of the face: more than the face (cloth on cloth, or an outline that does not "
              "match the drape)";
  } else if (ev.figures.coverage < min_coverage) {
    ev.note = "covers " + percent(ev.figures.coverage) + " of the face (less than " +
              percent(min_coverage) + ")";
  } else {
    ev.feasible = true;
  }
}

/// The default constraint follows the best coverage of an ok drape so far (at most the whole
/// face): every drape is judged again when it rises, so that none wins by covering less
/// than another.
void update_constraint(OptimizeResult& r) {
  for (const auto& ev : r.evaluations)
    if (ev.status == "ok" && !over_covers(ev))
      r.best_coverage = std::max(r.best_coverage, ev.figures.coverage);
  if (r.min_coverage_default) r.min_coverage = std::min(r.best_coverage, 1.0) - kCoverageSlack;
  for (auto& ev : r.evaluations) judge(ev, r.min_coverage);
}

/// Runs f(0) .. f(n - 1) on `jobs` threads (this one included).
void parallel_for(int n, int jobs, const std::function<void(int)>& f) {
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i = next++; i < n; i = next++) f(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(jobs, n); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

/// (value, index) order: smaller value first, ties to the earlier drape.
bool better(const Evaluation& a, const Evaluation& b, Objective o) {
  const double va = a.figures.value(o), vb = b.figures.value(o);
  return va < vb || (va == vb && a.index < b.index);
}

class Search {
 public:
  Search(const Space& sp, const OptimizeOptions& o, DrapeOptions drape, OptimizeResult& r)
      : sp_(sp), o_(o), drape_(std::move(drape)), r_(r) {}

  /// Drapes the candidates not draped before (at most `limit` new ones), in order, `jobs` at
  /// a time; the evaluation index of each candidate (-1 if left out by the limit).
  std::vector<int> run(const std::vector<Candidate>& cands, const std::string& phase, int limit) {
    std::vector<int> idx(cands.size(), -1);
    std::vector<std::size_t> fresh;
    for (std::size_t k = 0; k < cands.size(); ++k) {
      const UnitPoint key = {cands[k].uv.x(), cands[k].uv.y(), cands[k].angle, cands[k].path};
      const auto it = cache_.find(key);
      if (it != cache_.end()) {
        idx[k] = it->second;
        continue;
      }
      if (static_cast<int>(fresh.size()) >= limit) continue;
      const int i = static_cast<int>(r_.evaluations.size());
      Evaluation ev;
      ev.index = i;
      ev.phase = phase;
      ev.candidate = cands[k];
      r_.evaluations.push_back(ev);
      cache_[key] = i;
      idx[k] = i;
      fresh.push_back(static_cast<std::size_t>(i));
    }
    std::mutex progress_mutex;
    parallel_for(static_cast<int>(fresh.size()), o_.jobs, [&](int k) {
      Evaluation& ev = r_.evaluations[fresh[static_cast<std::size_t>(k)]];
      if (o_.cancel && o_.cancel->load()) {
        ev.status = "error";
        ev.note = "cancelled";
        return;
      }
      auto pb = problem_at(*sp_.scene, *sp_.face, sp_.reference, ev.candidate, &ev.seed);
      if (pb) {
        drape_into(*sp_.face, *pb, drape_, *sp_.scene, ev);
      } else {
        ev.status = "error";
        ev.error = pb.error();
      }
      if (o_.progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        o_.progress(++done_, o_.evaluations);
      }
    });
    spent_ += static_cast<int>(fresh.size());
    update_constraint(r_);
    if (o_.cancel && o_.cancel->load()) r_.cancelled = true;
    return idx;
  }

  int spent() const { return spent_; }

 private:
  const Space& sp_;
  const OptimizeOptions& o_;
  DrapeOptions drape_;
  OptimizeResult& r_;
  std::map<UnitPoint, int> cache_;
  int spent_ = 0;
  int done_ = 0;
};

/// One compass search of the refinement.
struct Local {
  UnitPoint x{};
  int index = -1;  ///< its evaluation
  UnitPoint h{};   ///< step per axis
  bool active = true;
};

/// The poll point x + sign h_a e_a, or nothing if it leaves the box (an angle over its whole
/// period wraps).
std::optional<UnitPoint> poll_point(const Space& sp, const Local& l, int a, double sign) {
  const auto k = static_cast<std::size_t>(a);
  UnitPoint y = l.x;
  y[k] += sign * l.h[k];
  if (sp.axis[a].periodic)
    y[k] -= std::floor(y[k]);
  else if (y[k] < 0.0 || y[k] > 1.0)
    return std::nullopt;
  return y;
}

/// Distance between two points of the search over the varying axes (the largest
/// coordinate difference, across the wrap for periodic axes).
double unit_distance(const Space& sp, const UnitPoint& x, const UnitPoint& y) {
  double dist = 0.0;
  for (int a : sp.dims) {
    double d = std::abs(x[static_cast<std::size_t>(a)] - y[static_cast<std::size_t>(a)]);
    if (sp.axis[a].periodic) d = std::min(d, 1.0 - d);
    dist = std::max(dist, d);
  }
  return dist;
}

/// Compass searches (Kolda, Lewis, Torczon 2003) from the best drapes so far that lie more
/// than h0 apart: each polls x +- h e_a on every varying axis, moves to its best strictly
/// improving feasible poll point or halves h; it stops when every step is below the axis's
/// smallest step. All searches poll in one batch, so the drapes run in parallel.
void refine(const Space& sp, Search& search, OptimizeResult& r, Objective obj, int budget,
            double h0) {
  const std::string phase = std::string("refine:") + to_string(obj);
  std::vector<int> order;
  for (const auto& ev : r.evaluations)
    if (ev.feasible && ev.phase != "scene") order.push_back(ev.index);
  auto ev_at = [&](int i) -> const Evaluation& {
    return r.evaluations[static_cast<std::size_t>(i)];
  };
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return better(ev_at(a), ev_at(b), obj); });
  std::vector<Local> locals;
  for (int i : order) {
    if (static_cast<int>(locals.size()) >= kRefineStarts) break;
    Local l;
    l.x = sp.unit(ev_at(i).candidate);
    l.index = i;
    l.h.fill(h0);
    if (std::all_of(locals.begin(), locals.end(),
                    [&](const Local& m) { return unit_distance(sp, l.x, m.x) > h0; }))
      locals.push_back(l);
  }
  int left = budget;
  while (left > 0 && !r.cancelled) {
    std::vector<Candidate> cands;
    std::vector<std::pair<std::size_t, UnitPoint>> owner;  // poll point k: its search and point
    for (std::size_t k = 0; k < locals.size(); ++k) {
      const Local& l = locals[k];
      if (!l.active) continue;
      for (int a : sp.dims) {
        if (l.h[static_cast<std::size_t>(a)] < sp.axis[a].min_step) continue;
        for (double sign : {1.0, -1.0}) {
          const auto y = poll_point(sp, l, a, sign);
          if (!y) continue;
          // Only the polled coordinate changes (the others keep their exact values, a lattice
          // angle among them).
          const Candidate c =
              sp.with(ev_at(l.index).candidate, a, (*y)[static_cast<std::size_t>(a)]);
          if (!sp.admissible(c)) continue;
          cands.push_back(c);
          owner.emplace_back(k, *y);
        }
      }
    }
    const int before = search.spent();
    const std::vector<int> idx = search.run(cands, phase, left);
    left -= search.spent() - before;
    for (std::size_t k = 0; k < locals.size(); ++k) {
      Local& l = locals[k];
      // A search whose point no longer meets a risen coverage constraint stops.
      if (!ev_at(l.index).feasible) l.active = false;
      if (!l.active) continue;
      int best = -1;
      UnitPoint best_x{};
      for (std::size_t p = 0; p < owner.size(); ++p) {
        if (owner[p].first != k || idx[p] < 0) continue;
        const Evaluation& ev = ev_at(idx[p]);
        if (!ev.feasible || !(ev.figures.value(obj) < ev_at(l.index).figures.value(obj))) continue;
        if (best < 0 || better(ev, ev_at(best), obj)) {
          best = idx[p];
          best_x = owner[p].second;
        }
      }
      if (best >= 0) {
        l.x = best_x;
        l.index = best;
      } else {
        for (double& h : l.h) h *= 0.5;
      }
      bool steps = false;
      for (int a : sp.dims)
        steps = steps || l.h[static_cast<std::size_t>(a)] >= sp.axis[a].min_step;
      // Two searches that meet go on as one.
      for (std::size_t q = 0; q < k; ++q)
        if (locals[q].active && locals[q].index == l.index) steps = false;
      l.active = steps;
    }
    if (std::none_of(locals.begin(), locals.end(), [](const Local& l) { return l.active; })) break;
  }
}

}  // namespace

namespace {

/// Each objective, its name, and the figure it reads.
struct ObjectiveRow {
  Objective value;
  const char* name;
  double Figures::*figure;
};
constexpr ObjectiveRow kObjectives[] = {
    {Objective::kEnergy, "energy", &Figures::energy},
    {Objective::kMaxShear, "max-shear", &Figures::max_shear_deg},
    {Objective::kArea, "area", &Figures::flat_area}};
static_assert(detail::lists_enum(kObjectives, Objective::kArea));

}  // namespace

const char* to_string(Objective o) {
  return detail::name_in(kObjectives, o, "?");
}

std::optional<Objective> parse_objective(const std::string& name) {
  return detail::value_named(kObjectives, name);
}

double Figures::value(Objective o) const {
  const ObjectiveRow* row = detail::row_of(kObjectives, o);
  return this->*(row ? row->figure : &Figures::energy);
}

Result<DrapeProblem> candidate_problem(const SearchScene& scene, const MoldSurface& surface,
                                       const OptimizeResult& r, const Candidate& c) {
  const auto* face = dynamic_cast<const Face*>(&surface.impl());
  if (!face) return Error{ErrorCode::kSearchNeedsOneFace};
  return problem_at(scene, *face, r.reference, c, nullptr);
}

namespace {

/// The scene as given, draped: the reference evaluation, the default constraint and the
/// reference direction carried to every seed.
Status drape_scene(const Face& face, const SearchScene& scene, const DrapeOptions& dopt,
                   DrapeResult& scene_res) {
  try {
    auto res = drape(face, scene.problem, dopt);
    if (!res) return res.error();
    scene_res = std::move(res).value();
  } catch (const std::exception& e) {
    return Error{ErrorCode::kInternal, {}, {std::string(e.what())}};
  }
  return ok_status();
}

void record_scene(const Face& face, const SearchScene& scene, const DrapeResult& scene_res,
                  const OptimizeOptions& o, OptimizeResult& r) {
  Evaluation ref;
  ref.phase = "scene";
  ref.status = scene_res.partial ? "partial" : "ok";
  ref.warnings = scene_res.warnings;
  ref.figures = figures_of(face, scene_res, scene);
  ref.candidate.uv = scene_res.start_at.uv;
  ref.seed = scene_res.start_point;
  r.evaluations.push_back(ref);
  r.min_coverage_default = !o.min_coverage;
  if (o.min_coverage) r.min_coverage = *o.min_coverage;
  update_constraint(r);
  r.reference = scene_res.base_tangent;
}

/// The seeds' box: the face's samples (within the radius), one sample step wider; the scene's
/// seed alone where the start does not vary.
void seed_box(const Face& face, const Space& sp, const Vec2& uv0, bool vary_start, Vec2& lo,
              Vec2& hi) {
  const ParamDomain& dom = face.domain();
  lo = uv0;
  hi = uv0;
  if (!vary_start) return;
  for (const auto& [uv, p] : sample_face(face, kSeedBoxSamples)) {
    if (sp.radius && (p - sp.start0).norm() > *sp.radius) continue;
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  const Vec2 step(dom.width_u() / kSeedBoxSamples, dom.width_v() / kSeedBoxSamples);
  lo = Vec2(std::max(dom.u0, lo.x() - step.x()), std::max(dom.v0, lo.y() - step.y()));
  hi = Vec2(std::min(dom.u1, hi.x() + step.x()), std::min(dom.v1, hi.y() + step.y()));
}

/// The search space around the scene's drape: the seeds' box, the angles' periods and ranges,
/// each axis's smallest refinement step, the axes that vary.
Space search_space(const SearchScene& scene, const Face& face, const DrapeResult& scene_res,
                   const OptimizeOptions& o, OptimizeResult& r) {
  Space sp;
  sp.scene = &scene;
  sp.face = &face;
  sp.reference = r.reference;
  sp.start0 = scene_res.start_point;
  sp.radius = o.radius;
  r.radius = o.radius;
  Vec2 lo, hi;
  seed_box(face, sp, scene_res.start_at.uv, o.vary_start, lo, hi);
  r.uv_lo = lo;
  r.uv_hi = hi;
  // The cloth's symmetry: a square weave turned by 90 degrees on a fixed base path is the same
  // cloth, unequal spacings by 180, a bounded ply (its rectangle turns with it) only by 360.
  // A base path and its reverse are one (the drape sweeps both sides): period 180.
  const auto& ply = scene.problem.ply;
  r.angle_period = ply.rect ? 2 * kPi : (ply.d_weft == ply.d_warp ? kPi / 2 : kPi);
  const double path_period = kPi;
  r.angle_range = o.vary_angle ? std::min(o.angle_range.value_or(kPi), r.angle_period / 2) : 0.0;
  r.path_range = o.vary_path ? std::min(o.path_range.value_or(kPi), path_period / 2) : 0.0;
  // Steps below these move the seed, or a node one face size away, by less than
  // kRefineResolution spacings.
  const double d = std::min(ply.d_weft, ply.d_warp);
  const Vec2 speeds = face.speeds();
  auto min_step = [&](double width, double speed) {
    return width > 0 && speed > 0 ? kRefineResolution * d / (width * speed) : 1.0;
  };
  const double angle_step = kRefineResolution * d / face.size();
  sp.axis[0] = {lo.x(), hi.x(), false, min_step(hi.x() - lo.x(), speeds.x())};
  sp.axis[1] = {lo.y(), hi.y(), false, min_step(hi.y() - lo.y(), speeds.y())};
  sp.axis[2] = {-r.angle_range, r.angle_range, r.angle_range >= r.angle_period / 2,
                r.angle_range > 0 ? angle_step / (2 * r.angle_range) : 1.0};
  sp.axis[3] = {-r.path_range, r.path_range, r.path_range >= path_period / 2,
                r.path_range > 0 ? angle_step / (2 * r.path_range) : 1.0};
  if (o.vary_start) sp.dims = {0, 1};
  if (o.vary_angle) sp.dims.push_back(2);
  if (o.vary_path) sp.dims.push_back(3);
  return sp;
}

/// The design: the scene's seed and directions first; then Halton points over the varying
/// axes (bases 2, 3, 5, 7), the first kLatticeShare of them with the ply at the lattice
/// angles in turn instead of the Halton angle. Seeds off the face or beyond the radius are
/// skipped (counted in r.skipped).
std::vector<Candidate> design(const Space& sp, const SearchScene& scene, const Vec2& uv0,
                              const OptimizeOptions& o, int n_design, OptimizeResult& r) {
  const int dims = static_cast<int>(sp.dims.size());
  const int n_lattice = o.vary_angle ? static_cast<int>(std::ceil(n_design * kLatticeShare)) : 0;
  Candidate c0;
  c0.uv = uv0;
  std::vector<Candidate> out = {c0};
  const UnitPoint x0 = sp.unit(c0);
  const std::uint64_t bases[kAxes] = {2, 3, 5, 7};
  const long tries = static_cast<long>(n_design) * kDesignTriesPerDrape;
  for (long k = 1; static_cast<int>(out.size()) < n_design && k <= tries; ++k) {
    UnitPoint x = x0;
    for (int a = 0; a < dims; ++a)
      x[static_cast<std::size_t>(sp.dims[static_cast<std::size_t>(a)])] =
          radical_inverse(static_cast<std::uint64_t>(k), bases[a]);
    Candidate c = sp.at(x);
    if (!sp.admissible(c)) {
      ++r.skipped;
      continue;
    }
    if (static_cast<int>(out.size()) < n_lattice) {
      const auto angles = lattice_angles(scene.problem.ply, c.path, r.angle_range, r.angle_period);
      c.angle = angles[out.size() % angles.size()];
    }
    out.push_back(c);
  }
  return out;
}

/// The best drape per objective and the Pareto front, over every feasible drape (the
/// scene's too).
void best_and_front(OptimizeResult& r) {
  for (int k = 0; k < kObjectiveCount; ++k) {
    const auto obj = static_cast<Objective>(k);
    for (const auto& ev : r.evaluations)
      if (ev.feasible &&
          (r.best[k] < 0 || better(ev, r.evaluations[static_cast<std::size_t>(r.best[k])], obj)))
        r.best[k] = ev.index;
  }
  auto figs = [&](const Evaluation& e) {
    return std::array<double, 3>{e.figures.energy, e.figures.max_shear_deg, e.figures.flat_area};
  };
  for (const auto& a : r.evaluations) {
    if (!a.feasible) continue;
    const auto fa = figs(a);
    bool dominated = false;
    for (const auto& b : r.evaluations) {
      if (!b.feasible || b.index == a.index) continue;
      const auto fb = figs(b);
      const bool no_worse = fb[0] <= fa[0] && fb[1] <= fa[1] && fb[2] <= fa[2];
      // Equal figures: the earlier drape stands for both.
      if (no_worse && (fb != fa || b.index < a.index)) {
        dominated = true;
        break;
      }
    }
    if (!dominated) r.front.push_back(a.index);
  }
  std::sort(r.front.begin(), r.front.end(), [&](int a, int b) {
    return better(r.evaluations[static_cast<std::size_t>(a)],
                  r.evaluations[static_cast<std::size_t>(b)], Objective::kEnergy);
  });
}

}  // namespace

Result<OptimizeResult> optimize(const SearchScene& scene, const MoldSurface& surface,
                                const OptimizeOptions& o) {
  const auto* one = dynamic_cast<const Face*>(&surface.impl());
  if (!one) return Error{ErrorCode::kSearchNeedsOneFace};
  const Face& face = *one;
  OptimizeResult r;
  DrapeOptions dopt = scene.drape;
  dopt.cancel = o.cancel;
  dopt.progress = nullptr;
  DrapeResult scene_res;
  if (auto ok = drape_scene(face, scene, dopt, scene_res); !ok) return ok.error();
  if (o.cancel && o.cancel->load()) {
    r.cancelled = true;
    return r;
  }
  record_scene(face, scene, scene_res, o, r);
  const Space sp = search_space(scene, face, scene_res, o, r);
  Search search(sp, o, dopt, r);
  const int n_design = std::max(1, static_cast<int>(std::ceil(o.evaluations * kDesignShare)));
  search.run(design(sp, scene, scene_res.start_at.uv, o, n_design, r), "design", n_design);
  r.design = search.spent();
  // Refinement per objective, the remaining budget shared equally; the first steps are half
  // the design's spacing.
  const int dims = static_cast<int>(sp.dims.size());
  const double h0 =
      0.5 * std::pow(static_cast<double>(std::max(1, r.design)), -1.0 / std::max(1, dims));
  for (std::size_t k = 0; k < o.objectives.size() && !r.cancelled; ++k) {
    const int left = o.evaluations - search.spent();
    const int share = left / static_cast<int>(o.objectives.size() - k);
    if (share > 0) refine(sp, search, r, o.objectives[k], share, h0);
  }
  if (r.cancelled) return r;
  best_and_front(r);
  return r;
}

}  // namespace plyfit
