#pragma once
// Building drape problems in tests: the same argument order everywhere.

#include <plyfit/kernel/drape.hpp>

#include <cmath>
#include <vector>

namespace plyfit::support {

/// A drape problem with equal spacings d, the 2D start s2, base direction b2, sweeps w2, and
/// the 3D start s3, base-plane normal bn and sweeps w3.
inline DrapeProblem problem(double d, Vec2 s2, Vec2 b2, std::vector<Vec2> w2, Vec3 s3, Vec3 bn,
                            std::vector<Vec3> w3) {
  DrapeProblem pb;
  pb.ply.d_weft = pb.ply.d_warp = d;
  pb.ply.start = s2;
  pb.ply.base_dir = b2;
  pb.ply.sweeps = std::move(w2);
  pb.start = s3;
  pb.base_normal = bn;
  pb.sweeps = std::move(w3);
  return pb;
}

/// A hemisphere of radius R about the z axis draped from its pole at spacing d: base path on
/// the plane x = 0, sweeps both ways.
inline DrapeProblem pole_problem(double R, double d) {
  return problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, Vec3(0, 0, R), Vec3(1, 0, 0),
                 {Vec3(1, 0, 0), Vec3(-1, 0, 0)});
}

/// On that hemisphere, the meridian at azimuth 45 deg (half-way between the threads through
/// the pole, where the cloth shears most) from the rim up to 40 deg from the pole, a point per
/// degree: a dart.
inline std::vector<Vec3> meridian_dart(double R) {
  std::vector<Vec3> curve;
  const double az = 45.0 * kDegToRad;
  for (double polar = 90.0; polar >= 40.0; polar -= 1.0) {
    const double t = polar * kDegToRad;
    curve.push_back(R * Vec3(std::sin(t) * std::cos(az), std::sin(t) * std::sin(az), std::cos(t)));
  }
  return curve;
}

}  // namespace plyfit::support
