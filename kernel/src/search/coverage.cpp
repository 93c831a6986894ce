// The outline's coverage (optimize.hpp: outline_surface_area).
#include <plyfit/kernel/optimize.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace plyfit {

/// Surface area of the region the flat pattern's outline covers: the integral over the
/// outline of the ratio J of surface to flat area, J constant per cell of the ply (its four
/// corners' 3D quadrilateral, on the surface extended past the face for corners outside it).
/// By Green's theorem the integral is the outline's boundary integral of G dy, G(x, y) the
/// integral of J along the cell row up to x, so the cells the outline cuts count only their
/// part inside it, whatever the grid's position. G may start anywhere in each row: a term
/// c(y) dy integrates to zero around a closed loop.
double outline_surface_area(const DrapeResult& res, const FlatPattern& flat) {
  const double dw = res.ply->spec().d_weft, dv = res.ply->spec().d_warp;
  // The outline's edges cut where they cross the grid: each piece lies in one cell.
  struct Piece {
    std::int64_t j, i;
    Vec2 a, b;
  };
  std::vector<Piece> pieces;
  std::vector<double> ts;
  auto cell = [](double x, double h) { return static_cast<std::int64_t>(std::floor(x / h)); };
  for (const auto& loop : flat.outline) {
    const std::size_t n = loop.points.size();
    for (std::size_t e = 0; e < n; ++e) {
      const Vec2 a = loop.points[e], b = loop.points[(e + 1) % n];
      ts.assign({0.0, 1.0});
      auto cuts = [&](double pa, double pb, double h) {
        if (pa == pb) return;
        const double lo = std::min(pa, pb), hi = std::max(pa, pb);
        for (auto g = static_cast<std::int64_t>(std::ceil(lo / h)); static_cast<double>(g) * h < hi;
             ++g)
          if (static_cast<double>(g) * h > lo)
            ts.push_back((static_cast<double>(g) * h - pa) / (pb - pa));
      };
      cuts(a.x(), b.x(), dw);
      cuts(a.y(), b.y(), dv);
      std::sort(ts.begin(), ts.end());
      for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
        const Vec2 pa = a + ts[k] * (b - a), pb = a + ts[k + 1] * (b - a);
        if (pa.y() == pb.y()) continue;  // no dy
        const Vec2 mid = 0.5 * (pa + pb);
        pieces.push_back({cell(mid.y(), dv), cell(mid.x(), dw), pa, pb});
      }
    }
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece& p, const Piece& q) { return p.j < q.j || (p.j == q.j && p.i < q.i); });
  auto corner = [&](std::int64_t i, std::int64_t j, Vec3& p) {
    const DrapeNode* n =
        res.find(NodeId::regular(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)));
    if (!n || !(n->mapped() || n->has(DrapeNode::kExtended))) return false;
    p = n->point;
    return true;
  };
  double area = 0.0;
  std::vector<double> jac, run;  // per cell of the row: J, and G at the cell's left edge
  for (std::size_t r0 = 0; r0 < pieces.size();) {
    std::size_t r1 = r0;
    while (r1 < pieces.size() && pieces[r1].j == pieces[r0].j) ++r1;
    const std::int64_t j = pieces[r0].j, i0 = pieces[r0].i, i1 = pieces[r1 - 1].i;
    jac.assign(static_cast<std::size_t>(i1 - i0 + 1), 1.0);
    run.assign(jac.size(), 0.0);
    double acc = 0.0;
    for (std::int64_t i = i0; i <= i1; ++i) {
      Vec3 p[4];
      const auto k = static_cast<std::size_t>(i - i0);
      if (corner(i, j, p[0]) && corner(i + 1, j, p[1]) && corner(i + 1, j + 1, p[2]) &&
          corner(i, j + 1, p[3]))
        jac[k] = 0.5 * (p[2] - p[0]).cross(p[3] - p[1]).norm() / (dw * dv);
      run[k] = acc;
      acc += jac[k] * dw;
    }
    for (std::size_t q = r0; q < r1; ++q) {
      const Piece& pc = pieces[q];
      const auto k = static_cast<std::size_t>(pc.i - i0);
      const double x_left = static_cast<double>(pc.i) * dw;
      const double ga = run[k] + jac[k] * (pc.a.x() - x_left);
      const double gb = run[k] + jac[k] * (pc.b.x() - x_left);
      area += 0.5 * (ga + gb) * (pc.b.y() - pc.a.y());
    }
    r0 = r1;
  }
  return area;
}

void warn_outline_short(const FlatPattern& flat, double surface_area, DrapeResult& res) {
  if (res.partial || res.ply->spec().rect || !(surface_area > 0.0)) return;
  for (const Warning& w : res.warnings)
    if (w.code == WarningCode::kUncoveredArea) return;
  const double coverage = outline_surface_area(res, flat) / surface_area;
  if (!(coverage < 1.0 - kCoverageSlack)) return;
  const NodeCounts& c = res.metrics.nodes;
  auto count = [](std::uint64_t n) { return MessageValue(static_cast<std::int64_t>(n)); };
  res.warnings.push_back({WarningCode::kOutlineShort,
                          {coverage, kCoverageSlack, count(c.shear_limit), count(c.overlap),
                           count(c.failed), count(c.conflict), count(c.path_end)}});
}

}  // namespace plyfit
