// plyfit-bench throughput | tolerance | convergence | hard: full drapes.
//   throughput   drape time, mapped nodes per second and peak memory per node for plies of
//                100^2 .. 2000^2 nodes on three faces; fitted exponent of time against n
//   tolerance    drape time against the constraint errors for Newton tolerances 1e-3 .. 1e-14
//   convergence  discretisation error against spacing on cases with exact answers
//   hard         hard cases, one full drape each

#include <plyfit/exporters/messages.hpp>
#include "geometry/analytic_surfaces.hpp"
#include "pattern/flat_pattern.hpp"

#include "bench.hpp"
#include "drape_cases.hpp"
#include "occt_util.hpp"
#include "support/surfaces.hpp"
#include "tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <sstream>

namespace plyfit::bench {

namespace {

// The report's faces.
constexpr double kSphereRadius = 20.0;
constexpr const char* kTrimmedFile = "occ22470.igs";
constexpr int kTrimmedIndex = 16;
// Ply sizes (nodes per side) of the tolerance table.
constexpr int kToleranceSizeBicubic = 500;
constexpr int kToleranceSizeSphere = 300;
// Timed rounds of the tolerance table at least (differences of a few percent between
// tolerances need more than kMinRuns on a shared machine).
constexpr int kToleranceRounds = 9;

/// Least-squares slope of log(y) against log(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2) return 0.0;
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < n; ++k) {
    mx += std::log(x[k]);
    my += std::log(y[k]);
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sxy += (std::log(x[k]) - mx) * (std::log(y[k]) - my);
    sxx += (std::log(x[k]) - mx) * (std::log(x[k]) - mx);
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

/// A face of the throughput and tolerance tables with its drape problem at spacing d.
struct ReportFace {
  std::string name;
  FacePtr face;
  std::function<Result<DrapeProblem>(double d)> problem;
};

Result<std::vector<ReportFace>> report_faces() {
  std::vector<ReportFace> out;
  auto wave = builtin_face("wave", {});
  if (!wave) return wave.error();
  const FacePtr w = *wave;
  out.push_back({"bicubic free-form (wave, 12x12 poles)", w,
                 [w](double d) { return middle_problem(*w, d, true); }});
  auto sphere = builtin_face("sphere-octant", {{"R", kSphereRadius}});
  if (!sphere) return sphere.error();
  // The paper's case (b): the base path on the meridian y = 0 from its midpoint, swept +Y.
  out.push_back({"rational sphere octant (R 20)", *sphere, [](double d) -> Result<DrapeProblem> {
                   const double R = kSphereRadius;
                   return problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, Vec3(R / 2, 0, R / 2),
                                  Vec3(0, 1, 0), {Vec3(0, 1, 0)});
                 }});
  auto cad = cad_face(kTrimmedFile, kTrimmedIndex);
  if (!cad) return cad.error();
  const FacePtr c = *cad;
  out.push_back({std::string("trimmed CAD face (") + kTrimmedFile + " #" +
                     std::to_string(kTrimmedIndex) + ", rational)",
                 c, [c](double d) { return middle_problem(*c, d, true); }});
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Table 1

// The flat pattern is timed up to this ply size (size^2 nodes).
constexpr int kFlatPatternMaxSize = 1000;

ThroughputReport throughput_report(const ThroughputOptions& o) {
  ThroughputReport rep;
  auto faces = report_faces();
  if (failed(faces, "throughput", rep.ok)) return rep;
  Table& t = rep.table;
  t.caption = format(
      "Plies of about size^2 nodes (spacing d = sqrt(face area / size^2)), unbounded ply, "
      "default options. Time: wall time of drape() (scan and metrics), median of %d runs on "
      "one core. Nodes: mapped regular and auxiliary nodes. Peak heap: the most heap bytes "
      "held at once during drape() (replacement operator new counting malloc_usable_size; "
      "everything: node vector growth, index, frontier, path, metrics), per mapped node. "
      "Peak RSS: growth of the resident set's high-water mark during the first run. Held: "
      "DrapeResult::bytes_per_node() after the drape. Flat pattern: wall time of "
      "flat_pattern() on the drape's result (exact outline and staircase), median of %d "
      "runs, per mapped node; sizes up to %d^2 only, to keep the report short.",
      std::max(o.runs, kMinRuns), std::max(o.runs, kMinRuns), kFlatPatternMaxSize);
  t.header = {"face",
              "size",
              "d (mm)",
              "nodes",
              "time (ms)",
              "Mnodes/s",
              "ns/node",
              "ns/(n log2 n)",
              "peak heap B/node",
              "peak RSS B/node",
              "held B/node",
              "link err/d",
              "flat pattern ns/node"};
  t.right = {false, true, true, true, true, true, true, true, true, true, true, true, true};
  Table& fit = rep.fit;
  fit.caption =
      "Growth of the drape time with the number of nodes n: least-squares slope of log(time) "
      "against log(n) over all sizes, and between the two largest (1 = linear; n log n "
      "shows as slightly above 1 and a constant time/(n log2 n)).";
  fit.header = {"face", "exponent (all sizes)", "exponent (two largest)",
                "time/(n log2 n) smallest .. largest (ns)"};
  fit.right = {false, true, true, true};
  for (std::size_t fi = 0; fi < faces->size(); ++fi) {
    const ReportFace& rf = (*faces)[fi];
    std::vector<double> ns, ts, tnl;
    for (int size : o.sizes) {
      const double d = spacing_for_nodes(*rf.face, static_cast<double>(size) * size);
      auto pb = rf.problem(d);
      if (failed(pb, rf.name, rep.ok)) continue;
      DrapeRun first;
      auto tm = median_drape_time(*rf.face, *pb, {}, o.runs, &first);
      if (failed(tm, rf.name, rep.ok)) continue;
      const double n = static_cast<double>(net_nodes(first.result));
      const double sec = *tm;
      const NetErrors err = net_errors(first.result);
      const double nlogn = n * std::log2(n);
      ns.push_back(n);
      ts.push_back(sec);
      tnl.push_back(sec * 1e9 / nlogn);
      const double peak = static_cast<double>(first.peak_heap) / n;
      std::string flat = "-";
      if (size <= kFlatPatternMaxSize) {
        const double ft = median_time([&] { (void)flat_pattern(*rf.face, first.result); },
                                      std::max(o.runs, kMinRuns));
        flat = format("%.0f", ft * 1e9 / n);
      }
      t.add(
          {rf.name, format("%d^2", size), format("%.4g", d), format("%.0f", n),
           format("%.1f", sec * 1e3), format("%.2f", n / sec * 1e-6), format("%.0f", sec * 1e9 / n),
           format("%.1f", sec * 1e9 / nlogn), format("%.0f", peak),
           first.peak_rss_bytes >= 0 ? format("%.0f", first.peak_rss_bytes / n) : std::string("-"),
           format("%.0f", first.result.bytes_per_node()), format("%.1e", err.link_rel), flat});
      if (fi == 0) {
        rep.bicubic_nodes_per_s.push_back(n / sec);
        rep.bicubic_link_rel = std::max(rep.bicubic_link_rel, err.link_rel);
      }
      rep.peak_bytes_per_node.push_back(peak);
      std::fprintf(stderr, "throughput: %s %d^2: %.0f nodes, %.1f ms\n", rf.name.c_str(), size, n,
                   sec * 1e3);
    }
    const std::size_t k = ns.size();
    fit.add({rf.name, format("%.3f", loglog_slope(ns, ts)),
             k >= 2 ? format("%.3f", loglog_slope({ns[k - 2], ns[k - 1]}, {ts[k - 2], ts[k - 1]}))
                    : std::string("-"),
             k >= 1 ? format("%.1f .. %.1f", tnl.front(), tnl.back()) : std::string("-")});
  }
  return rep;
}

ThroughputOptions throughput_options(const std::vector<std::string>& args) {
  ThroughputOptions o;
  const std::string sizes = option_value(args, "--sizes", "");
  if (!sizes.empty()) {
    o.sizes.clear();
    std::stringstream ss(sizes);
    std::string item;
    while (std::getline(ss, item, ',')) o.sizes.push_back(std::stoi(item));
  }
  o.runs = std::stoi(option_value(args, "--runs", std::to_string(kMinRuns)));
  return o;
}

// ---------------------------------------------------------------------------------------
// Table 2

ToleranceReport tolerance_report(int runs) {
  ToleranceReport rep;
  runs = std::max(runs, kToleranceRounds);
  auto faces = report_faces();
  if (failed(faces, "tolerance", rep.ok)) return rep;
  const double default_tol = Tolerances{}.newton_residual_rel;
  Table& t = rep.table;
  t.caption = format(
      "Newton tolerance newton_residual_rel (x d) against drape time (median of %d runs, "
      "round-robin over the tolerances; evaluations/solve is the noise-free measure of the "
      "cost) and "
      "the constraint errors measured from the nodes: link length (max | |p_a - p_b| - rest | "
      "/ d), distance to the surface / d (bicubic: Gauss-Newton foot point on OpenCASCADE's "
      "Geom_BSplineSurface from each node's (u, v); sphere: | |p| - R |), base-plane distance "
      "of the path nodes / d, and the largest node displacement from the net at the default "
      "tolerance / d. The solver's stop is max(tol d, roundoff_rel (|x|max + face size + d)): "
      "the floor "
      "column is that rounding floor over d. Bicubic face at %d^2 nodes, sphere octant at "
      "%d^2. The default (%.0e) is marked *.",
      std::max(runs, kMinRuns), kToleranceSizeBicubic, kToleranceSizeSphere, default_tol);
  t.header = {"face",       "tolerance (x d)",  "floor/d",           "time (ms)",
              "ns/node",    "iterations/solve", "evaluations/solve", "solve residual/d",
              "link err/d", "surface dist/d",   "base-plane/d",      "displacement/d"};
  t.right = {false, true, true, true, true, true, true, true, true, true, true, true};
  std::vector<double> tols;
  for (int e = 3; e <= 14; ++e) tols.push_back(std::pow(10.0, -e));
  for (std::size_t fi = 0; fi < 2; ++fi) {
    const ReportFace& rf = (*faces)[fi];
    const bool sphere = fi == 1;
    const int size = sphere ? kToleranceSizeSphere : kToleranceSizeBicubic;
    const double d = spacing_for_nodes(*rf.face, static_cast<double>(size) * size);
    auto pb = rf.problem(d);
    if (failed(pb, rf.name, rep.ok)) continue;
    // Reference net at the default tolerance, for the displacement column.
    auto ref = drape(*rf.face, *pb, {});
    if (failed(ref, rf.name, rep.ok)) continue;
    double xmax = 0.0;
    for (const DrapeNode& n : ref->nodes)
      if (n.mapped()) xmax = std::max(xmax, n.point.cwiseAbs().maxCoeff());
    const double floor_rel = Tolerances{}.roundoff_rel * (xmax + rf.face->size() + d) / d;
    const OcctDistance occt(rf.face->surface().data());
    auto distance = [&](const Vec3& p, const Vec2& uv) {
      return sphere ? std::abs(p.norm() - kSphereRadius) : occt(p, uv);
    };
    // Timings round-robin over the tolerances (each round drapes at every tolerance once), so
    // that a change of the machine's load hits all tolerances alike.
    std::vector<std::vector<double>> times(tols.size());
    for (int round = 0; round < std::max(runs, kMinRuns); ++round) {
      for (std::size_t k = 0; k < tols.size(); ++k) {
        DrapeOptions opt;
        opt.tol.newton_residual_rel = tols[k];
        auto r = run_drape(*rf.face, *pb, opt);
        if (failed(r, rf.name, rep.ok)) return rep;
        times[k].push_back(r->seconds);
      }
    }
    for (std::size_t k = 0; k < tols.size(); ++k) {
      const double tol = tols[k];
      DrapeOptions opt;
      opt.tol.newton_residual_rel = tol;
      auto res = drape(*rf.face, *pb, opt);
      if (failed(res, rf.name, rep.ok)) continue;
      const double tm = median(times[k]);
      const DrapeResult& r = *res;
      const NetErrors err = net_errors(r, distance);
      double disp = 0.0;
      for (const DrapeNode& n : r.nodes) {
        if (!n.mapped()) continue;
        const DrapeNode* m = ref->find(n.id);
        if (m && m->mapped()) disp = std::max(disp, (m->point - n.point).norm() / d);
      }
      const double n = static_cast<double>(net_nodes(r));
      const auto& m = r.metrics;
      t.add({rf.name, format("%.0e%s", tol, tol == default_tol ? " *" : ""),
             format("%.1e", floor_rel), format("%.1f", tm * 1e3), format("%.0f", tm * 1e9 / n),
             format("%.2f", static_cast<double>(m.iterations) / static_cast<double>(m.solves)),
             format("%.2f", static_cast<double>(m.evaluations) / static_cast<double>(m.solves)),
             format("%.1e", m.solve_residual_max_rel), format("%.1e", err.link_rel),
             format("%.1e", err.surface_rel), format("%.1e", err.base_plane_rel),
             format("%.1e", disp)});
      rep.points.push_back(
          {sphere ? "sphere octant" : "bicubic", tol, tm * 1e3, err.link_rel, err.surface_rel,
           static_cast<double>(m.iterations) / static_cast<double>(m.solves), disp});
      std::fprintf(stderr, "tolerance: %s %.0e: %.1f ms, link %.1e\n", rf.name.c_str(), tol,
                   tm * 1e3, err.link_rel);
    }
  }
  return rep;
}

std::string tolerance_summary(const std::vector<TolerancePoint>& points, double default_tol) {
  std::string out;
  std::vector<std::string> faces;
  for (const auto& p : points)
    if (std::find(faces.begin(), faces.end(), p.face) == faces.end()) faces.push_back(p.face);
  for (const auto& face : faces) {
    auto at = [&](double tol) -> const TolerancePoint* {
      for (const auto& p : points)
        if (p.face == face && std::abs(p.tol / tol - 1) < 1e-9) return &p;
      return nullptr;
    };
    const TolerancePoint *def = at(default_tol), *t10 = at(1e-10), *t6 = at(1e-6), *t3 = at(1e-3);
    if (!def || !t10 || !t6 || !t3) continue;
    out += format(
        "- %s: at the default the drape takes %+.1f%% against a tolerance of 1e-6 d and "
        "%+.1f%% against 1e-10 d (same run), for a link error of %.1e d instead of "
        "%.1e d and %.1e d; Newton iterations per solve: %.2f at 1e-3, %.2f at 1e-10, "
        "%.2f at the default. At 1e-10 d nodes move %.1e d from the default's net "
        "(%.0f times the tolerance).\n",
        face.c_str(), 100.0 * (def->ms / t6->ms - 1.0), 100.0 * (def->ms / t10->ms - 1.0),
        def->link_rel, t6->link_rel, t10->link_rel, t3->iterations, t10->iterations,
        def->iterations, t10->displacement, t10->displacement / 1e-10);
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Table 3

ConvergenceReport convergence_report() {
  ConvergenceReport rep;
  Table& t = rep.table;
  t.caption =
      "Error against spacing d = L / k on cases with exact answers (L: part size). Cylinder R "
      "10, H 40, 120 degrees, base path at 45 degrees to the threads along a generator: the "
      "max shear |pi/2 - gamma| (exact: 0, the cylinder develops). Flat outline "
      "(flat_pattern) of a cylinder sector (R 10, H 20, 90 degrees; exact: the rectangle R "
      "alpha x H) and of a cone sector (r 20 to 10, H 15, 90 degrees; exact: the annular "
      "sector), relative area and perimeter errors, signed (outline minus exact). Order: "
      "log-log slope of |error| from the previous spacing.";
  t.header = {"case", "L/d", "d (mm)", "nodes", "error", "order"};
  t.right = {false, true, true, true, true, true};
  Table& o = rep.orders;
  o.caption =
      "Observed order of convergence: least-squares log-log slope of the error "
      "against d over all spacings, and over the three coarsest.";
  o.header = {"case", "order (all spacings)", "order (k = 10..50)"};
  o.right = {false, true, true};
  const std::vector<int> ks = {10, 20, 50, 100, 200, 400};

  struct Series {
    std::string name;
    std::vector<double> d, err;
  };
  std::vector<Series> series;
  auto add_rows = [&](Series& s, const std::vector<double>& nodes) {
    for (std::size_t k = 0; k < s.d.size(); ++k) {
      const double L_over_d = ks[k];
      std::string order = "-";
      const double e0 = k > 0 ? std::abs(s.err[k - 1]) : 0.0, e1 = std::abs(s.err[k]);
      if (e0 > 0 && e1 > 0)
        order = format("%.2f%s", std::log(e0 / e1) / std::log(s.d[k - 1] / s.d[k]),
                       (s.err[k - 1] > 0) != (s.err[k] > 0) ? " (sign change)" : "");
      t.add({s.name, format("%.0f", L_over_d), format("%.4g", s.d[k]), format("%.0f", nodes[k]),
             format("%.2e", s.err[k]), order});
    }
    series.push_back(s);
  };

  {  // Cylinder at 45 degrees: max shear.
    const double R = 10, H = 40, alpha = 120 * kDegToRad;
    auto f = builtin_face("cylinder", {{"R", R}, {"H", H}, {"angle", 120}});
    if (failed(f, "convergence", rep.ok)) return rep;
    const double a = kPi / 3, L = std::max(R * alpha, H);
    const Vec3 s3(R * std::cos(a), R * std::sin(a), 20), tang(-std::sin(a), std::cos(a), 0);
    Series s{"cylinder at 45 deg: max shear (rad)", {}, {}};
    std::vector<double> nodes;
    for (int k : ks) {
      const double d = L / k;
      auto r = drape(**f, problem(d, Vec2(0, 0), Vec2(1, 1), {Vec2(-1, 1), Vec2(1, -1)}, s3, tang,
                                  {tang, -tang}));
      if (failed(r, "cylinder", rep.ok)) return rep;
      s.d.push_back(d);
      s.err.push_back(net_errors(*r).max_shear);
      nodes.push_back(static_cast<double>(net_nodes(*r)));
    }
    add_rows(s, nodes);
  }
  // Flat outlines: area and perimeter against the exact development.
  auto outline = [&](const std::string& name, const FacePtr& f, const Vec3& s3, const Vec3& tang,
                     double L, double area, double perimeter) {
    Series sa{name + ": outline area", {}, {}}, sp{name + ": outline perimeter", {}, {}};
    std::vector<double> nodes;
    for (int k : ks) {
      const double d = L / k;
      auto r = drape(*f, problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, s3, tang,
                                 {tang, -tang}));
      if (!r) {
        print_error(name, r.error());
        rep.ok = false;
        return;
      }
      const FlatPattern fp = flat_pattern(*f, *r);
      sa.d.push_back(d);
      sp.d.push_back(d);
      sa.err.push_back((fp.area - area) / area);
      sp.err.push_back((fp.perimeter - perimeter) / perimeter);
      nodes.push_back(static_cast<double>(net_nodes(*r)));
    }
    add_rows(sa, nodes);
    add_rows(sp, nodes);
  };
  {
    const double R = 10, H = 20, alpha = kPi / 2;
    auto f = builtin_face("cylinder", {{"R", R}, {"H", H}, {"angle", 90}});
    if (failed(f, "convergence", rep.ok)) return rep;
    const double a = 0.37;
    outline("cylinder sector", *f, Vec3(R * std::cos(a), R * std::sin(a), 7.3),
            Vec3(-std::sin(a), std::cos(a), 0), std::max(R * alpha, H), R * alpha * H,
            2 * (R * alpha + H));
  }
  {
    const double r0 = 20, r1 = 10, H = 15, alpha = kPi / 2;
    auto f = builtin_face("cone", {{"r0", r0}, {"r1", r1}, {"H", H}, {"angle", 90}});
    if (failed(f, "convergence", rep.ok)) return rep;
    const double L = std::hypot(r0 - r1, H);
    const double ro = r0 * L / (r0 - r1), ri = r1 * L / (r0 - r1), phi = alpha * (r0 - r1) / L;
    const double a = kPi / 4;
    outline("cone sector", *f, Vec3(15 * std::cos(a), 15 * std::sin(a), 7.5),
            Vec3(-std::sin(a), std::cos(a), 0), ro * phi, phi / 2 * (ro * ro - ri * ri),
            phi * (ro + ri) + 2 * L);
  }
  for (const Series& s : series) {
    std::vector<double> e;
    for (double x : s.err) e.push_back(std::abs(x));
    const std::size_t n3 = std::min<std::size_t>(3, s.d.size());
    const std::vector<double> d3(s.d.begin(), s.d.begin() + n3), e3(e.begin(), e.begin() + n3);
    o.add({s.name, format("%.2f", loglog_slope(s.d, e)), format("%.2f", loglog_slope(d3, e3))});
  }
  return rep;
}

// ---------------------------------------------------------------------------------------
// Table 5

namespace {

struct HardCase {
  std::string name;
  FacePtr face;
  DrapeProblem problem;
  DrapeOptions options;
};

Result<std::vector<HardCase>> hard_cases() {
  std::vector<HardCase> out;
  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  auto both = [](double d, const Vec3& s3, const Vec3& bn) {
    return problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, s3, bn, {bn, -bn});
  };
  {
    auto f = builtin_face("sphere-octant", {{"R", 20}});
    if (!f) return f.error();
    // The paper's case (a): from the pole along the meridian y = 0.
    out.push_back({"start at a pole (sphere octant R 20, paper case (a)), d 0.5",
                   *f,
                   problem(0.5, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, Vec3(0, 0, 20), Y, {Y}),
                   {}});
    // The paper's case (c) with a lock angle of 30 degrees: the shear limit is reached.
    DrapeOptions lock;
    lock.lock_angle = 30 * kDegToRad;
    out.push_back({"near the shear limit (octant, case (c), lock angle 30 deg), d 0.5", *f,
                   problem(0.5, Vec2(15, 0), Vec2(1, 1), {Vec2(-1, 1)}, Vec3(0, 0, 20), Y, {Y}),
                   lock});
  }
  {
    auto f = data_face(support::roof(10));  // 40 x 60 mm
    if (!f) return f.error();
    // The base path runs across the crease.
    out.push_back({"C0 crease (roof, slopes +-1/2), d 0.5", *f, both(0.5, Vec3(-10, 0, 5), Y), {}});
  }
  {
    auto f = data_face(support::wild_plane(false, true));
    if (!f) return f.error();
    out.push_back(
        {"extreme weights (0.01..100, plane), d 0.2", *f, both(0.2, Vec3(0.3, 0.1, 0), Y), {}});
    auto g = data_face(support::wild_plane(true, false));
    if (!g) return g.error();
    out.push_back({"non-uniform knots (spans 1000x apart, plane), d 0.2",
                   *g,
                   both(0.2, Vec3(0.3, 0.1, 0), Y),
                   {}});
  }
  for (double scale : {1e-3, 1e4}) {
    NurbsSurfaceData w = wave_surface(100.0, 8.0, 70.0, 10);
    for (auto& p : w.poles) p *= scale;
    auto f = data_face(w);
    if (!f) return f.error();
    out.push_back({format("scale %.0e (wave x %.0e), d %.0e", scale, scale, 0.5 * scale),
                   *f,
                   both(0.5 * scale, Vec3(50, 50, 0) * scale, Vec3(-0.3, 1, 0)),
                   {}});
  }
  {
    auto f = data_face(sphere_patch(1.0, -1.4, 1.5, 0.0, 5.0));
    if (!f) return f.error();
    out.push_back({"curvature radius = d (sphere R 1, d 1)", *f, both(1.0, Vec3(1, 0, 0), Y), {}});
  }
  {
    auto f = builtin_face("cylinder", {{"R", 10}, {"H", 40}, {"angle", 360}});
    if (!f) return f.error();
    // Swept both ways around the axis until the cloth meets itself (overlap test per node).
    out.push_back({"closed face (cylinder R 10, 360 deg), d 0.2",
                   *f,
                   problem(0.2, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, Vec3(10, 0, 20),
                           Y, {Y, -Y}),
                   {}});
  }
  {
    auto f = builtin_face("saddle", {{"size", 40}, {"rho", 20}});
    if (!f) return f.error();
    out.push_back(
        {"saddle (40 mm, rho 20), d 0.2", *f, both(0.2, Vec3(0, 0, 0), Vec3(-0.2, 1, 0)), {}});
  }
  for (const auto& [file, index, label] :
       {std::tuple<const char*, int, const char*>{"bug27693_cornetta-step.stp", 7,
                                                  "face with 3 holes (rational)"},
        {"PRO20359-L1.igs", 0, "real trimmed face (5x5, 41x25 poles)"}}) {
    auto f = cad_face(file, index);
    if (!f) return f.error();
    const double d = spacing_for_nodes(**f, 300.0 * 300.0);
    auto pb = middle_problem(**f, d, true);
    if (!pb) return pb.error();
    out.push_back({format("%s (%s #%d), d %.3g", label, file, index, d), *f, *pb, {}});
  }
  (void)X;
  (void)Z;
  return out;
}

}  // namespace

Table hard_case_table(int runs, bool* ok) {
  Table t;
  t.caption = format(
      "Hard cases, one full drape each (unbounded ply, default options unless stated). "
      "Status: complete, or partial with the drape's warnings. Nodes by status: mapped "
      "(regular + auxiliary), outside the face, at the shear limit, failed (no solution) / "
      "conflict (two fronts of cloth met and disagree) / overlap (the cloth would lie on "
      "itself). Max residual: "
      "the solvers' largest final residual (|F1| + |F2|) / d "
      "(DrapeMetrics::solve_residual_max_rel); then, measured from the nodes, the largest "
      "link-length error / d over all links between mapped nodes (including links that no "
      "solve closed, where a node had more known neighbours than its solver uses) and the "
      "base-plane distance / d. Time: median of %d runs.",
      std::max(runs, kMinRuns));
  t.header = {"case",
              "status",
              "mapped",
              "outside",
              "shear limit",
              "failed / conflict / overlap",
              "solve residual/d",
              "link err/d",
              "base-plane/d",
              "max shear (deg)",
              "time (ms)"};
  t.right = {false, false, true, true, true, true, true, true, true, true, true};
  auto cases = hard_cases();
  if (!cases) {
    print_error("hard cases", cases.error());
    if (ok) *ok = false;
    return t;
  }
  for (const HardCase& c : *cases) {
    DrapeRun first;
    auto tm = median_drape_time(*c.face, c.problem, c.options, runs, &first);
    if (!tm) {
      t.add({c.name, "error: " + exporters::describe(tm.error()), "-", "-", "-", "-", "-", "-", "-",
             "-", "-"});
      if (ok) *ok = false;
      continue;
    }
    const DrapeResult& r = first.result;
    const NetErrors e = net_errors(r);
    const auto& m = r.metrics.nodes;
    t.add({c.name, drape_status(r),
           format("%llu + %llu", (unsigned long long)m.mapped, (unsigned long long)m.auxiliary),
           format("%llu", (unsigned long long)m.outside),
           format("%llu", (unsigned long long)m.shear_limit),
           format("%llu / %llu / %llu", (unsigned long long)m.failed,
                  (unsigned long long)m.conflict, (unsigned long long)m.overlap),
           format("%.1e", r.metrics.solve_residual_max_rel), format("%.1e", e.link_rel),
           format("%.1e", e.base_plane_rel), format("%.2f", e.max_shear * kRadToDeg),
           format("%.2f", *tm * 1e3)});
    std::fprintf(stderr, "hard: %s: %.2f ms\n", c.name.c_str(), *tm * 1e3);
  }
  return t;
}

// ---------------------------------------------------------------------------------------
// Overlap test and closed faces (issues 13 and 14)

namespace {

// Ply sizes (nodes per side) of the overlap table.
constexpr int kOverlapSizes[] = {300, 1000};

// The closed hemisphere (R kSphereRadius) with the octant's problem swept both ways: the
// cloth goes round the axis from the meridian y = 0 and meets itself.
Result<ReportFace> hemisphere_face() {
  auto h = builtin_face("hemisphere", {{"R", kSphereRadius}});
  if (!h) return h.error();
  return ReportFace{"closed hemisphere (R 20)", *h, [](double d) -> Result<DrapeProblem> {
                      const double R = kSphereRadius, c = std::sqrt(0.5);
                      return problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                                     Vec3(R * c, 0, R * c), Vec3(0, 1, 0),
                                     {Vec3(0, 1, 0), Vec3(0, -1, 0)});
                    }};
}

}  // namespace

Table overlap_table(int runs, std::vector<int> sizes, bool* ok) {
  Table t;
  if (sizes.empty()) sizes.assign(std::begin(kOverlapSizes), std::end(kOverlapSizes));
  runs = std::max(runs, kMinRuns);
  t.caption = format(
      "Cost of the overlap test (every mapped node tested for landing on cloth already laid, "
      "DrapeOptions::overlap_test) and closed against open faces: drape() wall time per mapped "
      "node with the test and without it, runs alternating between the two in one process, "
      "median of %d each; cost = with / without - 1 of the medians, and the median of the "
      "same ratio over the pairs of runs made one after the other (paired: it follows the "
      "machine's drift less). The closed hemisphere's ns/node is compared with the sphere "
      "octant's (the same rational sphere, open) at the same size.",
      runs);
  t.header = {"face", "size",         "nodes",    "overlaps", "ns/node with", "ns/node without",
              "cost", "cost, paired", "vs octant"};
  t.right = {false, true, true, true, true, true, true, true, true};
  auto faces = report_faces();
  auto hemi = hemisphere_face();
  if (!faces || !hemi) {
    print_error("overlap", faces ? hemi.error() : faces.error());
    if (ok) *ok = false;
    return t;
  }
  faces->push_back(*hemi);
  for (int size : sizes) {
    double octant_ns = 0.0;
    for (const ReportFace& rf : *faces) {
      const double d = spacing_for_nodes(*rf.face, static_cast<double>(size) * size);
      auto pb = rf.problem(d);
      if (!pb) {
        print_error(rf.name, pb.error());
        if (ok) *ok = false;
        continue;
      }
      DrapeOptions opts[2];  // with the test, without
      opts[1].overlap_test = false;
      std::vector<double> secs[2];
      DrapeResult first;
      bool failed = false;
      for (int k = 0; k < runs && !failed; ++k) {
        for (int b = 0; b < 2; ++b) {
          auto r = run_drape(*rf.face, *pb, opts[b]);
          if (!r) {
            print_error(rf.name, r.error());
            failed = true;
            break;
          }
          secs[b].push_back(r->seconds);
          if (k == 0 && b == 0) first = std::move(r->result);
        }
      }
      if (failed) {
        if (ok) *ok = false;
        continue;
      }
      const double n = static_cast<double>(net_nodes(first));
      const std::vector<double>&tw = secs[0], &to = secs[1];
      const double ns_with = median(tw) * 1e9 / n, ns_without = median(to) * 1e9 / n;
      std::vector<double> paired;
      for (std::size_t k = 0; k < tw.size() && k < to.size(); ++k) paired.push_back(tw[k] / to[k]);
      const bool octant = rf.name.find("octant") != std::string::npos;
      const bool closed = rf.face->closes_on_itself();
      if (octant) octant_ns = ns_with;
      t.add({rf.name, format("%d^2", size), format("%.0f", n),
             format("%llu", (unsigned long long)first.metrics.nodes.overlap),
             format("%.0f", ns_with), format("%.0f", ns_without),
             format("%+.1f %%", (ns_with / ns_without - 1) * 100),
             format("%+.1f %%", (median(paired) - 1) * 100),
             closed && octant_ns > 0 ? format("%.2fx", ns_with / octant_ns) : std::string("-")});
      std::fprintf(stderr, "overlap: %s %d^2: %.0f / %.0f ns/node\n", rf.name.c_str(), size,
                   ns_with, ns_without);
    }
  }
  return t;
}

// ---------------------------------------------------------------------------------------
// Subcommands

namespace {

// One face of the overlap table at one size, with and without the overlap test (runs
// alternating), or one of the two alone (`--only on|off`, e.g. under callgrind): median wall
// and thread CPU time per node, peak heap per node, and a digest of every node's status and
// point (equal digests: the same drape).
int run_overlap_ab(const std::vector<std::string>& args) {
  const std::string which = option_value(args, "--face", "wave");
  const int size = std::stoi(option_value(args, "--size", "300"));
  const int runs = std::max(1, std::stoi(option_value(args, "--runs", "1")));
  const std::string only = option_value(args, "--only", "");
  auto faces = report_faces();
  auto hemi = hemisphere_face();
  if (!faces || !hemi) {
    print_error("overlap-ab", faces ? hemi.error() : faces.error());
    return 1;
  }
  faces->push_back(*hemi);
  const ReportFace* rf = nullptr;
  for (const ReportFace& f : *faces)
    if (f.name.find(which) != std::string::npos) rf = &f;
  if (!rf) {
    std::fprintf(stderr, "plyfit-bench: overlap-ab: no face named like '%s'\n", which.c_str());
    return 1;
  }
  auto pb = rf->problem(spacing_for_nodes(*rf->face, static_cast<double>(size) * size));
  if (!pb) {
    print_error(rf->name, pb.error());
    return 1;
  }
  struct Mode {
    const char* name;
    bool test;
  };
  std::vector<Mode> modes;
  if (only != "off") modes.push_back({"on", true});
  if (only != "on") modes.push_back({"off", false});
  const std::size_t nm = modes.size();
  std::vector<std::vector<double>> wall(nm), cpu(nm);
  std::uint64_t nodes = 0;
  for (int k = 0; k < runs; ++k)
    for (std::size_t m = 0; m < nm; ++m) {
      DrapeOptions o;
      o.overlap_test = modes[m].test;
      timespec c0{}, c1{};
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
      auto r = run_drape(*rf->face, *pb, o, k == 0);  // the peak heap printed: a first drape's
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
      if (!r) {
        print_error(rf->name, r.error());
        return 1;
      }
      wall[m].push_back(r->seconds);
      cpu[m].push_back(static_cast<double>(c1.tv_sec - c0.tv_sec) +
                       1e-9 * static_cast<double>(c1.tv_nsec - c0.tv_nsec));
      if (k > 0) continue;
      nodes = net_nodes(r->result);
      std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over statuses and point bits
      auto feed = [&h](const void* p, std::size_t n) {
        for (std::size_t b = 0; b < n; ++b)
          h = (h ^ static_cast<const unsigned char*>(p)[b]) * 1099511628211ULL;
      };
      for (const DrapeNode& n : r->result.nodes) {
        feed(&n.status, sizeof n.status);
        feed(n.point.data(), 3 * sizeof(double));
      }
      std::printf(
          "%s %d^2 overlap test %s: %llu nodes, %llu overlap, peak heap %.1f B/node, digest "
          "%016llx\n",
          rf->name.c_str(), size, modes[m].name, (unsigned long long)nodes,
          (unsigned long long)r->result.metrics.nodes.overlap,
          static_cast<double>(r->peak_heap) / static_cast<double>(nodes), (unsigned long long)h);
    }
  const double n = static_cast<double>(nodes);
  for (std::size_t m = 0; m < nm; ++m)
    std::printf("test %s: wall %.0f ns/node, cpu %.0f ns/node (median of %d)\n", modes[m].name,
                median(wall[m]) * 1e9 / n, median(cpu[m]) * 1e9 / n, runs);
  // Runs k of two modes ran one after the other: the median of their ratios follows the
  // machine's drift less than the ratio of the medians.
  auto cost = [&](const char* what, std::size_t a, std::size_t b) {
    std::vector<double> paired;
    for (std::size_t k = 0; k < wall[a].size(); ++k) paired.push_back(wall[a][k] / wall[b][k]);
    std::printf("%s: wall %+.1f %%, cpu %+.1f %%, wall of paired runs %+.1f %% (median)\n", what,
                (median(wall[a]) / median(wall[b]) - 1) * 100,
                (median(cpu[a]) / median(cpu[b]) - 1) * 100, (median(paired) - 1) * 100);
  };
  if (nm >= 2 && modes[0].test && !modes[1].test) cost("cost", 0, 1);
  return 0;
}

int run_throughput(const std::vector<std::string>& args) {
  const ThroughputReport r = throughput_report(throughput_options(args));
  std::printf("%s\n%s", r.table.markdown().c_str(), r.fit.markdown().c_str());
  return r.ok ? 0 : 1;
}

int run_convergence(const std::vector<std::string>&) {
  const ConvergenceReport r = convergence_report();
  std::printf("%s\n%s", r.table.markdown().c_str(), r.orders.markdown().c_str());
  return r.ok ? 0 : 1;
}

int run_overlap(const std::vector<std::string>& args) {
  std::vector<int> sizes;
  const std::string list = option_value(args, "--sizes", "");
  if (!list.empty()) {
    std::stringstream ss(list);
    std::string item;
    while (std::getline(ss, item, ',')) sizes.push_back(std::stoi(item));
  }
  bool ok = true;
  const Table t =
      overlap_table(std::stoi(option_value(args, "--runs", std::to_string(kMinRuns))), sizes, &ok);
  std::printf("%s", t.markdown().c_str());
  return ok ? 0 : 1;
}

const BenchmarkRegistrar kOverlapAb{
    {"overlap-ab",
     "one face of the overlap table with and without the test: wall and CPU ns/node, heap, "
     "digest of the nodes [--face wave|octant|CAD|hemisphere --size N --runs R --only on|off]",
     run_overlap_ab}};
const BenchmarkRegistrar kOverlap{
    {"overlap",
     "cost of the overlap test (with and without, alternating) and closed against open faces "
     "[--sizes 300,1000 --runs R]",
     run_overlap}};
const BenchmarkRegistrar kThroughput{
    {"throughput",
     "drape time, nodes/s and peak memory per node for 100^2 .. 2000^2 nodes on three faces "
     "[--sizes 100,300 --runs R]",
     run_throughput}};
const BenchmarkRegistrar kTolerance{runs_table_benchmark(
    "tolerance", "drape time against constraint errors for Newton tolerances 1e-3 .. 1e-14",
    [](int runs, bool* ok) {
      ToleranceReport r = tolerance_report(runs);
      *ok = r.ok;
      return r.table;
    })};
const BenchmarkRegistrar kConvergence{
    {"convergence", "discretisation error against spacing on cases with exact answers",
     run_convergence}};
const BenchmarkRegistrar kHard{
    runs_table_benchmark("hard", "hard cases, one full drape each", hard_case_table)};

}  // namespace

}  // namespace plyfit::bench
