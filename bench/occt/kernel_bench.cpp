// plyfit-bench kernel: the native NURBS kernel against OpenCASCADE on point + first
// derivatives (NurbsSurface::eval1 against Geom_BSplineSurface::D1), on the same random
// parameters, for a bicubic, a biquintic and a rational biquadratic surface.

#include <plyfit/kernel/nurbs.hpp>

#include "bench.hpp"
#include "nurbs_conversion.hpp"
#include "tables.hpp"

#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace plyfit::bench {
namespace {

using plyfit::occt::to_occt;

/// Evaluations per timed run, and timed runs per method (medians are reported).
constexpr int kEvaluations = 200000;
constexpr int kRuns = 7;

struct Case {
  std::string name;
  NurbsSurfaceData data;
};

// Clamped knot vector with random (non-uniform) interior spacing and a few double knots.
std::vector<double> nonuniform_knots(std::mt19937_64& g, int count, int degree) {
  std::uniform_real_distribution<double> step(0.3, 1.7);
  std::vector<double> k(degree + 1, 0.0);
  double x = 0.0;
  int interior = count - degree - 1;
  while (interior > 0) {
    x += step(g);
    const int mult = (interior >= 2 && g() % 5 == 0) ? 2 : 1;
    k.insert(k.end(), mult, x);
    interior -= mult;
  }
  x += step(g);
  k.insert(k.end(), degree + 1, x);
  return k;
}

// A 20 x 20 surface of the given degrees: a smooth bumpy sheet about 200 mm across.
NurbsSurfaceData make_surface(std::mt19937_64& g, int degree, bool rational) {
  constexpr int kPoles = 20;
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  NurbsSurfaceData d;
  d.degree_u = d.degree_v = degree;
  d.count_u = d.count_v = kPoles;
  d.knots_u = nonuniform_knots(g, kPoles, degree);
  d.knots_v = nonuniform_knots(g, kPoles, degree);
  for (int i = 0; i < kPoles; ++i)
    for (int j = 0; j < kPoles; ++j) {
      const double x = 10.0 * i + jitter(g), y = 10.0 * j + jitter(g);
      d.poles.emplace_back(x, y, 15.0 * std::sin(0.05 * x) * std::cos(0.07 * y) + jitter(g));
      if (rational) d.weights.push_back(0.5 + 0.75 * (1.0 + jitter(g)));
    }
  return d;
}

Vec3 v3(const gp_XYZ& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}

struct CaseResult {
  std::string name;
  double native_ns = 0, occt_ns = 0, occt_cached_ns = 0, max_rel_dev = 0;
};

CaseResult run_case(const Case& c, std::mt19937_64& g) {
  const NurbsSurface s = NurbsSurface::create(c.data).value();
  const Handle(Geom_BSplineSurface) o = to_occt(c.data);
  const GeomAdaptor_Surface adaptor(o);
  const ParamDomain& d = s.domain();
  std::uniform_real_distribution<double> ru(d.u0, d.u1), rv(d.v0, d.v1);
  std::vector<double> us(kEvaluations), vs(kEvaluations);
  for (int k = 0; k < kEvaluations; ++k) {
    us[k] = ru(g);
    vs[k] = rv(g);
  }

  // Deviation: points relative to the control-net bbox diagonal, derivatives relative to
  // bbox / parameter-range width (as in tests/occt/kernel_vs_occt_test.cpp).
  BBox3 box;
  for (const Vec3& p : c.data.poles) box.add(p);
  const double size = box.diagonal();
  CaseResult r;
  r.name = c.name;
  for (int k = 0; k < kEvaluations; ++k) {
    const SurfaceEval1 e = s.eval1(us[k], vs[k]);
    gp_Pnt P;
    gp_Vec Du, Dv;
    o->D1(us[k], vs[k], P, Du, Dv);
    r.max_rel_dev = std::max({r.max_rel_dev, (e.p - v3(P.XYZ())).norm() / size,
                              (e.du - v3(Du.XYZ())).norm() * d.width_u() / size,
                              (e.dv - v3(Dv.XYZ())).norm() * d.width_v() / size});
  }

  double sink = 0.0;  // every evaluation feeds it, so none can be optimised away
  auto native = [&] {
    double acc = 0.0;
    for (int k = 0; k < kEvaluations; ++k) {
      const SurfaceEval1 e = s.eval1(us[k], vs[k]);
      acc += e.p.x() + e.du.y() + e.dv.z();
    }
    sink += acc;
  };
  // OpenCASCADE's evaluation, by the surface itself or through its caching adaptor.
  auto occt_d1 = [&](const auto& surface) {
    double acc = 0.0;
    gp_Pnt P;
    gp_Vec Du, Dv;
    for (int k = 0; k < kEvaluations; ++k) {
      surface.D1(us[k], vs[k], P, Du, Dv);
      acc += P.X() + Du.Y() + Dv.Z();
    }
    sink += acc;
  };
  auto occt = [&] { occt_d1(*o); };
  auto cached = [&] { occt_d1(adaptor); };
  // Interleaved runs, so that load from other processes hits all three alike.
  std::vector<double> tn, to, tc;
  for (int run = 0; run < kRuns; ++run) {
    tn.push_back(time_once(native));
    to.push_back(time_once(occt));
    tc.push_back(time_once(cached));
  }
  if (!std::isfinite(sink)) std::cerr << "sink " << sink << "\n";
  r.native_ns = median(tn) * 1e9 / kEvaluations;
  r.occt_ns = median(to) * 1e9 / kEvaluations;
  r.occt_cached_ns = median(tc) * 1e9 / kEvaluations;
  return r;
}

std::vector<CaseResult> run_cases() {
  std::mt19937_64 g(20240601);
  std::vector<Case> cases;
  cases.push_back({"bicubic 20x20", make_surface(g, 3, false)});
  cases.push_back({"biquintic 20x20", make_surface(g, 5, false)});
  cases.push_back({"rational biquadratic 20x20", make_surface(g, 2, true)});
  std::vector<CaseResult> results;
  for (const Case& c : cases) results.push_back(run_case(c, g));
  return results;
}

Table make_table(const std::vector<CaseResult>& results) {
  Table t;
  t.caption = format("Point + first derivatives at %d random (u, v), median of %d runs",
                     kEvaluations, kRuns);
  t.header = {"surface",           "native eval1 (ns)",           "OCCT D1 (ns)",
              "speed-up",          "OCCT cached adaptor D1 (ns)", "speed-up vs cached",
              "max rel. deviation"};
  t.right = {false, true, true, true, true, true, true};
  for (const CaseResult& r : results)
    t.add({r.name, format("%.1f", r.native_ns), format("%.1f", r.occt_ns),
           format("%.2fx", r.occt_ns / r.native_ns), format("%.1f", r.occt_cached_ns),
           format("%.2fx", r.occt_cached_ns / r.native_ns), format("%.1e", r.max_rel_dev)});
  return t;
}

int run_kernel_bench(const std::vector<std::string>& args) {
  const bool json = has_flag(args, "--json");
  const std::vector<CaseResult> results = run_cases();
  if (json) {
    std::printf("{\n  \"benchmark\": \"kernel\",\n  \"evaluations\": %d,\n  \"runs\": %d,\n",
                kEvaluations, kRuns);
    std::printf("  \"cases\": [\n");
    for (size_t i = 0; i < results.size(); ++i) {
      const CaseResult& r = results[i];
      std::printf(
          "    {\"name\": \"%s\", \"native_ns\": %.2f, \"occt_ns\": %.2f, \"speedup\": %.3f, "
          "\"occt_cached_ns\": %.2f, \"speedup_vs_cached\": %.3f, \"max_rel_dev\": %.3e}%s\n",
          r.name.c_str(), r.native_ns, r.occt_ns, r.occt_ns / r.native_ns, r.occt_cached_ns,
          r.occt_cached_ns / r.native_ns, r.max_rel_dev, i + 1 < results.size() ? "," : "");
    }
    std::printf("  ]\n}\n");
    return 0;
  }
  std::printf("%s", make_table(results).markdown().c_str());
  return 0;
}

const BenchmarkRegistrar kRegistrar({"kernel",
                                     "native NURBS evaluation against OpenCASCADE "
                                     "(Geom_BSplineSurface::D1) [--json]",
                                     run_kernel_bench});

}  // namespace

Table kernel_table() {
  return make_table(run_cases());
}

}  // namespace plyfit::bench
