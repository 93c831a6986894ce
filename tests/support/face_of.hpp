#pragma once
// The kernel Face behind a MoldSurface of one face (importers::load_face gives a MoldSurface),
// for tests that look at the face's internals.

#include "surface/face.hpp"

#include <plyfit/kernel/mold.hpp>

namespace plyfit::test {

inline const Face& face_of(const MoldSurface& surface) {
  return dynamic_cast<const Face&>(surface.impl());
}

}  // namespace plyfit::test
