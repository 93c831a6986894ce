// Darts: the curves on the surface, the crossing test the scan asks, and the cut lines.
#include "drape/darts.hpp"
#include "geometry/numeric.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace plyfit::detail {

namespace {

MessageValue number(std::size_t k) {
  return static_cast<std::int64_t>(k);
}

std::string point_text(const Vec3& p) {
  return std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z());
}

// The curve's points projected onto the surface, with points added between them so that none
// is more than `step` from the next (each added point projected too).
Result<DartCurve> follow_curve(const DrapeSurface& s, const std::vector<Vec3>& given, std::size_t k,
                               double step, double on_mold) {
  DartCurve c;
  auto add = [&](const Vec3& p, bool check) -> Status {
    const Projection pr = s.project(p);
    if (!pr.ok || (check && pr.distance > on_mold))
      return Error{ErrorCode::kDartOffMold,
                   "dart",
                   {number(k + 1), pr.ok ? pr.distance : -1.0, on_mold, point_text(p)}};
    c.add(pr.point, s.normal(pr.at).n);
    return ok_status();
  };
  for (std::size_t i = 0; i < given.size(); ++i) {
    if (i > 0) {
      const Vec3 a = given[i - 1], b = given[i];
      const int pieces = static_cast<int>(std::ceil((b - a).norm() / step));
      for (int m = 1; m < pieces; ++m)
        if (auto st = add(a + (b - a) * (double(m) / pieces), false); !st) return st.error();
    }
    if (auto st = add(given[i], true); !st) return st.error();
  }
  if (c.points.size() < 2)
    return Error{ErrorCode::kDartCurvePoints, "dart", {number(k + 1), number(c.points.size())}};
  return c;
}

// Distance from p to the segment a-b.
double segment_distance(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 e = b - a;
  const double ee = e.squaredNorm();
  const double t = ee > 0.0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (p - (a + t * e)).norm();
}

}  // namespace

void DartCurve::add(const Vec3& p, const Vec3& n, std::uint64_t link) {
  if (!points.empty() && (p - points.back()).norm() == 0.0) return;
  if (link != kNoLink) links.resize(points.size(), kNoLink);
  if (!links.empty()) links.push_back(link);
  if (points.empty()) lo = hi = p;
  if (!points.empty()) length += (p - points.back()).norm();
  lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  points.push_back(p);
  normals.push_back(n);
}

namespace {

// A walk's step is projected by Gauss-Newton from the last point's location while it settles
// within kWalkSettleSteps steps to kWalkSettleRel of the walk's step (the global projection
// otherwise: past the face's edge, or where it does not settle).
constexpr int kWalkSettleSteps = 8;
constexpr double kWalkSettleRel = 1e-9;

// The point of `s` nearest to t, by Gauss-Newton from `at` across the shell's shared edges
// (DrapeSurface::locate); none when it does not settle to `tol` or leaves the surface.
std::optional<Projection> project_near(const DrapeSurface& s, SurfaceLocation at, const Vec3& t,
                                       double tol) {
  for (int k = 0; k < kWalkSettleSteps; ++k) {
    const SurfaceEval1 e = s.eval1(at);
    if (!e.ok) return std::nullopt;
    const Vec2 step = detail::metric_solve(e, t - e.p);
    at = s.locate(at, at.uv + step);
    if ((e.du * step.x() + e.dv * step.y()).norm() > tol) continue;
    const SurfaceEval1 f = s.eval1(at);
    if (!f.ok || !s.contains(at)) return std::nullopt;
    return Projection{at, f.p, (t - f.p).norm(), true};
  }
  return std::nullopt;
}

}  // namespace

// Each step projected, the direction kept along the last step.
WalkEnd walk_on_surface(const DrapeSurface& s, Vec3 p, Vec3 dir, double h, double length,
                        DartCurve& c) {
  return walk_on_surface(s, p, dir, h, length, c, nullptr);
}

WalkEnd walk_on_surface(const DrapeSurface& s, Vec3 p, Vec3 dir, double h, double length,
                        DartCurve& c, const std::function<bool(const Vec3&)>& enough) {
  const int steps = static_cast<int>(std::ceil(length / h));
  std::optional<SurfaceLocation> at;  // the last point's, once projected
  for (int k = 0; k < steps; ++k) {
    const Vec3 target = p + h * dir.normalized();
    std::optional<Projection> near =
        at ? project_near(s, *at, target, kWalkSettleRel * h) : std::nullopt;
    const Projection pr = near ? *near : s.project(target);
    at = pr.at;
    // A crease the surface turns away at: the step lands farther than its length from it.
    if (!pr.ok || pr.distance > h) return WalkEnd::kCrease;
    // The face's edge: the step, projected, is shorter than half its length.
    const Vec3 step = pr.point - p;
    if (step.norm() < 0.5 * h) return WalkEnd::kEdge;
    const SurfaceNormal n = s.normal(pr.at);
    if (!n.ok) return WalkEnd::kCrease;
    c.add(pr.point, n.n);
    dir = step;
    p = pr.point;
    if (enough && enough(p)) break;
  }
  return WalkEnd::kLength;
}

Result<DartSet> DartSet::create(const DrapeSurface& s, const std::vector<std::vector<Vec3>>& darts,
                                double d, const Tolerances& tol) {
  std::vector<DartCurve> curves;
  const double on_mold = tol.boundary_on_mold_rel * s.size();
  for (std::size_t k = 0; k < darts.size(); ++k) {
    const auto& given = darts[k];
    const bool finite =
        std::all_of(given.begin(), given.end(), [](const Vec3& p) { return p.allFinite(); });
    if (given.size() < 2 || !finite)
      return Error{ErrorCode::kDartCurvePoints, "dart", {number(k + 1), number(given.size())}};
    auto c = follow_curve(s, given, k, kDartStepRel * d, on_mold);
    if (!c) return c.error();
    curves.push_back(std::move(c).value());
  }
  return of(std::move(curves), d);
}

DartSet DartSet::of(std::vector<DartCurve> curves, double d) {
  DartSet set;
  set.curves_ = std::move(curves);
  set.d_ = d;
  set.index();
  return set;
}

void DartSet::index() {
  const double reach = kDartNearRel * d_;
  for (std::size_t c = 0; c < curves_.size(); ++c) {
    const auto& pts = curves_[c].points;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      segments_.push_back({static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(k)});
      segment_max_ = std::max(segment_max_, (pts[k + 1] - pts[k]).norm());
    }
  }
  const CubeKeys cubes{reach};
  segment_cubes_ = FrozenGrid(reach, static_cast<std::uint32_t>(segments_.size()),
                              [&](std::uint32_t i, auto&& emit) {
                                const auto& pts = curves_[segments_[i].curve].points;
                                const std::size_t k = segments_[i].k;
                                cubes.in_box(pts[k].cwiseMin(pts[k + 1]).array() - reach,
                                             pts[k].cwiseMax(pts[k + 1]).array() + reach, emit);
                              });
}

double DartSet::distance(const Segment& g, const Vec3& p) const {
  const auto& pts = curves_[g.curve].points;
  return segment_distance(pts[g.k], pts[g.k + 1], p);
}

bool DartSet::near(const Vec3& p) const {
  const double reach = kDartNearRel * d_;
  const auto segs = segment_cubes_.in(p);
  return std::any_of(segs.begin(), segs.end(),
                     [&](std::uint32_t i) { return distance(segments_[i], p) <= reach; });
}

int DartSet::nearest(const Vec3& p) const {
  int best = -1;
  double best_d = kDartNearRel * d_;
  for (std::uint32_t i : segment_cubes_.in(p))
    if (const double dist = distance(segments_[i], p); dist <= best_d)
      best = static_cast<int>(segments_[i].curve), best_d = dist;
  return best;
}

// A segment of a dart crossing the link p-q passes within |p - q| plus the normal reach plus
// its own length of p: within kDartNearRel * d (the index's reach) for links and neighbours
// two links apart; a longer segment p-q is tested against every segment.
bool DartSet::crosses(const Vec3& p, const Vec3& q) const {
  const double within = (q - p).norm() + kDartOffsetRel * d_ + segment_max_;
  if (within <= kDartNearRel * d_) {
    const auto segs = segment_cubes_.in(p);
    return std::any_of(segs.begin(), segs.end(), [&](std::uint32_t i) {
      return crosses(curves_[segments_[i].curve], segments_[i].k, p, q);
    });
  }
  for (const DartCurve& c : curves_)
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k)
      if (crosses(c, k, p, q)) return true;
  return false;
}

// The link p-q crosses segment k of curve c: in the tangent plane of the segment (the mean of
// its ends' normals) p and q lie on two sides of the segment's line, the crossing falls
// within the segment (half-open, so that a crossing at a shared point counts once), and the
// link passes within kDartOffsetRel * d of it along the normal.
bool DartSet::crosses(const DartCurve& c, std::size_t k, const Vec3& p, const Vec3& q) const {
  const double reach = kDartOffsetRel * d_;
  const Vec3& c0 = c.points[k];
  const Vec3& c1 = c.points[k + 1];
  const Vec3 lo = p.cwiseMin(q).array() - reach, hi = p.cwiseMax(q).array() + reach;
  if ((lo.array() > c0.cwiseMax(c1).array()).any() || (hi.array() < c0.cwiseMin(c1).array()).any())
    return false;
  const Vec3 n = (c.normals[k] + c.normals[k + 1]).normalized();
  Vec3 e1 = c1 - c0;
  e1 -= e1.dot(n) * n;
  const double len = e1.norm();
  if (!(len > 0.0) || !n.allFinite()) return false;
  e1 /= len;
  const Vec3 e2 = n.cross(e1);
  const double op = (p - c0).dot(e2), oq = (q - c0).dot(e2);
  if ((op >= 0.0) == (oq >= 0.0)) return false;
  const double f = op / (op - oq);  // where the link meets the segment's line
  const double t = ((p - c0).dot(e1) + f * (q - p).dot(e1)) / len;
  const bool last = k + 2 == c.points.size();
  if (t < 0.0 || t > 1.0 || (t == 1.0 && !last)) return false;
  const double h = (p - c0).dot(n) + f * (q - p).dot(n);
  return std::abs(h) <= reach;
}

namespace {

// A dart's cut line moves in the ply by at most this many times the curve's step on the part
// (a cell sheared to 30 degrees stretches a step by 2.7 in the ply) plus kCutLineSlackRel * d
// (the line passing from one node's cells to the next node's); more is a jump onto cloth
// from elsewhere in the ply.
constexpr double kCutLineJump = 4.0;
constexpr double kCutLineSlackRel = 2.0;

// The ply point of p carried through the cell corner a and its linked weft and warp
// neighbours (the cell's affine map, least squares in the tangent plane); false where a has
// no such neighbours or its links are sheared flat.
bool carry(const DrapeResult& res, const DrapeNode& a, const Vec3& p, double min_sin2, Vec2& out) {
  const DrapeNode* b = res.linked(a, ThreadDir::kPlusX);
  if (!b || !b->mapped()) b = res.linked(a, ThreadDir::kMinusX);
  const DrapeNode* c = res.linked(a, ThreadDir::kPlusY);
  if (!c || !c->mapped()) c = res.linked(a, ThreadDir::kMinusY);
  if (!b || !c || !b->mapped() || !c->mapped()) return false;
  const Vec3 e1 = b->point - a.point, e2 = c->point - a.point, r = p - a.point;
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > min_sin2 * g11 * g22)) return false;
  const double s = (g22 * e1.dot(r) - g12 * e2.dot(r)) / det;
  const double t = (g11 * e2.dot(r) - g12 * e1.dot(r)) / det;
  out = a.ply + s * (b->ply - a.ply) + t * (c->ply - a.ply);
  return true;
}

// Quadrilateral area (shoelace, unsigned).
double quad_area(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  return 0.5 * std::abs(cross2(a, b) + cross2(b, c) + cross2(c, d) + cross2(d, a));
}

// The cloth on each side of curve point i (left, right): the nearest mapped node on each side
// within reach.
// Nodes whose normal turns from the curve's by 90 degrees or more lie on another sheet of the
// part (a thin shell's other wall within reach): not the cloth beside the curve.
struct NearNodes {
  FrozenGrid grid;
  std::vector<Vec3> normals;  // per node: zero for a node not in the grid
};

void sides(const DartCurve& c, std::size_t i, const NearNodes& near, const DrapeResult& res,
           double reach, const DrapeNode* best[2]) {
  const Vec3& p = c.points[i];
  const Vec3 t = c.points[std::min(i + 1, c.points.size() - 1)] - c.points[i > 0 ? i - 1 : 0];
  const Vec3 left = c.normals[i].cross(t);
  auto side = [&](const DrapeNode& n) { return (n.point - p).dot(left) >= 0.0 ? 0 : 1; };
  double best_d[2] = {reach, reach};
  near.grid.around(p, [&](std::uint32_t k) {
    const DrapeNode& n = res.nodes[k];
    const double dist = (n.point - p).norm();
    if (near.normals[k].dot(c.normals[i]) > 0.0 && dist < best_d[side(n)])
      best_d[side(n)] = dist, best[side(n)] = &n;
  });
}

// A seam's cut lines: the fronts on its two sides are ply neighbours, so in the flat pattern it
// is a slit through the middles of the links it cut (both lines), in the order of its points
// (the points between them have no link). On the part each link is off its rest length: the
// fronts leave a gap (opening_area) or lie on each other (removed_area), a strip of the
// link's rest length across the seam per link.
void seam_lines(const DartCurve& c, const DrapeResult& res, DartResult& out) {
  for (std::uint64_t link : c.links) {
    if (link == DartCurve::kNoLink) continue;
    const DrapeNode& a = res.nodes[link >> 32];
    const DrapeNode& b = res.nodes[link & 0xffffffffu];
    if (!a.mapped() || !b.mapped()) continue;
    const Vec2 mid = 0.5 * (a.ply + b.ply);
    out.line_left.push_back(mid);
    out.line_right.push_back(mid);
    const double rest = (b.ply - a.ply).norm(), off = (b.point - a.point).norm() - rest;
    (off > 0.0 ? out.opening_area : out.removed_area) += std::abs(off) * rest;
  }
}

// The dart's cut lines: each curve point carried through the cloth on each side (sides()) and
// its cells; points with no cloth on one side are left out. The area between the lines, per
// pair of points, is cut out where the right side's line lies away from the left side's
// cloth, and a gap on the part where it lies in it.
void cut_lines(const DartCurve& c, const NearNodes& near, const DrapeResult& res, double reach,
               double min_sin2, DartResult& out) {
  struct Pair {
    Vec3 p;
    Vec2 l, r;
    double away;  // right line's offset away from the left cloth
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const Vec3& p = c.points[i];
    const DrapeNode* best[2] = {nullptr, nullptr};
    sides(c, i, near, res, reach, best);
    Vec2 l, r;
    if (!best[0] || !best[1] || !carry(res, *best[0], p, min_sin2, l) ||
        !carry(res, *best[1], p, min_sin2, r))
      continue;
    const Vec2 cloth = best[0]->ply - l;
    const double cn = cloth.norm();
    pairs.push_back({p, l, r, cn > 0.0 ? -(r - l).dot(cloth) / cn : 0.0});
  }
  // The longest run of pairs each of whose lines moves in the ply by no more than
  // kCutLineJump times the curve's step on the part plus kCutLineSlackRel * d: where the
  // nearest node on a side is cloth that came round from elsewhere in the ply (a closed
  // shell's fronts), the line jumps across the pattern.
  const double slack = kCutLineSlackRel * res.ply->d();
  std::size_t best_first = 0, best_size = pairs.empty() ? 0 : 1;
  for (std::size_t first = 0, k = 1; k <= pairs.size(); ++k) {
    const bool joined = k < pairs.size() && [&] {
      const double jump = kCutLineJump * (pairs[k].p - pairs[k - 1].p).norm() + slack;
      return (pairs[k].l - pairs[k - 1].l).norm() <= jump &&
             (pairs[k].r - pairs[k - 1].r).norm() <= jump;
    }();
    if (joined) continue;
    if (k - first > best_size) best_first = first, best_size = k - first;
    first = k;
  }
  for (std::size_t k = best_first; k < best_first + best_size; ++k) {
    out.line_left.push_back(pairs[k].l);
    out.line_right.push_back(pairs[k].r);
    out.width_max = std::max(out.width_max, (pairs[k].r - pairs[k].l).norm());
  }
  const auto& L = out.line_left;
  const auto& R = out.line_right;
  for (std::size_t i = 0; i + 1 < L.size(); ++i) {
    const double a = quad_area(L[i], L[i + 1], R[i + 1], R[i]);
    const double away = pairs[best_first + i].away + pairs[best_first + i + 1].away;
    (away >= 0.0 ? out.removed_area : out.opening_area) += a;
  }
}

}  // namespace

void lay_darts(const DrapeSurface& s, const DartSet& darts,
               const std::vector<std::uint64_t>& cut_out, const Tolerances& tol, DrapeResult& res) {
  if (darts.empty()) return;
  const double d = res.ply->d();
  const double reach = kDartNearRel * d;
  std::vector<Vec3> normals(res.nodes.size(), Vec3::Zero());
  for (std::uint32_t k = 0; k < res.nodes.size(); ++k) {
    const DrapeNode& n = res.nodes[k];
    if (!n.mapped() || !darts.near(n.point)) continue;
    if (const SurfaceNormal normal = s.normal(n.at()); normal.ok) normals[k] = normal.n;
  }
  const auto in_grid = [&](std::uint32_t k) { return normals[k] != Vec3::Zero(); };
  // (The grid is made before the normals move into the struct: aggregate initialisers run in
  // order.)
  const NearNodes near{FrozenGrid(reach, static_cast<std::uint32_t>(res.nodes.size()), in_grid,
                                  [&](std::uint32_t k) { return res.nodes[k].point; }),
                       std::move(normals)};
  const double min_sin2 = std::pow(std::sin(tol.fold_angle), 2);
  for (std::size_t k = 0; k < darts.curves().size(); ++k) {
    const DartCurve& c = darts.curves()[k];
    DartResult out;
    out.curve = c.points;
    out.length = c.length;
    out.tip = c.points.back();
    out.nodes_cut_out = k < cut_out.size() ? cut_out[k] : 0;
    if (c.links.empty())
      cut_lines(c, near, res, reach, min_sin2, out);
    else
      seam_lines(c, res, out);
    res.darts.push_back(std::move(out));
  }
  for (std::uint64_t key : res.cut_links) {
    const DrapeNode& a = res.nodes[key >> 32];
    const DrapeNode& b = res.nodes[key & 0xffffffffu];
    if (!a.mapped() || !b.mapped()) continue;
    const Vec3 mid = 0.5 * (a.point + b.point);
    const int k = darts.nearest(mid);
    if (k >= 0) ++res.darts[static_cast<std::size_t>(k)].links_cut;
  }
}

}  // namespace plyfit::detail
