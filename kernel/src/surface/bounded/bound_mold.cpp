// bound_mold(): a mold restricted to a ply boundary's region, as a list of steps.
#include "surface/bounded/bounded.hpp"
#include "surface/shell/shell.hpp"

#include <plyfit/kernel/boundary.hpp>

#include <cmath>
#include <map>

namespace plyfit {

namespace {

// A restricted surface and, per face, its face in the mold given.
struct Restricted {
  MoldSurface surface;
  std::vector<int> faces;
  bool winding = false;  // a loop winds round a closed face: its side was chosen
};

// One face restricted: its new trims, or an empty result when the region misses it.
Result<Restricted> restrict_face(const Face& face, const std::vector<detail::MoldLoop>& loops,
                                 const Tolerances& tol, bool far_side) {
  detail::FaceCut cut = detail::cut_face(face, loops, tol, far_side);
  if (cut.kind == detail::FaceCut::kNone) return Error{ErrorCode::kBoundarySeedOutside, "boundary"};
  FaceData data = face.data();
  data.area = face.area();
  if (cut.kind == detail::FaceCut::kPart) {
    data.loops = std::move(cut.loops);
    data.area = cut.area;
  }
  auto s = MoldSurface::from_face(std::move(data), tol);
  if (!s) return s.error();
  return Restricted{std::move(s).value(), {0}, cut.winding};
}

// Shared edges that lost a side become free; the rest are numbered again from 0.
void renumber_edges(ShellData& data) {
  std::map<std::int32_t, std::vector<std::size_t>> uses;
  for (std::size_t k = 0; k < data.faces.size(); ++k)
    for (const auto& loop : data.faces[k].loops)
      for (std::int32_t e : loop.edges)
        if (e != TrimLoop::kFreeEdge) {
          auto& u = uses[e];
          if (u.empty() || u.back() != k) u.push_back(k);
        }
  std::map<std::int32_t, std::int32_t> number;
  for (const auto& [e, faces] : uses)
    if (faces.size() == 2) number.emplace(e, static_cast<std::int32_t>(number.size()));
  for (auto& f : data.faces)
    for (auto& loop : f.loops)
      for (std::int32_t& e : loop.edges) {
        const auto it = number.find(e);
        e = it == number.end() ? TrimLoop::kFreeEdge : it->second;
      }
  data.edge_count = static_cast<std::int32_t>(number.size());
}

// A shell restricted: each face cut, faces the region misses left out.
Result<Restricted> restrict_shell(const Shell& shell, const std::vector<detail::MoldLoop>& loops,
                                  const Tolerances& tol, bool far_side) {
  const ShellData all = shell.data();
  ShellData data;
  data.tolerance = all.tolerance;
  Restricted out{MoldSurface(nullptr), {}};
  for (std::int32_t k = 0; k < shell.face_count(); ++k) {
    detail::FaceCut cut = detail::cut_face(shell.face(k), loops, tol, far_side);
    out.winding = out.winding || cut.winding;
    if (cut.kind == detail::FaceCut::kNone) continue;
    FaceData f = all.faces[static_cast<std::size_t>(k)];
    f.area = shell.face(k).area();
    if (cut.kind == detail::FaceCut::kPart) {
      f.loops = std::move(cut.loops);
      f.area = cut.area;
    }
    data.faces.push_back(std::move(f));
    data.source_faces.push_back(all.source_faces[static_cast<std::size_t>(k)]);
    out.faces.push_back(k);
  }
  if (data.faces.empty()) return Error{ErrorCode::kBoundarySeedOutside, "boundary"};
  renumber_edges(data);
  auto s = MoldSurface::from_shell(std::move(data), tol);
  if (!s) return s.error();
  out.surface = std::move(s).value();
  return out;
}

Result<Restricted> restrict_mold(const MoldSurface& mold,
                                 const std::vector<detail::MoldLoop>& loops, const Tolerances& tol,
                                 bool far_side) {
  if (const auto* face = dynamic_cast<const Face*>(&mold.impl()))
    return restrict_face(*face, loops, tol, far_side);
  if (const auto* shell = dynamic_cast<const Shell*>(&mold.impl()))
    return restrict_shell(*shell, loops, tol, far_side);
  return Error{ErrorCode::kInternal};
}

// True when p's place on the mold (its projection) lies on the restricted surface, p within
// `reach` of it (a point past the mold's edge projects onto the edge: it is not on the mold).
bool on_region(const MoldSurface& mold, const Restricted& r, const Vec3& p,
               double reach = INFINITY) {
  const Projection pr = mold.project(p);
  if (!pr.ok || pr.distance > reach) return false;
  for (std::size_t k = 0; k < r.faces.size(); ++k)
    if (r.faces[k] == pr.at.face)
      return r.surface.impl().contains(SurfaceLocation(pr.at.uv, static_cast<std::int32_t>(k)));
  return false;
}

// The mold restricted to the loops' region; where a loop winds round a closed face (and so
// bounds a side of it, not an area) the side that holds the seed.
Result<Restricted> region_holding(const MoldSurface& mold,
                                  const std::vector<detail::MoldLoop>& loops, const Tolerances& tol,
                                  const Vec3& seed) {
  auto near = restrict_mold(mold, loops, tol, false);
  if (!near || !near->winding || on_region(mold, *near, seed)) return near;
  return restrict_mold(mold, loops, tol, true);
}

std::vector<PlyBoundaryLoop> loops_on_mold(const std::vector<detail::MoldLoop>& loops) {
  std::vector<PlyBoundaryLoop> out;
  for (const auto& l : loops) {
    PlyBoundaryLoop b;
    b.points = l.points;
    for (std::size_t i = 0; i < l.points.size(); ++i) {
      b.length += (l.points[(i + 1) % l.points.size()] - l.points[i]).norm();
      if (b.curves.empty() || b.curves.back() != l.curve[i]) b.curves.push_back(l.curve[i]);
    }
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace

Result<BoundedMold> bound_mold(const MoldSurface& mold, const PlyBoundary& boundary,
                               const Vec3& seed, const Tolerances& tol) {
  const double size = mold.size();
  auto loops = detail::chain_curves(boundary, tol.boundary_gap_rel * size);
  if (!loops) return loops.error();
  for (auto& l : *loops) detail::densify(l, tol.boundary_step_rel * size);
  if (auto st = detail::project_loops(mold, boundary, *loops, tol.boundary_on_mold_rel * size); !st)
    return st.error();
  auto region = region_holding(mold, *loops, tol, seed);
  if (!region) return region.error();
  if (boundary.offset != 0.0) {
    const auto inside = [&](const Vec3& p, double reach) {
      return on_region(mold, *region, p, reach);
    };
    detail::offset_loops(mold, *loops, boundary.offset, inside);
    region = region_holding(mold, *loops, tol, seed);
    if (!region) return region.error();
  }
  if (!on_region(mold, *region, seed)) return Error{ErrorCode::kBoundarySeedOutside, "boundary"};
  BoundedMold out{region->surface, loops_on_mold(*loops), region->surface.area(), region->faces};
  return out;
}

}  // namespace plyfit
