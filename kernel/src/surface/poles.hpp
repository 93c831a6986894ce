// Private to the kernel: poles of a drape surface (collapsed edges of a face's parameter
// domain) and the location of points near them. Near a pole (u, v) is polar: Newton on it can
// cross the pole onto the surface extended past the collapsed edge, or stall. A Face finds
// its poles once (Face::poles) and settles there the points a solve reached past one
// (Face::settle); the solvers use the fan of a pole to leave it in a given direction.
#pragma once

#include <plyfit/kernel/tolerances.hpp>
#include "surface/face.hpp"

#include <optional>
#include <vector>

namespace plyfit::detail {

// At a pole, a step must make a cosine above this with some direction the face offers (the
// fan of the collapsed edge's derivatives); otherwise it leaves the face at once.
inline constexpr double kMinFanCos = 1e-6;

/// The free parameter of a collapsed edge (a pole) whose inward derivative best points along
/// `dir`, with the cosine between the two (-2 where nothing could be evaluated).
struct FanFit {
  double t = 0.0;
  double cos = -2.0;
};

/// The fan of a pole: the derivative across its edge, S_u (u fixed) or S_v, turned inward,
/// sampled along the edge and refined by golden section; the best fit to `dir`.
FanFit fan_fit(const DrapeSurface& surface, const Pole& e, const Vec3& dir);

/// The poles of every face of `surface`: domain edges whose ends and middle coincide in 3D
/// within kCollapsedEdgeRel of the surface's size (as Face::boundary() marks collapsed edges).
std::vector<Pole> find_poles(const DrapeSurface& surface);

/// The location of 3D point p on the surface through pole e: along the fan direction that
/// holds the direction from the pole to p best, |p - pole| / |derivative| into the domain,
/// refined by Gauss-Newton on |S - p|^2 within the domain. Nullopt when no direction of the
/// fan points towards p. The caller checks how close S(result) is to p.
std::optional<SurfaceLocation> locate_through_pole(const DrapeSurface& s, const Pole& e,
                                                   const Vec3& p, const Tolerances& tol);

}  // namespace plyfit::detail
