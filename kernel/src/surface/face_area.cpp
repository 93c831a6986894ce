// Sampling a face and its area by adaptive Gauss quadrature.
#include "surface/face.hpp"

#include "geometry/bspline_basis.hpp"
#include "geometry/numeric.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {
// Parameter values covering [a, b]: every knot span gets at least degree + 1 points (so
// strongly non-uniform knot vectors are sampled where the geometry is), n in all at least.
std::vector<double> span_samples(const std::vector<double>& knots, int degree, double a, double b,
                                 int n) {
  const auto br = detail::breakpoints(knots, a, b);
  const int spans = std::max(1, static_cast<int>(br.size()) - 1);
  const int per = std::max(degree + 1, (n + spans - 1) / spans);
  std::vector<double> out;
  for (int i = 0; i < spans; ++i) {
    const double lo = br.size() > 1 ? br[i] : a, hi = br.size() > 1 ? br[i + 1] : b;
    for (int k = 0; k < per; ++k) out.push_back(lo + (hi - lo) * k / per);
  }
  out.push_back(b);
  return out;
}
}  // namespace

std::vector<std::pair<Vec2, Vec3>> sample_face(const Face& face, int n) {
  const auto& s = face.surface();
  const auto& d = s.domain();
  const auto us = span_samples(s.data().knots_u, s.data().degree_u, d.u0, d.u1, n);
  const auto vs = span_samples(s.data().knots_v, s.data().degree_v, d.v0, d.v1, n);
  // Evaluated a row along u at a time (eval1_along_u: eval1's values, for about half the work),
  // listed u by u. Wrapping moves v alike for every point of a row.
  const std::size_t nu = us.size(), nv = vs.size();
  std::vector<Vec3> points(nu * nv);  // [j * nu + i]: at (us[i], vs[j])
  std::vector<char> on(nu * nv, 0);   // inside the trims and evaluated
  std::vector<double> row_u;
  std::vector<std::size_t> row_i;
  std::vector<SurfaceEval1> row_e;
  for (std::size_t j = 0; j < nv; ++j) {
    row_u.clear();
    row_i.clear();
    double v = vs[j];
    for (std::size_t i = 0; i < nu; ++i) {
      const Vec2 uv(us[i], vs[j]);
      if (!face.contains(uv)) continue;
      const Vec2 w = face.wrap(uv);
      row_u.push_back(w.x());
      row_i.push_back(i);
      v = w.y();
    }
    row_e.resize(row_u.size());
    s.eval1_along_u(v, row_u.data(), row_u.size(), row_e.data());
    for (std::size_t k = 0; k < row_e.size(); ++k) {
      points[j * nu + row_i[k]] = row_e[k].p;
      on[j * nu + row_i[k]] = row_e[k].ok ? 1 : 0;
    }
  }
  std::vector<std::pair<Vec2, Vec3>> out;
  out.reserve(nu * nv);
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j)
      if (on[j * nu + i]) out.emplace_back(Vec2(us[i], vs[j]), points[j * nu + i]);
  return out;
}

namespace {

// Face::compute_area: relative tolerance of the adaptive quadrature, the depth of cell
// splitting and a cap on surface evaluations (trims make the integrand jump, where splitting
// converges only to first order).
constexpr double kAreaRel = 1e-10;
constexpr int kAreaMaxDepth = 12;
constexpr long kAreaMaxEvaluations = 4'000'000;
// Starting cells: each direction gets at least about kAreaStartPoints Gauss points in all
// (kAreaStartSplitsMax splits of a knot span at most), kAreaTrimmedSplits times more on a
// trimmed face.
constexpr int kAreaStartPoints = 64;
constexpr int kAreaStartSplitsMax = 16;
constexpr int kAreaTrimmedSplits = 4;

// A cell of the area quadrature: its rule's value on its four quarters, their sum and how far
// that sum is from the rule on the whole cell.
struct AreaCell {
  double ua, ub, va, vb;
  double q[4];
  double fine, err;
  int depth;
};

// Global adaptive quadrature of |Su x Sv| over the face: every cell knows its 5 x 5 Gauss
// rule's value and its quarters'; the cell whose two disagree most is split until the
// disagreements add up to the tolerance (a rational surface with extreme weights varies its
// area element by orders of magnitude within a span; the trims make the integrand jump).
template <class Inside>
class AreaQuadrature {
 public:
  AreaQuadrature(const NurbsSurface& s, const Inside& inside, bool trimmed)
      : s_(s), inside_(inside), trimmed_(trimmed) {}

  // The starting cells: each knot span split into su x sv cells (more on a trimmed face).
  void start(const std::vector<double>& bu, const std::vector<double>& bv) {
    const int su = splits(bu), sv = splits(bv);
    const int extra = trimmed_ ? kAreaTrimmedSplits : 1;
    for (size_t i = 0; i + 1 < bu.size(); ++i)
      for (int a = 0; a < su * extra; ++a) {
        const double ua = bu[i] + (bu[i + 1] - bu[i]) * a / (su * extra);
        const double ub = bu[i] + (bu[i + 1] - bu[i]) * (a + 1) / (su * extra);
        for (size_t j = 0; j + 1 < bv.size(); ++j)
          for (int b = 0; b < sv * extra; ++b) {
            const double va = bv[j] + (bv[j + 1] - bv[j]) * b / (sv * extra);
            const double vb = bv[j] + (bv[j + 1] - bv[j]) * (b + 1) / (sv * extra);
            heap_.push_back(make(ua, ub, va, vb, rule(ua, ub, va, vb), 0));
            area_ += heap_.back().fine;
            err_ += heap_.back().err;
          }
      }
  }

  // Splits the worst cell until the error is within the tolerance (or the budget is spent).
  double refine() {
    std::make_heap(heap_.begin(), heap_.end(), worse);
    while (!heap_.empty() && err_ > kAreaRel * std::abs(area_) && budget_ > 0) {
      std::pop_heap(heap_.begin(), heap_.end(), worse);
      const AreaCell c = heap_.back();
      heap_.pop_back();
      area_ -= c.fine;
      err_ -= c.err;
      if (c.depth >= kAreaMaxDepth) {  // kept as it is, its error counted no more
        area_ += c.fine;
        continue;
      }
      const double um = 0.5 * (c.ua + c.ub), vm = 0.5 * (c.va + c.vb);
      const AreaCell kids[4] = {make(c.ua, um, c.va, vm, c.q[0], c.depth + 1),
                                make(um, c.ub, c.va, vm, c.q[1], c.depth + 1),
                                make(c.ua, um, vm, c.vb, c.q[2], c.depth + 1),
                                make(um, c.ub, vm, c.vb, c.q[3], c.depth + 1)};
      for (const AreaCell& k : kids) {
        area_ += k.fine;
        err_ += k.err;
        heap_.push_back(k);
        std::push_heap(heap_.begin(), heap_.end(), worse);
      }
    }
    return area_;
  }

 private:
  static bool worse(const AreaCell& x, const AreaCell& y) { return x.err < y.err; }

  // Splits of each knot span per direction: about kAreaStartPoints Gauss points in all.
  static int splits(const std::vector<double>& breaks) {
    return std::clamp(kAreaStartPoints / (5 * static_cast<int>(breaks.size() - 1)) + 1, 1,
                      kAreaStartSplitsMax);
  }

  // The 5 x 5 Gauss rule on the cell [ua, ub] x [va, vb], points off the trims left out.
  double rule(double ua, double ub, double va, double vb) {
    double cell = 0.0;
    for (int gi = 0; gi < 5; ++gi) {
      const double u = 0.5 * (ua + ub) + 0.5 * (ub - ua) * detail::kGauss5X[gi];
      for (int gj = 0; gj < 5; ++gj) {
        const double v = 0.5 * (va + vb) + 0.5 * (vb - va) * detail::kGauss5X[gj];
        if (trimmed_ && !inside_(Vec2(u, v))) continue;
        const SurfaceEval1 e = s_.eval1(u, v);
        --budget_;
        if (e.ok) cell += detail::kGauss5W[gi] * detail::kGauss5W[gj] * e.du.cross(e.dv).norm();
      }
    }
    return cell * 0.25 * (ub - ua) * (vb - va);
  }

  AreaCell make(double ua, double ub, double va, double vb, double whole, int depth) {
    const double um = 0.5 * (ua + ub), vm = 0.5 * (va + vb);
    AreaCell c{
        ua,
        ub,
        va,
        vb,
        {rule(ua, um, va, vm), rule(um, ub, va, vm), rule(ua, um, vm, vb), rule(um, ub, vm, vb)},
        0.0,
        0.0,
        depth};
    c.fine = c.q[0] + c.q[1] + c.q[2] + c.q[3];
    c.err = std::abs(c.fine - whole);
    return c;
  }

  const NurbsSurface& s_;
  const Inside& inside_;
  bool trimmed_;
  long budget_ = kAreaMaxEvaluations;
  std::vector<AreaCell> heap_;
  double area_ = 0.0, err_ = 0.0;
};

}  // namespace

double Face::compute_area() const {
  const auto& s = *surface_;
  const auto& d = s.domain();
  // A natural boundary given as a loop (a shell's face tagged with its shared edges) bounds
  // the whole domain: no trim to test, no jump to refine.
  const bool trimmed = !loops_.empty() && !natural_;
  const auto inside = [this, trimmed](const Vec2& uv) { return !trimmed || inside_trims(uv); };
  AreaQuadrature<decltype(inside)> q(s, inside, trimmed);
  q.start(detail::breakpoints(s.data().knots_u, d.u0, d.u1),
          detail::breakpoints(s.data().knots_v, d.v0, d.v1));
  return q.refine();
}

}  // namespace plyfit

namespace plyfit {

namespace {

// boundary_area: the Gauss cells per knot span of the inner integral (in u) and of the outer
// one (a loop's segment is divided so that no piece spans more than that share of a v span).
constexpr int kInnerCellsPerSpan = 4;
constexpr int kOuterCellsPerSpan = 4;
// A piece of a loop's segment shorter than a cell over this in both u and v gets the 2-point
// rule: its error, (h / cell)^4 / 4320 of the piece's share, is below 1e-10 of it; the 5-point
// rule everywhere made this integral most of bound_mold()'s time (a densified boundary has
// thousands of short segments per face).
constexpr double kShortPieceCells = 32.0;

// F(u, v) = integral of |Su x Sv|(s, v) ds from the domain's u0 to u, by 5-point Gauss rules on
// kInnerCellsPerSpan cells of each knot span (the area element is smooth within a span).
double area_column(const NurbsSurface& s, const std::vector<double>& breaks, double u, double v) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size() && breaks[i] < u; ++i) {
    const double lo = breaks[i], hi = std::min(breaks[i + 1], u);
    for (int c = 0; c < kInnerCellsPerSpan; ++c) {
      const double a = lo + (hi - lo) * c / kInnerCellsPerSpan;
      const double b = lo + (hi - lo) * (c + 1) / kInnerCellsPerSpan;
      for (int g = 0; g < 5; ++g) {
        const SurfaceEval1 e = s.eval1(0.5 * (a + b) + 0.5 * (b - a) * detail::kGauss5X[g], v);
        if (e.ok) sum += 0.5 * (b - a) * detail::kGauss5W[g] * e.du.cross(e.dv).norm();
      }
    }
  }
  return sum;
}

// The parameters t in (0, 1) where a + t (b - a) crosses one of `breaks` in coordinate `axis`.
void crossings(const Vec2& a, const Vec2& b, int axis, const std::vector<double>& breaks,
               std::vector<double>& ts) {
  const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
  for (double k : breaks)
    if (k > lo && k < hi) ts.push_back((k - a[axis]) / (b[axis] - a[axis]));
}

}  // namespace

double boundary_area(const NurbsSurface& s, const std::vector<std::vector<Vec2>>& loops) {
  const auto& d = s.domain();
  const auto knots_u = detail::breakpoints(s.data().knots_u, d.u0, d.u1);
  const auto knots_v = detail::breakpoints(s.data().knots_v, d.v0, d.v1);
  const auto spans = [](const std::vector<double>& b) {
    return static_cast<double>(std::max<std::size_t>(1, b.size() - 1));
  };
  const double cell_u = d.width_u() / (spans(knots_u) * kInnerCellsPerSpan);
  const double cell_v = d.width_v() / (spans(knots_v) * kOuterCellsPerSpan);
  double total = 0.0;
  std::vector<double> ts;
  for (const auto& loop : loops) {
    if (loop.empty()) continue;
    // Green's theorem: the area is the loop's integral of F(u, v) dv, F the column integral
    // from any u (a function of v alone integrates to 0 round a closed loop): from the loop's
    // least u, so that the columns span the loop's width, not the domain's.
    double u_ref = loop.front().x();
    for (const Vec2& p : loop) u_ref = std::min(u_ref, p.x());
    std::vector<double> breaks{u_ref};
    for (double b : knots_u)
      if (b > u_ref) breaks.push_back(b);
    const auto piece_integral = [&](const Vec2& a, const Vec2& b) {
      const Vec2 mid = 0.5 * (a + b), half = 0.5 * (b - a);
      double sum = 0.0;
      if (std::abs(b.x() - a.x()) * kShortPieceCells <= cell_u &&
          std::abs(b.y() - a.y()) * kShortPieceCells <= cell_v) {
        for (double x : detail::kGauss2X) {
          const Vec2 p = mid + half * x;
          sum += area_column(s, breaks, p.x(), p.y());
        }
      } else {
        for (int g = 0; g < 5; ++g) {
          const Vec2 p = mid + half * detail::kGauss5X[g];
          sum += detail::kGauss5W[g] * area_column(s, breaks, p.x(), p.y());
        }
      }
      return half.y() * sum;
    };
    for (std::size_t k = 0, n = loop.size(); k < n; ++k) {
      const Vec2 a = loop[k], b = loop[(k + 1) % n];
      if (a.y() == b.y()) continue;
      // F is smooth only within a knot span (it has a kink where the segment crosses a knot
      // of a C0 or C1 surface): the segment is cut at the knots it crosses, and into pieces
      // of at most a cell in v.
      ts.assign({0.0, 1.0});
      crossings(a, b, 0, knots_u, ts);
      crossings(a, b, 1, knots_v, ts);
      const int pieces = static_cast<int>(std::ceil(std::abs(b.y() - a.y()) / cell_v));
      for (int c = 1; c < pieces; ++c) ts.push_back(static_cast<double>(c) / pieces);
      std::sort(ts.begin(), ts.end());
      for (std::size_t i = 0; i + 1 < ts.size(); ++i)
        if (ts[i + 1] > ts[i])
          total += piece_integral(a + (b - a) * ts[i], a + (b - a) * ts[i + 1]);
    }
  }
  return std::abs(total);
}

}  // namespace plyfit
