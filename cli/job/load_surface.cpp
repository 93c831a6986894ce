// load_surface: the surface a job drapes, from a built-in mold or shell or from a mold file
// (one face, or faces sewn into a shell), with what the report says of the mold.

#include "job/drape_job.hpp"

#include <plyfit/exporters/exporters.hpp>
#include <plyfit/importers/importers.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

namespace plyfit::cli {

namespace {

using BuiltinSpec = std::pair<std::string, std::map<std::string, double>>;

// One face as the drape's surface, on the job's side.
Result<MoldSurface> surface_from_face(const DrapeJob& job, FaceData data, exporters::RunInfo& run) {
  if (job.flip_normal) data.reversed = !data.reversed;
  auto face = MoldSurface::from_face(std::move(data), job.drape.tol);
  if (!face) return Error(face.error()).in(job.mold).at_face(job.face);
  run.faces.push_back(job.face);
  return face;
}

// Faces sewn into a shell as the drape's surface, on the job's side; run.faces gets each
// face's index in the mold file.
Result<MoldSurface> surface_from_shell(const DrapeJob& job, ShellData data,
                                       exporters::RunInfo& run) {
  if (job.flip_normal)
    for (auto& f : data.faces) f.reversed = !f.reversed;
  const std::size_t n = data.faces.size();
  const std::vector<int> sources = data.source_faces;
  auto shell = MoldSurface::from_shell(std::move(data), job.drape.tol);
  if (!shell) return Error(shell.error()).in(job.mold);
  for (std::size_t k = 0; k < n; ++k)
    run.faces.push_back(run.faces_info.size() > k ? run.faces_info[k].index
                        : sources.empty()         ? static_cast<int>(k)
                                                  : sources[k]);
  return shell;
}

// No face of the mold found under point p.
Error no_face_at(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%g, %g, %g", p.x(), p.y(), p.z());
  return Error{ErrorCode::kNoFaceAtPoint, "", {std::string(buf)}};
}

// --faces connected: the faces of `data` reached from the face nearest the job's point (faces-at,
// else the seed) across shared edges no sharper than max-crease, in the shell's order.
Result<ShellData> connected_part(const DrapeJob& job, ShellData data) {
  if (!job.faces_at && !job.seed) return Error{ErrorCode::kConnectedNeedsPoint, "faces"};
  const ShellData all = data;
  auto shell = MoldSurface::from_shell(std::move(data), job.drape.tol);
  if (!shell) return Error(shell.error()).in(job.mold);
  const Vec3 p = job.faces_at ? *job.faces_at : *job.seed;
  const Projection at = shell->project(p);
  if (!at.ok) return no_face_at(p).in(job.faces_at ? "faces-at" : "seed");
  std::vector<std::int32_t> faces =
      connected_faces(*shell, at.at.face, job.max_crease_deg * kDegToRad);
  std::sort(faces.begin(), faces.end());
  return sub_shell(all, faces);
}

Result<MoldSurface> load_builtin(const DrapeJob& job, const BuiltinSpec& spec,
                                 exporters::RunInfo& run) {
  run.mold_unit = "millimetre";
  if (is_builtin_shell(spec.first)) {
    auto data = builtin_shell(spec.first, spec.second);
    if (!data) return data.error();
    if (job.connected_faces) data = connected_part(job, std::move(data).value());
    if (!data) return data.error();
    for (std::size_t k = 0; k < data->faces.size(); ++k) {
      FaceInfo fi;
      fi.index = data->source_faces.empty() ? static_cast<int>(k) : data->source_faces[k];
      fi.name = data->faces[k].name;
      fi.kind = "builtin:" + spec.first;
      run.faces_info.push_back(fi);
    }
    return surface_from_shell(job, std::move(data).value(), run);
  }
  auto data = builtin_mold(spec.first, spec.second);
  if (!data) return data.error();
  FaceInfo fi;
  fi.name = data->name;
  fi.kind = "builtin:" + spec.first;
  run.faces_info.push_back(fi);
  return surface_from_face(job, std::move(data).value(), run);
}

Result<MoldSurface> load_face_of(const DrapeJob& job, importers::MoldFile& file,
                                 exporters::RunInfo& run);

// Distance from p to a box (0 inside; infinite for an empty box).
double box_distance(const BBox3& b, const Vec3& p) {
  if (b.empty) return std::numeric_limits<double>::infinity();
  return (p - p.cwiseMax(b.min).cwiseMin(b.max)).norm();
}

// The face of the file nearest p: faces in order of their boxes' distance, each converted and
// projected onto while its box is nearer than the best face so far (a face's box holds it).
Result<int> face_at(importers::MoldFile& file, const Vec3& p, const Tolerances& tol) {
  const Mold& mold = file.mold();
  std::vector<std::pair<double, int>> order;
  for (const FaceInfo& f : mold.faces) order.emplace_back(box_distance(f.bbox, p), f.index);
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  int best_face = -1;
  for (const auto& [box, index] : order) {
    if (!(box < best)) break;
    auto data = file.convert_face(index);
    if (!data) continue;  // a face that does not convert is not under the point
    auto surface = MoldSurface::from_face(std::move(data).value(), tol);
    if (!surface) continue;
    const Projection pr = surface->project(p);
    if (pr.ok && pr.distance < best) {
      best = pr.distance;
      best_face = index;
    }
  }
  if (best_face < 0) return no_face_at(p);
  return best_face;
}

Result<MoldSurface> load_file(const DrapeJob& job, exporters::RunInfo& run) {
  importers::ImportOptions io;
  io.format = job.format;
  io.tolerances = job.drape.tol;
  auto file = importers::open_mold(job.mold, io);
  if (!file) return file.error();
  if (job.all_faces || job.connected_faces || !job.faces.empty()) {
    const bool every = job.all_faces || job.connected_faces;
    auto data = (*file)->convert_shell(every ? (*file)->all_faces() : job.faces);
    if (data && job.connected_faces) data = connected_part(job, std::move(data).value());
    if (!data) return data.error();
    for (int i : data->source_faces) {
      auto info = (*file)->describe(i);
      if (!info) return info.error();
      run.faces_info.push_back(*info);
    }
    run.mold_unit = (*file)->summary().unit;
    run.warnings = (*file)->summary().warnings;
    return surface_from_shell(job, std::move(data).value(), run);
  }
  if (job.faces_at) {
    auto face = face_at(**file, *job.faces_at, job.drape.tol);
    if (!face) return Error(face.error()).in("faces-at");
    DrapeJob at = job;
    at.face = *face;
    at.faces_at.reset();
    return load_face_of(at, **file, run);
  }
  return load_face_of(job, **file, run);
}

// Face job.face of an open file: only this face is described and converted, the others are
// never listed.
Result<MoldSurface> load_face_of(const DrapeJob& job, importers::MoldFile& file,
                                 exporters::RunInfo& run) {
  auto info = file.describe(job.face);
  if (!info) return info.error();
  run.faces_info.push_back(*info);
  run.mold_unit = file.summary().unit;
  run.warnings = file.summary().warnings;
  auto data = file.convert_face(job.face);
  if (!data) return data.error();
  return surface_from_face(job, std::move(data).value(), run);
}

}  // namespace

Result<MoldSurface> load_surface(const DrapeJob& job, exporters::RunInfo* run_out) {
  exporters::RunInfo scratch;
  exporters::RunInfo& run = run_out ? *run_out : scratch;
  if (job.mold.rfind("builtin:", 0) != 0) return load_file(job, run);
  auto spec = parse_builtin_spec(job.mold.substr(8));
  if (!spec) return spec.error();
  if (job.face != 0 || !job.faces.empty())
    return Error{ErrorCode::kBuiltinFaceGiven, job.faces.empty() ? "face" : "faces"};
  return load_builtin(job, *spec, run);
}

}  // namespace plyfit::cli
