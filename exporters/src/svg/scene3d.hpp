#pragma once
// What the 3D pictures (drape.svg, view.svg) share: the orthographic camera, the mold's free
// boundary in 3D, and the mapped cells coloured by shear and shaded by their slope to the view.

#include <plyfit/kernel/mold.hpp>

#include "svg/draw.hpp"

#include <utility>
#include <vector>

namespace plyfit::exporters::svg {

/// An orthographic camera: Z up on the page (Y when looking down Z).
struct Camera {
  Vec3 right, up, towards;  ///< towards the viewer
  /// Looking along -`view` (a zero vector: the isometric (1, 1, 1)).
  static Camera from(const Vec3& view);
  Vec2 project(const Vec3& p) const { return {p.dot(right), p.dot(up)}; }
  double depth(const Vec3& p) const { return p.dot(towards); }
};

/// A picture's projection: the camera, then the frame.
struct View {
  Camera cam;
  Frame frame;
  Vec2 map(const Vec3& p) const { return frame.map(cam.project(p)); }
};

using Segment3 = std::pair<Vec3, Vec3>;

/// What a 3D picture shows, projected: the mapped nodes and `boundary`, with a margin of
/// kScenePad of its extent.
constexpr double kScenePad = 0.03;
Box2 scene_box(const DrapeResult& r, const std::vector<Segment3>& boundary, const Camera& cam);

/// The free boundary in 3D (the kernel's: seams of closed faces, collapsed pole edges and the
/// edges a shell's faces share are no boundary), each segment split into `pieces` (one on
/// loops of many points).
std::vector<Segment3> free_boundary(const MoldSurface& surface, int pieces);

/// How a cell's edges are drawn: in its own colour (closing the hairline gaps between cells),
/// or left to the stroke of the group the cells are drawn in.
enum class CellEdges { kOwnColour, kGroupStroke };

/// `cells` coloured by shear and shaded by their slope to the view, as primitives of class
/// "cell" at their centres' depth.
void add_cells(std::vector<Prim>& prims, const DrapeResult& r,
               const std::vector<detail::NetCell>& cells, const render::ShearScale& scale,
               const View& v, CellEdges edges);

}  // namespace plyfit::exporters::svg
