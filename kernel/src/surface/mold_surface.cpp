// MoldSurface: the public handle of a face or shell, forwarding to the kernel's surface.
#include "surface/face.hpp"
#include "surface/shell/shell.hpp"

#include <plyfit/kernel/mold.hpp>

namespace plyfit {

Result<MoldSurface> MoldSurface::from_face(FaceData data, const Tolerances& tol) {
  auto face = Face::create(std::move(data), tol);
  if (!face) return face.error();
  return MoldSurface(std::make_shared<const Face>(std::move(face).value()));
}

Result<MoldSurface> MoldSurface::from_shell(ShellData data, const Tolerances& tol) {
  auto shell = Shell::create(std::move(data), tol);
  if (!shell) return shell.error();
  return MoldSurface(std::make_shared<const Shell>(std::move(shell).value()));
}

MoldSurface::MoldSurface(std::shared_ptr<const DrapeSurface> surface)
    : surface_(std::move(surface)) {}

std::int32_t MoldSurface::face_count() const {
  return surface_->face_count();
}
double MoldSurface::face_area(std::int32_t k) const {
  return surface_->face_area(k);
}
double MoldSurface::face_rounding(std::int32_t k) const {
  return surface_->face_rounding(k);
}
double MoldSurface::area() const {
  return surface_->area();
}
double MoldSurface::size() const {
  return surface_->size();
}
BBox3 MoldSurface::bbox() const {
  return surface_->bbox();
}
SurfaceEval1 MoldSurface::eval1(const SurfaceLocation& at) const {
  return surface_->eval1(at);
}
SurfaceNormal MoldSurface::normal(const SurfaceLocation& at) const {
  return surface_->normal(at);
}
Projection MoldSurface::project(const Vec3& p) const {
  return surface_->project(p);
}
std::vector<BoundaryLoop> MoldSurface::boundary() const {
  return surface_->boundary();
}
const ParamDomain& MoldSurface::domain(const SurfaceLocation& at) const {
  return surface_->domain(at);
}

}  // namespace plyfit
