#pragma once
// Building drape problems in tests: the same argument order everywhere.

#include <plyfit/kernel/drape.hpp>

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

}  // namespace plyfit::support
