#pragma once
// Faces the tests build from data they know to be valid (Face::create must succeed).

#include "surface/face.hpp"

#include <catch2/catch.hpp>

#include <utility>

namespace plyfit::support {

/// Face::create(fd), required to succeed.
inline Face make_face(FaceData fd) {
  auto f = Face::create(std::move(fd));
  REQUIRE(f.ok());
  return std::move(f).value();
}

/// The untrimmed face of surface d.
inline Face make_face(NurbsSurfaceData d) {
  FaceData fd;
  fd.surface = std::move(d);
  return make_face(std::move(fd));
}

}  // namespace plyfit::support
