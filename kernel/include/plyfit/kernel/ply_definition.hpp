#pragma once
/// \file A ply as composites tools define it: a seed point on the mold, a rosette (the part's
/// 0° direction) and a ply angle, from which the paper's initial conditions follow.
///
/// Conventions (Fibersim, CATIA CPD): the rosette is translational (its direction projected
/// onto the tangent plane at the seed is 0°); the ply angle turns the warp fibres from 0°
/// about the outward normal, counter-clockwise seen from outside (90° = normal x 0°). In ply
/// coordinates the warp runs along +y and the weft along +x, the frame (x, y, n) right-handed
/// on the part: x = y x n. The seed is the ply's origin.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/result.hpp>
#include <plyfit/kernel/tolerances.hpp>
#include <plyfit/kernel/types.hpp>

namespace plyfit {

/// Where a ply starts and how its fibres run.
struct PlyDefinition {
  Vec3 seed = Vec3::Zero();      ///< projected onto the mold: the ply's origin
  Vec3 rosette = Vec3::UnitX();  ///< the 0° direction (a translational rosette)
  double angle = 0.0;            ///< ply angle, radians, in [-pi, pi]
};

/// The ply's frame at a point of the mold.
struct PlyFrame {
  SurfaceLocation at;
  Vec3 point = Vec3::Zero();    ///< on the mold
  Vec3 normal = Vec3::UnitZ();  ///< outward
  Vec3 zero = Vec3::UnitX();    ///< the rosette's 0° direction on the tangent plane
  Vec3 warp = Vec3::UnitY();    ///< the warp fibres (ply +y)
  Vec3 weft = Vec3::UnitX();    ///< the weft fibres (ply +x = warp x normal)
  double angle = 0.0;           ///< the warp's angle from `zero` about `normal`, radians
  double moved = 0.0;           ///< distance from the given seed to `point`
};

/// The rosette's 0° direction on the tangent plane of normal `n`: `rosette` projected onto it.
/// Errors: a zero or non-finite rosette (kRosetteZero), a rosette within
/// Tolerances::rosette_min_angle of the normal (kRosetteAlongNormal, its angle from the normal
/// in degrees). The error blames "rosette".
Result<Vec3> rosette_zero(const Vec3& rosette, const Vec3& n, const Tolerances& tol = {});

/// The frame of ply `def` at its seed. Errors blame "seed" (not finite; farther from the mold
/// than half the mold's size: kSeedOffMold with the distance and that half size), "rosette"
/// (as rosette_zero) or "ply-angle" (outside [-180, 180] degrees).
Result<PlyFrame> ply_frame(const MoldSurface& mold, const PlyDefinition& def,
                           const Tolerances& tol = {});

/// The paper's initial conditions of ply `def` on `cloth` (its spacings, rectangle and 2D start,
/// the seed's place in ply coordinates; its directions are replaced): the base path along the
/// warp through the seed (base2d (0, 1), the base plane through the seed holding the warp and
/// the normal), both sweeps along the weft ((1, 0) towards warp x n, (-1, 0) the other way).
Result<DrapeProblem> ply_problem(const MoldSurface& mold, const PlyDefinition& def, PlySpec cloth,
                                 const Tolerances& tol = {});

/// `problem` turned by `angle` (radians) about the outward normal at its start: its base-plane
/// normal and 3D sweeps, so that every thread on the part turns by `angle` (the paper's
/// explicit initial conditions laid at a ply angle). Errors as drape()'s for the start.
Result<DrapeProblem> turned_problem(const MoldSurface& mold, DrapeProblem problem, double angle);

/// The frame a drape laid its warp in at its start, measured against `rosette`: the real ply
/// angle of the drape, whatever initial conditions made it.
Result<PlyFrame> draped_frame(const MoldSurface& mold, const DrapeResult& result,
                              const Vec3& rosette, const Tolerances& tol = {});

}  // namespace plyfit
