#include "svg/scene3d.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::exporters::svg {

namespace {
// A view direction within this angle (radians) of Z looks down Z: Y is up on the page then.
constexpr double kViewAlongZ = 1e-6;
// Loops of more points than this have their segments drawn in one piece.
constexpr std::size_t kManyBoundaryPoints = 64;
}  // namespace

Camera Camera::from(const Vec3& view) {
  Camera c;
  c.towards = view.norm() > 0 ? Vec3(view.normalized()) : Vec3(1, 1, 1).normalized();
  Vec3 world_up = Vec3::UnitZ();
  if (world_up.cross(c.towards).norm() < kViewAlongZ) world_up = Vec3::UnitY();
  c.right = world_up.cross(c.towards).normalized();
  c.up = c.towards.cross(c.right);
  return c;
}

std::vector<Segment3> free_boundary(const MoldSurface& surface, int pieces_per_segment) {
  std::vector<Segment3> boundary;
  for (const auto& loop : surface.boundary()) {
    const std::size_t n = loop.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      if (loop.kinds[k] != BoundaryLoop::kEdge) continue;
      const SurfaceLocation& a = loop.points[k];
      const SurfaceLocation& b = loop.points[(k + 1) % n];
      const int pieces = n > kManyBoundaryPoints ? 1 : std::max(1, pieces_per_segment);
      Vec3 prev = surface.eval1(a).p;
      for (int m = 1; m <= pieces; ++m) {
        const Vec3 q =
            surface.eval1(a.with_uv(a.uv + (b.uv - a.uv) * (static_cast<double>(m) / pieces))).p;
        boundary.emplace_back(prev, q);
        prev = q;
      }
    }
  }
  return boundary;
}

Box2 scene_box(const DrapeResult& r, const std::vector<Segment3>& boundary, const Camera& cam) {
  Box2 box;
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) box.add(cam.project(n.point));
  for (const auto& [a, b] : boundary) {
    box.add(cam.project(a));
    box.add(cam.project(b));
  }
  const double ext = box.empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  return padded(box, kScenePad * ext);
}

void add_cells(std::vector<Prim>& prims, const DrapeResult& r,
               const std::vector<detail::NetCell>& cells, const render::ShearScale& scale,
               const View& v, CellEdges edges) {
  for (const auto& c : cells) {
    std::vector<Vec2> pts;
    Vec3 centre = Vec3::Zero(), normal = Vec3::Zero();
    for (std::size_t k = 0; k < c.nodes.size(); ++k) {
      const Vec3& p = r.nodes[c.nodes[k]].point;
      const Vec3& q = r.nodes[c.nodes[(k + 1) % c.nodes.size()]].point;
      pts.push_back(v.map(p));
      centre += p;
      normal += p.cross(q);  // Newell's normal
    }
    centre /= static_cast<double>(c.nodes.size());
    const double facing =
        normal.norm() > 0 ? std::abs(normal.normalized().dot(v.cam.towards)) : 1.0;
    const std::string fill = scale.colour(c.shear).shaded(0.55 + 0.45 * facing).hex();
    const std::string stroke = edges == CellEdges::kOwnColour
                                   ? " stroke=\"" + fill + "\" stroke-width=\"0.3\""
                                   : std::string();
    prims.push_back({v.cam.depth(centre), polygon(pts, "cell", " fill=\"" + fill + "\"" + stroke)});
  }
}

}  // namespace plyfit::exporters::svg
