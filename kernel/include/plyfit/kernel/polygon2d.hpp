#pragma once
/// \file Closed polygons in the plane (ply coordinates, or (u, v) trim loops): signed area and
/// the even-odd point-in-polygon test. The last point joins the first.

#include <plyfit/kernel/types.hpp>

#include <vector>

namespace plyfit {

/// Signed area of the closed polygon (shoelace formula): positive when it runs
/// counter-clockwise.
double signed_area(const std::vector<Vec2>& polygon);

/// True when the edge a -> b crosses the ray from p towards +x: one step of the even-odd
/// rule. Half-open in y, so that a ray through a vertex of two edges counts it once.
inline bool crosses_ray(const Vec2& a, const Vec2& b, const Vec2& p) {
  return (a.y() > p.y()) != (b.y() > p.y()) &&
         p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
}

/// True when p lies inside the closed polygon (even-odd rule).
bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p);

}  // namespace plyfit

namespace plyfit {

/// A region of the plane: closed polygons combined by the even-odd rule (outer loops, holes,
/// islands in holes), as trim loops and ply boundaries are.
using Region2 = std::vector<std::vector<Vec2>>;

/// The intersection of two even-odd regions, as loops (outer loops and their holes) whose
/// even-odd combination is that intersection. Loops of no area are dropped.
Region2 intersect_regions(const Region2& a, const Region2& b);

/// The union of two even-odd regions, likewise.
Region2 unite_regions(const Region2& a, const Region2& b);

/// The area of an even-odd region.
double region_area(const Region2& r);

}  // namespace plyfit
