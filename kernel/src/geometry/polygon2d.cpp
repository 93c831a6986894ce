#include <plyfit/kernel/polygon2d.hpp>

namespace plyfit {

double signed_area(const std::vector<Vec2>& polygon) {
  double a = 0.0;
  for (std::size_t k = 0, n = polygon.size(); k < n; ++k)
    a += cross2(polygon[k], polygon[(k + 1) % n]);
  return 0.5 * a;
}

bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p) {
  bool inside = false;
  for (std::size_t k = 0, n = polygon.size(); k < n; ++k)
    if (crosses_ray(polygon[k], polygon[(k + 1) % n], p)) inside = !inside;
  return inside;
}

}  // namespace plyfit
