#pragma once
/// \file Pieces of the cloth, and cloth laid twice (internal to pattern/). Where the cloth
/// comes round onto itself (a closed face or a closed shell) the drape stops the nodes that
/// land on cloth already laid (overlap): a node within the overlap radius of a node far
/// from it on the ply. A node that lands between the nodes of the cloth already laid,
/// farther than that radius from each, escapes the test: threads of such nodes go on over
/// the cloth, and their cells make pieces of their own, cut off from the rest by the overlap
/// nodes around them (single cells where such a thread meets the face's edge). The same rule
/// is applied here against the cloth itself, its cells, not its nodes: a cell of a piece is
/// cloth laid twice when one of its nodes lies on the cloth of a larger piece, and is no
/// cloth to cut, as a cell with an overlap node is none. What is left of a piece lies where
/// no other cloth does: cloth of its own, which stays (docs/decisions/cloth-laid-twice.md).

#include <plyfit/kernel/types.hpp>

#include <functional>
#include <vector>

namespace plyfit::detail {

/// A corner of a polygon of cloth.
struct ClothCorner {
  Vec3 p3;    ///< on the mold
  Vec2 p2;    ///< on the ply
  bool node;  ///< a node of the drape (the corners the overlap rule tests)
};

/// Sets `out` to the corners of cloth polygon p, in order round it (a chord polygon of the
/// surface).
using ClothCorners = std::function<void(int p, std::vector<ClothCorner>& out)>;

/// What stops the cloth round cloth polygon p: -1 a stop of another kind than the seam (a
/// shear limit, a failure) at one of its node corners' cells, else 1 where the drape stopped
/// a node there as overlap or conflict (cloth there would lie on cloth already laid, or two
/// fronts meet that cannot be joined: the seam where the cloth meets itself), else 0 (mapped
/// nodes, or the face's edge).
using SeamBorder = std::function<int(int p)>;

/// The cloth polygons laid twice. `pieces[k]` lists the polygons (0 .. polygons - 1) of
/// piece k, larger pieces first. A polygon of piece k is laid twice when one of its node
/// corners lies within `radius` (3D) of a polygon of a piece before it that is not laid
/// twice, that polygon at least `separation` away from the node on the ply (a polygon
/// nearer on the ply is the same cloth, as at a vertex two pieces share). The whole of a
/// later piece is when the cloth round its other polygons stops at the seam, and only there
/// or at the face's edge (`border`, if given: every polygon 0 or 1, one of them 1): the
/// piece lies beyond the seam, which the cloth cannot cross, cut off from the cloth by the
/// nodes the drape stopped on cloth round it (nodes that escaped the drape's overlap test
/// between those that did not). No polygon of the first piece is.
std::vector<bool> polygons_laid_twice(const std::vector<std::vector<int>>& pieces,
                                      std::size_t polygons, const ClothCorners& corners,
                                      double radius, double separation,
                                      const SeamBorder& border = {});

}  // namespace plyfit::detail
