#include "face_measure_parts.hpp"

#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace plyfit::importers::occt::measure {

namespace {

// Gauss-Kronrod 7/15 nodes and weights on [-1, 1] (QUADPACK's qk15): Kronrod nodes, the odd
// ones (1, 3, 5) and the centre are the Gauss nodes.
constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975,
                           0.417959183673469387755102040816327};
// Budget of boundary segments for one face: past it the integration stops unconverged.
constexpr int kMaxSegments = 20000;

// The boundary integral of G(u, v) dv by Gauss-Kronrod.
class AreaIntegrator {
 public:
  explicit AreaIntegrator(const RowTable& table) : table_(table) {}

  // QUADPACK's 15-point Gauss-Kronrod estimate of a segment (value and error).
  void integrate(const EdgeRef& e, Segment& s) const {
    const double c = 0.5 * (s.t0 + s.t1), h = 0.5 * (s.t1 - s.t0), dh = std::abs(h);
    const double fc = f(e, c);
    double resg = fc * kWg[3], resk = fc * kWgk[7], resabs = std::abs(resk);
    double fv1[7], fv2[7];
    for (int j = 0; j < 7; ++j) {
      const double x = h * kXgk[j];
      fv1[j] = f(e, c - x);
      fv2[j] = f(e, c + x);
      resk += kWgk[j] * (fv1[j] + fv2[j]);
      resabs += kWgk[j] * (std::abs(fv1[j]) + std::abs(fv2[j]));
      if (j % 2 == 1) resg += kWg[j / 2] * (fv1[j] + fv2[j]);
    }
    const double reskh = 0.5 * resk;
    double resasc = kWgk[7] * std::abs(fc - reskh);
    for (int j = 0; j < 7; ++j)
      resasc += kWgk[j] * (std::abs(fv1[j] - reskh) + std::abs(fv2[j] - reskh));
    s.value = resk * h;
    resabs *= dh;
    resasc *= dh;
    double err = std::abs((resk - resg) * h);
    if (resasc != 0.0 && err != 0.0)
      err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    if (resabs > std::numeric_limits<double>::min() / (50.0 * kEps))
      err = std::max(50.0 * kEps * resabs, err);
    s.error = err;
    s.abs_value = resabs;
  }

 private:
  // The boundary integrand: G(u(t), v(t)) v'(t), signed by the edge's traversal.
  double f(const EdgeRef& e, double t) const {
    gp_Pnt2d p;
    gp_Vec2d d;
    e.curve->D1(t, p, d);
    if (d.Y() == 0.0) return 0.0;
    return e.sign * table_.G(p.X(), p.Y()) * d.Y();
  }

  const RowTable& table_;
};

}  // namespace

Breaks breaks_of(const Handle(Geom_Surface) & s, bool along_u) {
  Breaks br;
  const bool periodic = along_u ? s->IsUPeriodic() : s->IsVPeriodic();
  if (const auto b = Handle(Geom_BSplineSurface)::DownCast(s); !b.IsNull()) {
    const int n = along_u ? b->NbUKnots() : b->NbVKnots();
    for (int i = periodic ? 1 : 2; i <= (periodic ? n - 1 : n - 1); ++i)
      br.base.push_back(along_u ? b->UKnot(i) : b->VKnot(i));
    if (periodic) br.period = along_u ? b->UPeriod() : b->VPeriod();
    return br;
  }
  GeomAdaptor_Surface ad(s);
  const int n = along_u ? ad.NbUIntervals(GeomAbs_C2) : ad.NbVIntervals(GeomAbs_C2);
  if (n > 1 || periodic) {
    TColStd_Array1OfReal t(1, n + 1);
    if (along_u)
      ad.UIntervals(t, GeomAbs_C2);
    else
      ad.VIntervals(t, GeomAbs_C2);
    for (int i = periodic ? 1 : 2; i <= n; ++i) br.base.push_back(t(i));
    if (periodic) br.period = along_u ? s->UPeriod() : s->VPeriod();
  }
  return br;
}

Pass integrate_pass(const Evaluator& eval, const Region& r, double rel_tol, double inner_tol) {
  const auto& edges = r.edges;
  const auto& ranges = r.ranges;
  const RowTable table(eval, breaks_of(r.geometry, !r.transposed),
                       breaks_of(r.geometry, r.transposed), r.u0, r.u1, r.v0, r.v1, inner_tol);
  const AreaIntegrator integrator(table);
  std::vector<Segment> segs;
  const Breaks ub = table.column_breaks(), vb = table.band_breaks();
  for (size_t k = 0; k < edges.size(); ++k)
    split_at_crossings(edges[k].curve, ranges[k].first, ranges[k].second, ub, vb,
                       static_cast<int>(k), segs);
  // Globally adaptive: the segment with the largest error estimate is halved until the
  // estimates add up to the outer share of the requested accuracy.
  std::priority_queue<Segment> queue;
  Pass p;
  p.inner_rel = table.relative_error();
  for (Segment& seg : segs) {
    integrator.integrate(edges[static_cast<size_t>(seg.edge)], seg);
    p.total += seg.value;
    p.error += seg.error;
    p.magnitude += seg.abs_value;
    queue.push(seg);
  }
  while (p.error >
             std::max(kOuterShare * rel_tol * std::abs(p.total), kRoundoffFloor * p.magnitude) &&
         static_cast<int>(queue.size()) < kMaxSegments) {
    const Segment worst = queue.top();
    queue.pop();
    const double mid = 0.5 * (worst.t0 + worst.t1);
    if (!(mid > worst.t0 && mid < worst.t1)) {
      // Cannot be halved further: keep it as it is (its error stays in the sum).
      queue.push(Segment{worst.t0, worst.t1, worst.edge, worst.value, 0.0, worst.abs_value});
      p.error -= worst.error;
      continue;
    }
    Segment a{worst.t0, mid, worst.edge, 0, 0, 0}, b{mid, worst.t1, worst.edge, 0, 0, 0};
    integrator.integrate(edges[static_cast<size_t>(a.edge)], a);
    integrator.integrate(edges[static_cast<size_t>(b.edge)], b);
    p.total += a.value + b.value - worst.value;
    p.error += a.error + b.error - worst.error;
    p.magnitude += a.abs_value + b.abs_value - worst.abs_value;
    queue.push(a);
    queue.push(b);
  }
  return p;
}

}  // namespace plyfit::importers::occt::measure
