#pragma once
/// \file Closed polygons in the plane (ply coordinates, or (u, v) trim loops): signed area and
/// the even-odd point-in-polygon test. The last point joins the first.

#include <plyfit/kernel/types.hpp>

#include <optional>
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

/// The union of many even-odd regions, likewise (united two by two: each with regions of its
/// own size, not with the whole union so far).
Region2 unite_all(const std::vector<Region2>& regions);

/// Region a less region b (even-odd regions), likewise; none when b does not meet a (a is
/// then whole).
std::optional<Region2> subtract_regions(const Region2& a, const Region2& b);

/// The area of an even-odd region.
double region_area(const Region2& r);

/// A vertex of a clipped loop, by where it lies on the input: on edge `edge` of loop `loop`
/// (from its vertex `edge` to the next), at `t` in [0, 1) along it (0: the vertex itself), so
/// that a caller carries anything the input's vertices hold (a 3D point) to it.
struct ClipVertex {
  Vec2 p;
  std::size_t loop = 0, edge = 0;
  double t = 0.0;
};

/// The part of a region of oriented loops (outer loops counter-clockwise, holes clockwise, none
/// crossing another) in the slab lo <= x <= hi: loops of the same orientations. Exact: every
/// input vertex inside is kept as it is, the crossings of x = lo and x = hi are on the input's
/// edges, and the new edges run along those lines (as Boost.Geometry's booleans, which snap
/// points to a grid of about 1e-6 of the extent and drop collinear vertices, are not).
std::vector<std::vector<ClipVertex>> clip_to_slab(const Region2& loops, double lo, double hi);

}  // namespace plyfit
