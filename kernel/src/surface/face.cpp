#include "surface/face.hpp"

#include "surface/poles.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <string>

namespace plyfit {

namespace {

// Twice the signed area of a closed (u, v) polyline (shoelace).
double polygon_area2(const std::vector<Vec2>& pts) {
  double a = 0.0;
  for (std::size_t k = 0, m = pts.size() - 1; k < pts.size(); m = k++)
    a += pts[m].x() * pts[k].y() - pts[k].x() * pts[m].y();
  return a;
}

// 5-point Gauss-Legendre rule on [-1, 1].
constexpr double kGaussX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
constexpr double kGaussW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                               0.4786286704993665, 0.2369268850561891};

// Projection: Levenberg-Marquardt iteration cap and damping schedule (relative to the
// diagonal of the Gauss-Newton matrix).
constexpr int kProjectMaxIterations = 200;
constexpr double kProjectDampingStart = 1e-6;
constexpr double kProjectDampingUp = 8.0;
constexpr double kProjectDampingDown = 0.25;
constexpr double kProjectMaxDamping = 1e16;
// A boundary segment shorter than this in 3D, relative to the face size, is a collapsed edge
// (a pole): no boundary of the face.
constexpr double kCollapsedRel = 1e-9;
// Face::compute_area: relative tolerance of the adaptive quadrature, the depth of cell
// splitting and a cap on surface evaluations (trims make the integrand jump, where splitting
// converges only to first order).
constexpr double kAreaRel = 1e-10;
constexpr int kAreaMaxDepth = 12;
constexpr long kAreaMaxEvaluations = 4'000'000;
// Grid over the trim loops' box for contains(): about this many cells per direction per
// square root of the segment count, within bounds.
constexpr double kCellsPerSegmentRoot = 4.0;
constexpr int kCellsMin = 64;
constexpr int kCellsMax = 512;
// Relative widening of a segment's box when marking the cells it touches.
constexpr double kCellPadRel = 1e-6;

// Distinct knot values inside the domain: the breakpoints of the polynomial pieces.
std::vector<double> breakpoints(const std::vector<double>& knots, double a, double b) {
  std::vector<double> out;
  for (double k : knots)
    if (k >= a && k <= b && (out.empty() || k > out.back())) out.push_back(k);
  return out;
}

}  // namespace

Result<Face> Face::create(FaceData data, const Tolerances& tol) {
  auto surf = NurbsSurface::create(std::move(data.surface), tol);
  if (!surf) return surf.error();
  Face f;
  f.surface_ = std::make_shared<const NurbsSurface>(std::move(surf).value());
  f.tol_ = tol;
  f.reversed_ = data.reversed;
  f.closed_u_ = data.closed_u;
  f.closed_v_ = data.closed_v;
  f.name_ = std::move(data.name);
  for (size_t l = 0; l < data.loops.size(); ++l) {
    auto& loop = data.loops[l];
    // Drop a repeated closing point (and the tag of the segment from it back to the start).
    if (loop.points.size() > 1 && loop.points.front() == loop.points.back()) {
      loop.points.pop_back();
      if (loop.edges.size() > loop.points.size()) loop.edges.pop_back();
    }
    if (!loop.edges.empty() && loop.edges.size() != loop.points.size())
      return Error{"trim loop " + std::to_string(l) + " has " + std::to_string(loop.edges.size()) +
                   " edge tags for " + std::to_string(loop.points.size()) + " segments"};
    if (loop.points.size() < 3)
      return Error{"trim loop " + std::to_string(l) + " has fewer than 3 points"};
    for (const auto& p : loop.points)
      if (!p.allFinite())
        return Error{"trim loop " + std::to_string(l) + " has a non-finite point"};
  }
  f.loops_ = std::move(data.loops);
  f.build_slabs();
  // A single loop along the domain's border (a natural boundary given as a loop, e.g. to tag
  // a shell's shared edges) bounds the whole domain: contains() needs only the domain test.
  if (f.loops_.size() == 1) {
    const auto& d = f.domain();
    const double eu = tol.param_rel * d.width_u(), ev = tol.param_rel * d.width_v();
    bool border = true;
    for (const Vec2& p : f.loops_[0].points)
      border = border && (std::abs(p.x() - d.u0) <= eu || std::abs(p.x() - d.u1) <= eu ||
                          std::abs(p.y() - d.v0) <= ev || std::abs(p.y() - d.v1) <= ev);
    f.natural_ = border;
  }
  if (f.loops_.size() > 1) {  // holes: the outer loop is the one of largest (u, v) area
    double best = -1.0;
    for (std::size_t l = 0; l < f.loops_.size(); ++l) {
      const double a = std::abs(polygon_area2(f.loops_[l].points));
      if (a > best) {
        best = a;
        f.outer_ = static_cast<int>(l);
      }
    }
  }
  // Bounding box from samples on the face (control boxes can be far larger).
  for (const auto& s : sample_face(f, 33)) f.bbox_.add(s.second);
  if (f.bbox_.empty) return Error{"no point of the face lies inside its trim loops"};
  f.size_ = std::max(f.bbox_.diagonal(), f.surface_->control_bbox().diagonal() * 1e-6);
  if (!(f.size_ > 0.0)) return Error{"the face has zero size"};
  f.area_ = data.area > 0.0 ? data.area : f.compute_area();
  f.poles_ = detail::find_poles(f);
  return f;
}

SurfaceLocation Face::settle(const SurfaceLocation& at, const Vec3& p, double reach) const {
  if (poles_.empty() || contains(at.uv)) return at;
  const Vec2 w = wrap(at.uv);
  for (const Pole& e : poles_) {
    // Only past this pole's collapsed edge: where Newton crossed the pole.
    const double past = e.u_fixed ? w.x() - e.at.uv.x() : w.y() - e.at.uv.y();
    if (past * e.inward >= 0.0) continue;
    const auto loc = detail::locate_through_pole(*this, e, p, tol_);
    if (!loc || !contains(loc->uv)) continue;
    const SurfaceEval1 ev = eval1(*loc);
    if (ev.ok && (ev.p - p).norm() <= reach) return {loc->uv, at.face};
  }
  return at;
}

std::vector<std::vector<Vec2>> Face::boundary_loops() const {
  std::vector<std::vector<Vec2>> out;
  if (loops_.empty()) {
    const auto& d = domain();
    out.push_back({Vec2(d.u0, d.v0), Vec2(d.u1, d.v0), Vec2(d.u1, d.v1), Vec2(d.u0, d.v1)});
    return out;
  }
  for (const auto& l : loops_) out.push_back(l.points);
  return out;
}

std::vector<BoundaryLoop> Face::boundary() const {
  std::vector<BoundaryLoop> out;
  const auto& d = domain();
  // On-seam test: rounding of the domain's bounds.
  const double eu = d.width_u() * tol_.param_rel, ev = d.width_v() * tol_.param_rel;
  auto on = [](double x, double y, double e) { return std::abs(x - y) <= e; };
  for (const auto& loop : boundary_loops()) {
    BoundaryLoop b;
    const size_t n = loop.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2 a = loop[k], c = loop[(k + 1) % n];
      b.points.emplace_back(a);
      BoundaryLoop::Kind kind = BoundaryLoop::kEdge;
      if ((closed_u_ && ((on(a.x(), d.u0, eu) && on(c.x(), d.u0, eu)) ||
                         (on(a.x(), d.u1, eu) && on(c.x(), d.u1, eu)))) ||
          (closed_v_ && ((on(a.y(), d.v0, ev) && on(c.y(), d.v0, ev)) ||
                         (on(a.y(), d.v1, ev) && on(c.y(), d.v1, ev))))) {
        kind = BoundaryLoop::kSeam;
      } else {
        const SurfaceEval1 ea = eval1(a), em = eval1(0.5 * (a + c)), ec = eval1(c);
        const double len = (em.p - ea.p).norm() + (ec.p - em.p).norm();
        if (ea.ok && em.ok && ec.ok && len <= kCollapsedRel * size_)
          kind = BoundaryLoop::kCollapsed;
      }
      b.kinds.push_back(kind);
    }
    out.push_back(std::move(b));
  }
  return out;
}

void Face::build_slabs() {
  segs_.clear();
  slabs_.clear();
  if (loops_.empty()) return;
  loops_min_ = loops_max_ = loops_.front().points.front();
  for (const auto& l : loops_) {
    const size_t n = l.points.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2& a = l.points[k];
      const Vec2& b = l.points[(k + 1) % n];
      loops_min_ = loops_min_.cwiseMin(a);
      loops_max_ = loops_max_.cwiseMax(a);
      if (a.y() != b.y()) segs_.push_back({a, b});  // horizontal edges never cross the ray
    }
  }
  const int nslab =
      std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segs_.size()))), 1, 4096);
  slab_v0_ = loops_min_.y();
  slab_h_ = std::max((loops_max_.y() - loops_min_.y()) / nslab, 1e-300);
  slabs_.assign(nslab, {});
  for (int s = 0; s < static_cast<int>(segs_.size()); ++s) {
    const double lo = std::min(segs_[s].a.y(), segs_[s].b.y());
    const double hi = std::max(segs_[s].a.y(), segs_[s].b.y());
    const int k0 =
        std::clamp(static_cast<int>(std::floor((lo - slab_v0_) / slab_h_)), 0, nslab - 1);
    const int k1 =
        std::clamp(static_cast<int>(std::floor((hi - slab_v0_) / slab_h_)), 0, nslab - 1);
    for (int k = k0; k <= k1; ++k) slabs_[k].push_back(s);
  }
  // Cells of the loops' box that no loop segment touches are wholly inside or outside: their
  // centre's answer holds for all their points, and contains() needs no crossing count there.
  cells_n_ = std::clamp(
      static_cast<int>(kCellsPerSegmentRoot * std::sqrt(static_cast<double>(segs_.size() + 1))),
      kCellsMin, kCellsMax);
  cell_size_ = ((loops_max_ - loops_min_) / cells_n_).cwiseMax(Vec2::Constant(1e-300));
  cells_.assign(static_cast<std::size_t>(cells_n_) * cells_n_, kCellUnknown);
  auto cell = [&](double x, double o, double c) {
    return std::clamp(static_cast<int>(std::floor((x - o) / c)), 0, cells_n_ - 1);
  };
  for (const auto& l : loops_) {
    const size_t n = l.points.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2 lo = l.points[k].cwiseMin(l.points[(k + 1) % n]);
      const Vec2 hi = l.points[k].cwiseMax(l.points[(k + 1) % n]);
      // The segment's box widened by a hair: a point on a cell's border, which rounding may
      // put in either cell, is tested exactly.
      const Vec2 pad = kCellPadRel * cell_size_;
      const int i0 = cell(lo.x() - pad.x(), loops_min_.x(), cell_size_.x());
      const int i1 = cell(hi.x() + pad.x(), loops_min_.x(), cell_size_.x());
      const int j0 = cell(lo.y() - pad.y(), loops_min_.y(), cell_size_.y());
      const int j1 = cell(hi.y() + pad.y(), loops_min_.y(), cell_size_.y());
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j)
          cells_[static_cast<std::size_t>(i) * cells_n_ + j] = kCellBoundary;
    }
  }
  for (int i = 0; i < cells_n_; ++i)
    for (int j = 0; j < cells_n_; ++j) {
      auto& c = cells_[static_cast<std::size_t>(i) * cells_n_ + j];
      if (c == kCellUnknown)
        c = inside_trims(loops_min_ + Vec2((i + 0.5) * cell_size_.x(), (j + 0.5) * cell_size_.y()))
                ? kCellInside
                : kCellOutside;
    }
}

bool Face::inside_trims_fast(const Vec2& uv) const {
  const double u = uv.x(), v = uv.y();
  if (v < loops_min_.y() || v > loops_max_.y() || u < loops_min_.x() || u > loops_max_.x())
    return false;
  const int i =
      std::clamp(static_cast<int>((u - loops_min_.x()) / cell_size_.x()), 0, cells_n_ - 1);
  const int j =
      std::clamp(static_cast<int>((v - loops_min_.y()) / cell_size_.y()), 0, cells_n_ - 1);
  const std::uint8_t c = cells_[static_cast<std::size_t>(i) * cells_n_ + j];
  if (c != kCellBoundary) return c == kCellInside;
  return inside_trims(uv);
}

bool Face::inside_trims(const Vec2& uv) const {
  const double u = uv.x(), v = uv.y();
  if (v < loops_min_.y() || v > loops_max_.y() || u < loops_min_.x() || u > loops_max_.x())
    return false;
  const int k = std::clamp(static_cast<int>(std::floor((v - slab_v0_) / slab_h_)), 0,
                           static_cast<int>(slabs_.size()) - 1);
  bool inside = false;
  for (int s : slabs_[k]) {  // crossing number with half-open edges: robust at vertices
    const Vec2& a = segs_[s].a;
    const Vec2& b = segs_[s].b;
    if ((a.y() > v) != (b.y() > v)) {
      const double x = a.x() + (v - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (u < x) inside = !inside;
    }
  }
  return inside;
}

bool Face::contains(const Vec2& uv) const {
  const Vec2 w = wrap(uv);
  const auto& d = domain();
  if (!d.contains(w.x(), w.y(), tol_.param_rel * d.width_u(), tol_.param_rel * d.width_v()))
    return false;
  return loops_.empty() || natural_ || inside_trims_fast(w);
}

bool Face::in_hole(const Vec2& uv) const {
  if (outer_ < 0) return false;
  const Vec2 w = wrap(uv);
  if (!domain().contains(w.x(), w.y()) || contains(w)) return false;
  const auto& pts = loops_[static_cast<std::size_t>(outer_)].points;
  bool inside = false;  // crossing number, as inside_trims
  for (std::size_t k = 0, m = pts.size() - 1; k < pts.size(); m = k++) {
    const Vec2& a = pts[m];
    const Vec2& b = pts[k];
    if ((a.y() > w.y()) != (b.y() > w.y()) &&
        w.x() < a.x() + (w.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

SurfaceEval1 Face::eval1(const SurfaceLocation& at) const {
  const Vec2 w = wrap(at.uv);
  return surface_->eval1(w.x(), w.y());
}

SurfaceEval2 Face::eval2(const SurfaceLocation& at) const {
  const Vec2 w = wrap(at.uv);
  return surface_->eval2(w.x(), w.y());
}

SurfaceNormal Face::normal(const SurfaceLocation& at) const {
  const Vec2 w = wrap(at.uv);
  SurfaceNormal n = surface_->normal(w.x(), w.y());
  if (reversed_) n.n = -n.n;
  return n;
}

namespace {
// Parameter values covering [a, b]: every knot span gets at least degree + 1 points (so
// strongly non-uniform knot vectors are sampled where the geometry is), n in all at least.
std::vector<double> span_samples(const std::vector<double>& knots, int degree, double a, double b,
                                 int n) {
  const auto br = breakpoints(knots, a, b);
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
  std::vector<std::pair<Vec2, Vec3>> out;
  out.reserve(us.size() * vs.size());
  for (double u : us) {
    for (double v : vs) {
      const Vec2 uv(u, v);
      if (!face.contains(uv)) continue;
      const SurfaceEval1 e = face.eval1(uv);
      if (e.ok) out.emplace_back(uv, e.p);
    }
  }
  return out;
}

double Face::compute_area() const {
  const auto& s = *surface_;
  const auto& d = s.domain();
  const auto bu = breakpoints(s.data().knots_u, d.u0, d.u1);
  const auto bv = breakpoints(s.data().knots_v, d.v0, d.v1);
  // Start from cells that give each direction at least ~64 Gauss points in all, and at most
  // ~512; then refine each cell adaptively: a cell whose 5 x 5 Gauss rule disagrees with the
  // same rule on its four quarters by more than its share of the tolerance is split (a
  // rational surface with extreme weights varies its area element by orders of magnitude
  // within a span; the trims make the integrand jump).
  const int su = std::clamp(64 / (5 * static_cast<int>(bu.size() - 1)) + 1, 1, 16);
  const int sv = std::clamp(64 / (5 * static_cast<int>(bv.size() - 1)) + 1, 1, 16);
  const int extra = loops_.empty() ? 1 : 4;
  long budget = kAreaMaxEvaluations;
  auto rule = [&](double ua, double ub, double va, double vb) {
    double cell = 0.0;
    for (int gi = 0; gi < 5; ++gi) {
      const double u = 0.5 * (ua + ub) + 0.5 * (ub - ua) * kGaussX[gi];
      for (int gj = 0; gj < 5; ++gj) {
        const double v = 0.5 * (va + vb) + 0.5 * (vb - va) * kGaussX[gj];
        if (!loops_.empty() && !inside_trims(Vec2(u, v))) continue;
        const SurfaceEval1 e = s.eval1(u, v);
        --budget;
        if (e.ok) cell += kGaussW[gi] * kGaussW[gj] * e.du.cross(e.dv).norm();
      }
    }
    return cell * 0.25 * (ub - ua) * (vb - va);
  };
  // Global adaptive quadrature: every cell knows its rule's value and its quarters'; the cell
  // whose two disagree most is split until the disagreements add up to the tolerance.
  struct Cell {
    double ua, ub, va, vb;
    double q[4];  // the rule on the quarters
    double fine, err;
    int depth;
  };
  auto make = [&](double ua, double ub, double va, double vb, double whole, int depth) {
    const double um = 0.5 * (ua + ub), vm = 0.5 * (va + vb);
    Cell c{ua,
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
  };
  auto worse = [](const Cell& x, const Cell& y) { return x.err < y.err; };
  std::vector<Cell> heap;
  double area = 0.0, err = 0.0;
  for (size_t i = 0; i + 1 < bu.size(); ++i)
    for (int a = 0; a < su * extra; ++a) {
      const double ua = bu[i] + (bu[i + 1] - bu[i]) * a / (su * extra);
      const double ub = bu[i] + (bu[i + 1] - bu[i]) * (a + 1) / (su * extra);
      for (size_t j = 0; j + 1 < bv.size(); ++j)
        for (int b = 0; b < sv * extra; ++b) {
          const double va = bv[j] + (bv[j + 1] - bv[j]) * b / (sv * extra);
          const double vb = bv[j] + (bv[j + 1] - bv[j]) * (b + 1) / (sv * extra);
          heap.push_back(make(ua, ub, va, vb, rule(ua, ub, va, vb), 0));
          area += heap.back().fine;
          err += heap.back().err;
        }
    }
  std::make_heap(heap.begin(), heap.end(), worse);
  while (!heap.empty() && err > kAreaRel * std::abs(area) && budget > 0) {
    std::pop_heap(heap.begin(), heap.end(), worse);
    const Cell c = heap.back();
    heap.pop_back();
    area -= c.fine;
    err -= c.err;
    if (c.depth >= kAreaMaxDepth) {  // kept as it is, its error counted no more
      area += c.fine;
      continue;
    }
    const double um = 0.5 * (c.ua + c.ub), vm = 0.5 * (c.va + c.vb);
    const Cell kids[4] = {make(c.ua, um, c.va, vm, c.q[0], c.depth + 1),
                          make(um, c.ub, c.va, vm, c.q[1], c.depth + 1),
                          make(c.ua, um, vm, c.vb, c.q[2], c.depth + 1),
                          make(um, c.ub, vm, c.vb, c.q[3], c.depth + 1)};
    for (const Cell& k : kids) {
      area += k.fine;
      err += k.err;
      heap.push_back(k);
      std::push_heap(heap.begin(), heap.end(), worse);
    }
  }
  return area;
}

Projection Face::project(const Vec3& p) const {
  Projection best;
  const auto samples = sample_face(*this, 24);
  if (samples.empty()) return best;
  // Seeds: the few nearest samples.
  std::vector<size_t> order(samples.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const size_t nseed = std::min<size_t>(4, order.size());
  std::partial_sort(order.begin(), order.begin() + nseed, order.end(), [&](size_t a, size_t b) {
    return (samples[a].second - p).squaredNorm() < (samples[b].second - p).squaredNorm();
  });
  for (size_t si = 0; si < nseed; ++si) {
    const Projection q = project_from(p, samples[order[si]].first, true);
    if (q.ok && (!best.ok || q.distance < best.distance)) best = q;
  }
  return best;
}

Projection Face::project_from(const Vec3& p, const Vec2& seed, bool on_face) const {
  Projection out;
  const auto& d = domain();
  const Eigen::Array2d width(d.width_u(), d.width_v());
  Vec2 uv = wrap(seed);
  if (!closed_u_) uv.x() = std::clamp(uv.x(), d.u0, d.u1);
  if (!closed_v_) uv.y() = std::clamp(uv.y(), d.v0, d.v1);
  const SurfaceEval1 e0 = eval1(uv);
  if (!e0.ok) return out;
  double dist = (e0.p - p).norm();
  // Levenberg-Marquardt on |S(u, v) - p|^2 with Marquardt scaling: the full Hessian where
  // it is positive definite, Gauss-Newton elsewhere; damping grows when a step is refused
  // (longer distance or off the face) and shrinks when one is taken.
  double lambda = 0.0;
  for (int it = 0; it < kProjectMaxIterations; ++it) {
    const SurfaceEval2 e = eval2(uv);
    if (!e.ok) break;
    const Vec3 r = e.p - p;
    const Vec2 g(e.du.dot(r), e.dv.dot(r));
    Eigen::Matrix2d A;
    A << e.du.dot(e.du), e.du.dot(e.dv), e.du.dot(e.dv), e.dv.dot(e.dv);
    Eigen::Matrix2d H = A;
    H(0, 0) += r.dot(e.duu);
    H(0, 1) += r.dot(e.duv);
    H(1, 0) += r.dot(e.duv);
    H(1, 1) += r.dot(e.dvv);
    if (!(H.determinant() > 0.0 && H(0, 0) > 0.0)) H = A;
    const Vec2 D(std::max(A(0, 0), 1e-300), std::max(A(1, 1), 1e-300));
    bool taken = false, converged = false;
    while (lambda < kProjectMaxDamping) {
      // Solve in Jacobi-scaled variables: |Su| and |Sv| may differ by many orders.
      const Vec2 sc(1.0 / std::sqrt(D.x()), 1.0 / std::sqrt(D.y()));
      Eigen::Matrix2d M = sc.asDiagonal() * H * sc.asDiagonal();
      M(0, 0) += lambda;
      M(1, 1) += lambda;
      const Vec2 step = -(sc.asDiagonal() * M.fullPivLu().solve(sc.asDiagonal() * g)).eval();
      if (!step.allFinite()) break;
      Vec2 cand = uv + step;
      if (!closed_u_) cand.x() = std::clamp(cand.x(), d.u0, d.u1);
      if (!closed_v_) cand.y() = std::clamp(cand.y(), d.v0, d.v1);
      cand = wrap(cand);
      const bool tiny = (delta(uv, cand).cwiseAbs().array() <= tol_.param_rel * width).all();
      if (tiny) {
        converged = true;
        break;
      }
      if (!on_face || contains(cand)) {
        const SurfaceEval1 c = eval1(cand);
        const double cd = (c.p - p).norm();
        // Near the minimum a step of length h changes the distance by O(h^2), below its
        // rounding: there, a step that keeps the distance and shrinks the (scaled)
        // gradient is progress too.
        const Vec3 rc = c.p - p;
        const double gc =
            std::hypot(c.du.dot(rc) / std::sqrt(D.x()), c.dv.dot(rc) / std::sqrt(D.y()));
        const double g0 = std::hypot(g.x() / std::sqrt(D.x()), g.y() / std::sqrt(D.y()));
        const bool flat = cd <= dist + tol_.roundoff_rel * (p.norm() + dist + size_);
        if (c.ok && (cd < dist || (flat && gc < g0))) {
          uv = cand;
          dist = cd;
          taken = true;
          lambda *= kProjectDampingDown;
          break;
        }
      }
      lambda = lambda == 0.0 ? kProjectDampingStart : lambda * kProjectDampingUp;
    }
    if (!taken || converged) break;
  }
  out.at = SurfaceLocation(uv);
  out.point = eval1(uv).p;
  out.distance = dist;
  out.ok = true;
  return out;
}

}  // namespace plyfit
