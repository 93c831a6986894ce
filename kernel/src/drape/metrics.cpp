// The metrics of §7.1: thread angles (ours by central differences, and the paper's of eq. 12),
// shear energy, the paper's area (mapped crossings), the 2D and 3D areas of the mapped cells,
// and independent residual checks.
#include "drape/metrics.hpp"

#include "drape/net_links.hpp"
#include "drape/solvers/solvers.hpp"
#include "pattern/mapped_cells.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

constexpr double kHalfPi = kPi / 2;

double tri_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}
double tri_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * std::abs(cross2(b - a, c - a));
}

// Thread angles at mapped regular nodes: weft and warp directions by central differences
// where both neighbours along the thread are mapped, one-sided otherwise.
void thread_angles(DrapeResult& res) {
  for (DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    auto direction = [&](ThreadDir plus, Vec3& out) {
      const DrapeNode* p = res.linked(n, plus);
      const DrapeNode* m = res.linked(n, opposite(plus));
      const bool hp = p && p->mapped(), hm = m && m->mapped();
      if (hp && hm)
        out = p->point - m->point;
      else if (hp)
        out = p->point - n.point;
      else if (hm)
        out = n.point - m->point;
      else
        return false;
      return out.norm() > 0.0;
    };
    Vec3 wf, wp;
    if (!direction(ThreadDir::kPlusX, wf) || !direction(ThreadDir::kPlusY, wp)) continue;
    n.thread_angle = std::atan2(wf.cross(wp).norm(), wf.dot(wp));
    n.flags |= DrapeNode::kHasAngle;
  }
}

// The paper's thread angles (eq. 12, as Table 2 reports them): at each mapped node solved from
// a weft and a warp neighbour, the angle between its links to those two as they point (from
// the node to each); and, beside them, the same angle with each link taken along +x or +y
// (oriented: pi minus the paper's at a node solved from its +x and -y neighbours, or -x and
// +y). Min and max of both, the sum of cos^2 and the largest shear (the same for both: cos^2
// and |pi/2 - gamma| do not change under gamma -> pi - gamma). The angle falls as its cosine
// rises, so only the extreme nodes' angles are evaluated (atan2, which stays accurate near 0
// and pi where acos of the cosine would not).
void paper_angles(const DrapeResult& res, DrapeMetrics::PaperFigures& pf) {
  struct Extremes {
    Vec3 lo_a = Vec3::Zero(), lo_b = Vec3::Zero(), hi_a = Vec3::Zero(), hi_b = Vec3::Zero();
    double c_max = 0.0, c_min = 0.0;  // cosines of the smallest and largest angle
    void add(const Vec3& a, const Vec3& b, double c, bool first) {
      if (first || c > c_max) c_max = c, lo_a = a, lo_b = b;
      if (first || c < c_min) c_min = c, hi_a = a, hi_b = b;
    }
    static double angle(const Vec3& a, const Vec3& b) {
      return std::atan2(a.cross(b).norm(), a.dot(b));
    }
  } as_pointed, oriented;
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only() || !n.has(DrapeNode::kSolvedTwo)) continue;
    const bool plus_x = n.has(DrapeNode::kFromPlusX), plus_y = n.has(DrapeNode::kFromPlusY);
    const DrapeNode* a = res.neighbour(n, plus_x ? ThreadDir::kPlusX : ThreadDir::kMinusX);
    const DrapeNode* b = res.neighbour(n, plus_y ? ThreadDir::kPlusY : ThreadDir::kMinusY);
    if (!a || !b || !a->mapped() || !b->mapped()) continue;
    const Vec3 wf = a->point - n.point, wp = b->point - n.point;  // x1 - x, x2 - x (eq. 12)
    const double ff = wf.squaredNorm(), pp = wp.squaredNorm();
    if (!(ff > 0.0) || !(pp > 0.0)) continue;
    const double dot = wf.dot(wp);
    const double c = dot / std::sqrt(ff * pp);
    const double sign = (plus_x == plus_y) ? 1.0 : -1.0;  // one link turned: pi - gamma
    as_pointed.add(wf, wp, c, pf.angles == 0);
    oriented.add(wf, sign * wp, sign * c, pf.angles == 0);
    pf.energy += dot * dot / (ff * pp);
    ++pf.angles;
  }
  if (!pf.angles) return;
  pf.gamma_min = Extremes::angle(as_pointed.lo_a, as_pointed.lo_b);
  pf.gamma_max = Extremes::angle(as_pointed.hi_a, as_pointed.hi_b);
  pf.oriented_gamma_min = Extremes::angle(oriented.lo_a, oriented.lo_b);
  pf.oriented_gamma_max = Extremes::angle(oriented.hi_a, oriented.hi_b);
  pf.shear_max = std::max(std::abs(kHalfPi - pf.gamma_min), std::abs(pf.gamma_max - kHalfPi));
}

// 2D and 3D area of the mapped cells (each part as a fan of triangles), and per face the 3D
// area shared equally among each cell's corners.
void cell_areas(DrapeResult& res) {
  double a2 = 0.0, a3 = 0.0;
  auto& faces = res.metrics.faces;
  detail::visit_mapped_cells(res, [&](std::int32_t, std::int32_t, const std::uint32_t* v, int n) {
    const DrapeNode& o = res.nodes[v[0]];
    double cell = 0.0;
    for (int k = 1; k + 1 < n; ++k) {
      const DrapeNode& b = res.nodes[v[k]];
      const DrapeNode& c = res.nodes[v[k + 1]];
      a2 += tri_area2(o.ply, b.ply, c.ply);
      cell += tri_area(o.point, b.point, c.point);
    }
    a3 += cell;
    for (int k = 0; k < n; ++k) {
      const std::size_t f = res.nodes[v[k]].face;
      if (f < faces.size()) faces[f].covered_area += cell / n;
    }
  });
  res.metrics.flat_area = a2;
  res.metrics.surface_area = a3;
}

// A geodesic path's own plane test: at each interior path node q, with neighbours p and r on
// the path, the distance of r from the plane through q holding p and the normal at q, over d
// (zero for the straightest curve; the same test read from either end).
double geodesic_residual(const DrapeSurface& s, const DrapeResult& res) {
  const double d = res.ply->d();
  double worst = 0.0;
  const auto& bp = res.base_path;
  for (std::size_t k = 1; k + 1 < bp.size(); ++k) {
    const DrapeNode &p = res.nodes[bp[k - 1]], &q = res.nodes[bp[k]], &r = res.nodes[bp[k + 1]];
    if (!p.mapped() || !q.mapped() || !r.mapped()) continue;
    const SurfaceNormal sn = s.normal(q.at());
    const Vec3 m = sn.n.cross(p.point - q.point);
    if (!sn.ok || !(m.norm() > 0.0)) continue;
    worst = std::max(worst, std::abs(m.normalized().dot(r.point - q.point)) / d);
  }
  return worst;
}

// The stopped nodes' reasons, by status.
void count_stop_reasons(DrapeResult& res) {
  DrapeMetrics& m = res.metrics;
  for (const auto& [k, why] : res.failures) {
    const char* text = why && *why ? why : "unknown";
    if (res.nodes[k].status == NodeStatus::kFailed)
      ++m.nodes.failed_reasons[text];
    else if (res.nodes[k].status == NodeStatus::kConflict)
      ++m.nodes.conflict_reasons[text];
    else if (res.nodes[k].status == NodeStatus::kShearLimit)
      ++m.nodes.shear_limit_reasons[text];
    else if (res.nodes[k].status == NodeStatus::kOverlap)
      ++m.nodes.overlap_reasons[text];
  }
}

// Nodes by status, and the thread angles' range and shear energy.
void count_nodes(DrapeResult& res) {
  DrapeMetrics& m = res.metrics;
  bool first = true;
  for (const DrapeNode& n : res.nodes) {
    if (const auto* row = row_of(kNodeStatuses, n.status); row && row->count)
      ++(n.mapped() && n.id.is_path_only() ? m.nodes.auxiliary : m.nodes.*(row->count));
    if (n.has(DrapeNode::kHasAngle)) {
      const double g = n.thread_angle;
      m.gamma_min = first ? g : std::min(m.gamma_min, g);
      m.gamma_max = first ? g : std::max(m.gamma_max, g);
      first = false;
      m.shear_energy += std::cos(g) * std::cos(g);
      ++m.angles;
    }
  }
  m.area_mesh_points = m.nodes.mapped;
  if (m.angles)
    m.shear_max = std::max(std::abs(kHalfPi - m.gamma_min), std::abs(m.gamma_max - kHalfPi));
  for (const DrapeNode& n : res.nodes)
    if (n.mapped() && !n.id.is_path_only() && n.face < m.faces.size()) ++m.faces[n.face].mapped;
}

// Independent residual checks: link lengths, distance to the surface, the base plane; the
// rounding floor of the solves.
void check_residuals(const DrapeSurface& s, const Tolerances& tol, DrapeResult& res) {
  DrapeMetrics& m = res.metrics;
  const double d = res.ply->d();
  for_each_link(res, [&](std::uint32_t a, std::uint32_t b, double rest, LinkKind) {
    const double len = (res.nodes[a].point - res.nodes[b].point).norm();
    m.edge_length_max_rel = std::max(m.edge_length_max_rel, std::abs(len - rest) / d);
    const DrapeNode &na = res.nodes[a], &nb = res.nodes[b];
    if (!s.same_chart(na.at(), nb.at()))
      m.crease_angle_max = std::max(m.crease_angle_max, s.crease_angle(na.at(), nb.at()));
  });
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const SurfaceEval1 e = s.eval1(n.at());
    m.surface_distance_max =
        std::max(m.surface_distance_max, e.ok ? (e.p - n.point).norm() : INFINITY);
    if (n.has(DrapeNode::kOnPath) && res.seed_curve == SeedCurve::kPlane)
      m.base_plane_max_rel = std::max(m.base_plane_max_rel,
                                      std::abs(res.base_normal.dot(n.point - res.start_point)) / d);
  }
  if (res.seed_curve == SeedCurve::kGeodesic) m.base_plane_max_rel = geodesic_residual(s, res);
  if (!std::isfinite(m.surface_distance_max)) m.surface_distance_max = 1e300;
  const BBox3 box = s.bbox();
  const Vec3 far = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs());
  m.newton_floor = residual_floor(s, tol, far, d);
}

}  // namespace

void compute_metrics(const DrapeSurface& s, const Tolerances& tol, DrapeResult& res) {
  DrapeMetrics& m = res.metrics;
  m.faces.assign(static_cast<std::size_t>(std::max(s.face_count(), 1)), {});
  for (std::size_t k = 0; k < m.faces.size(); ++k)
    m.faces[k].area = s.face_area(static_cast<std::int32_t>(k));
  thread_angles(res);
  paper_angles(res, m.paper);
  count_stop_reasons(res);
  count_nodes(res);
  cell_areas(res);
  m.coverage = s.area() > 0.0 ? m.surface_area / s.area() : 0.0;
  check_residuals(s, tol, res);
}

}  // namespace plyfit::detail
