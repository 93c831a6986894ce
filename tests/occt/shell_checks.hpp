#pragma once
// Checks of a sewn shell (ShellData) against its file, for the shell tests
// (importers/shell_test.cpp, importers/shell_corpus_test.cpp): the uses of every shared edge
// lie on each other and run in opposite directions, the faces are convert_face's with loops on
// the original edges, and contains() agrees with OpenCASCADE's classifier.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>
#include "surface/shell/shell.hpp"

#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"
#include "support/warnings.hpp"

#include <map>
#include <set>

namespace plyfit::test {

/// The trim polylines' accuracy (Tolerances::trim_chord_rel of the face size): a polyline's
/// on-surface chords lie within it of the exact edge.
const double kChordRel = Tolerances{}.trim_chord_rel;
/// Golden-section steps for the nearest point of an on-surface chord (0.618^60 ~ 3e-13 of the
/// segment).
constexpr int kGoldenSteps = 60;
/// Nearest segments (by their straight 3D chords) searched on the surface for each point.
constexpr int kCandidateSegments = 3;

// ---------------------------------------------------------------------------------------------
// The runs of a shell's loops: maximal runs of segments with one tag.

struct EdgeRun {
  int face = 0;
  std::int32_t tag = TrimLoop::kFreeEdge;
  std::vector<Vec2> uv;  // the run's points, its first segment's start to its last one's end
};

inline std::vector<EdgeRun> edge_runs(const ShellData& shell) {
  std::vector<EdgeRun> runs;
  for (size_t f = 0; f < shell.faces.size(); ++f) {
    for (const auto& loop : shell.faces[f].loops) {
      const size_t n = loop.points.size();
      REQUIRE(n >= 3);
      REQUIRE(loop.edges.size() == n);
      for (auto t : loop.edges) CHECK((t >= TrimLoop::kFreeEdge && t < shell.edge_count));
      size_t start = 0;
      while (start < n && loop.edges[start] == loop.edges[(start + n - 1) % n]) ++start;
      if (start == n) {  // one edge closes the loop alone
        EdgeRun r{static_cast<int>(f), loop.edges[0], loop.points};
        r.uv.push_back(loop.points[0]);
        runs.push_back(std::move(r));
        continue;
      }
      for (size_t k = 0; k < n; ++k) {
        const size_t s = (start + k) % n;
        if (k == 0 || loop.edges[s] != loop.edges[(s + n - 1) % n])
          runs.push_back(EdgeRun{static_cast<int>(f), loop.edges[s], {loop.points[s]}});
        runs.back().uv.push_back(loop.points[(s + 1) % n]);
      }
    }
  }
  return runs;
}

// Distance from p to the on-surface chord S(a + s (b - a)), s in [0, 1] (golden section).
inline double chord_distance(const Face& face, const Vec3& p, const Vec2& a, const Vec2& b) {
  auto d = [&](double s) { return (face.eval1(a + s * (b - a)).p - p).norm(); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = d(x1), f2 = d(x2);
  for (int i = 0; i < kGoldenSteps; ++i) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = d(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = d(x2);
    }
  }
  return std::min({f1, f2, d(0.0), d(1.0)});
}

inline double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t =
      ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Largest distance from the points of run `a` (on their face) to run `b` as it lies on its
// face (its on-surface chords).
inline double run_distance(const EdgeRun& a, const Face& fa, const EdgeRun& b, const Face& fb) {
  std::vector<Vec3> pb;
  for (const Vec2& uv : b.uv) pb.push_back(fb.eval1(uv).p);
  double worst = 0.0;
  for (const Vec2& uv : a.uv) {
    const Vec3 p = fa.eval1(uv).p;
    std::vector<std::pair<double, size_t>> near;
    for (size_t k = 0; k + 1 < pb.size(); ++k)
      near.emplace_back(segment_distance(p, pb[k], pb[k + 1]), k);
    const size_t m = std::min<size_t>(kCandidateSegments, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<long>(m), near.end());
    double best = 1e300;
    for (size_t c = 0; c < m; ++c)
      best = std::min(best, chord_distance(fb, p, b.uv[near[c].second], b.uv[near[c].second + 1]));
    worst = std::max(worst, best);
  }
  return worst;
}

// Direction of a run in 3D at its middle.
inline Vec3 run_direction(const EdgeRun& r, const Face& f, Vec3& at) {
  const size_t k = (r.uv.size() - 1) / 2;
  at = f.eval1(r.uv[k]).p;
  return f.eval1(r.uv[k + 1]).p - at;
}

struct ShellCheck {
  int shared = 0;          // shared edges, each used once by two faces
  int free_runs = 0;       // runs of free segments
  int vertices = 0;        // distinct 3D points where runs meet
  double worst_ratio = 0;  // largest use-to-use distance over the allowed one
};

// Every shared edge is used by exactly two faces, whose polylines lie on the same 3D curve
// within the shell's tolerance plus the polylines' chord accuracy, and run in opposite
// directions (the faces are oriented alike). `sizes`: each face's size as the importer
// measured it (the listing's bounding-box diagonal), which scales its chord accuracy.
inline ShellCheck check_shell(const ShellData& shell, const std::vector<Face>& faces,
                              const std::vector<double>& sizes) {
  ShellCheck out;
  const auto runs = edge_runs(shell);
  std::map<std::int32_t, std::vector<const EdgeRun*>> uses;
  std::vector<Vec3> corners;
  double largest = 0.0;
  for (double s : sizes) largest = std::max(largest, s);
  for (const auto& r : runs) {
    if (r.tag == TrimLoop::kFreeEdge)
      ++out.free_runs;
    else
      uses[r.tag].push_back(&r);
    corners.push_back(faces[static_cast<size_t>(r.face)].eval1(r.uv.front()).p);
  }
  CHECK(static_cast<int>(uses.size()) == shell.edge_count);
  for (const auto& [tag, u] : uses) {
    INFO("shared edge " << tag);
    REQUIRE(u.size() == 2);
    CHECK(u[0]->face != u[1]->face);
    const Face &fa = faces[static_cast<size_t>(u[0]->face)],
               &fb = faces[static_cast<size_t>(u[1]->face)];
    const double allowed_ab = shell.tolerance + kChordRel * sizes[static_cast<size_t>(u[1]->face)];
    const double allowed_ba = shell.tolerance + kChordRel * sizes[static_cast<size_t>(u[0]->face)];
    const double ab = run_distance(*u[0], fa, *u[1], fb), ba = run_distance(*u[1], fb, *u[0], fa);
    CHECK(ab <= allowed_ab);
    CHECK(ba <= allowed_ba);
    out.worst_ratio = std::max({out.worst_ratio, ab / allowed_ab, ba / allowed_ba});
    Vec3 at_a, at_b;
    const Vec3 da = run_direction(*u[0], fa, at_a);
    run_direction(*u[1], fb, at_b);
    // The direction of b's polyline next to a's middle point.
    size_t nearest = 0;
    double dn = 1e300;
    for (size_t k = 0; k + 1 < u[1]->uv.size(); ++k) {
      const double d = segment_distance(at_a, fb.eval1(u[1]->uv[k]).p, fb.eval1(u[1]->uv[k + 1]).p);
      if (d < dn) dn = d, nearest = k;
    }
    const Vec3 db = fb.eval1(u[1]->uv[nearest + 1]).p - fb.eval1(u[1]->uv[nearest]).p;
    CHECK(da.dot(db) < 0.0);
    ++out.shared;
  }
  // Run ends closer than the shell's tolerance plus the chord accuracy are one vertex.
  const double merge = shell.tolerance + kChordRel * largest;
  std::vector<Vec3> distinct;
  for (const Vec3& c : corners) {
    bool known = false;
    for (const Vec3& d : distinct) known = known || (c - d).norm() <= merge;
    if (!known) distinct.push_back(c);
  }
  out.vertices = static_cast<int>(distinct.size());
  return out;
}

// The shell's faces as kernel faces, and their sizes from the listing.
inline std::pair<std::vector<Face>, std::vector<double>> kernel_faces(importers::MoldFile& file,
                                                                      const ShellData& shell) {
  std::vector<Face> faces;
  std::vector<double> sizes;
  for (size_t k = 0; k < shell.faces.size(); ++k) {
    auto face = Face::create(shell.faces[k]);
    REQUIRE(face.ok());
    faces.push_back(std::move(face).value());
    auto info = file.describe(shell.source_faces[k]);
    REQUIRE(info.ok());
    sizes.push_back(info->bbox.diagonal());
  }
  return {std::move(faces), std::move(sizes)};
}

/// The surface images of a converted face's trim polylines (about 60 segment midpoints per
/// loop) lie on the original face's edges, within the polylines' chord accuracy plus the edges'
/// tolerance (OCCT's 3D curves and pcurves agree only to it) plus `extra`.
inline void check_on_edges(const Face& face, const TopoDS_Face& original, double extra) {
  TopoDS_Compound edges;
  BRep_Builder builder;
  builder.MakeCompound(edges);
  double edge_tol = 0.0;
  for (TopExp_Explorer ex(original, TopAbs_EDGE); ex.More(); ex.Next()) {
    builder.Add(edges, ex.Current());
    edge_tol = std::max(edge_tol, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  }
  const double allowed = kChordRel * occt_size(original) + edge_tol + extra;
  BRepExtrema_DistShapeShape dist;
  dist.LoadS2(edges);
  for (const auto& loop : face.loops()) {
    const size_t n = loop.points.size();
    for (size_t k = 0; k < n; k += std::max<size_t>(1, n / 60)) {
      const Vec3 p = face.eval1(0.5 * (loop.points[k] + loop.points[(k + 1) % n])).p;
      dist.LoadS1(BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex());
      REQUIRE(dist.Perform());
      CHECK(dist.Value() <= allowed);
    }
  }
}

// Each face of the shell is the face convert_face gives (same NURBS, closed_u/v), but with
// loops; orientation as convert_face's unless the face is in `reoriented`. contains() agrees
// with OpenCASCADE's classifier on the original face.
inline void check_faces_like_convert_face(importers::MoldFile& file, const ShellData& shell,
                                          const std::vector<Face>& faces, const Reference& ref,
                                          const std::set<int>& reoriented, int samples) {
  Rng rng(5);
  for (size_t k = 0; k < shell.faces.size(); ++k) {
    const int i = shell.source_faces[k];
    INFO("face " << i);
    auto single = file.convert_face(i);
    REQUIRE(single.ok());
    const FaceData& s = shell.faces[k];
    CHECK(s.surface.knots_u == single->surface.knots_u);
    CHECK(s.surface.knots_v == single->surface.knots_v);
    CHECK(s.surface.weights == single->surface.weights);
    REQUIRE(s.surface.poles.size() == single->surface.poles.size());
    double pole_moved = 0.0;
    for (size_t p = 0; p < s.surface.poles.size(); ++p)
      pole_moved = std::max(pole_moved, (s.surface.poles[p] - single->surface.poles[p]).norm());
    // Exactly the same for B-splines; planes are converted over their (u, v) range, which the
    // sewing's new pcurves can change by round-off.
    CHECK(pole_moved <= kRoundoffRel * faces[k].size());
    CHECK(s.closed_u == single->closed_u);
    CHECK(s.closed_v == single->closed_v);
    CHECK(s.reversed == (single->reversed != (reoriented.count(i) > 0)));
    // Closed loops on the face's boundary: on the original face's edges, which the sewing
    // moved by at most the gap it closed.
    CHECK_FALSE(s.loops.empty());
    check_on_edges(faces[k], ref.face(i), shell.tolerance);
    CHECK(check_contains(faces[k], face_in_converted_parameters(ref.face(i)), samples, rng) >
          samples / 2);
  }
}

/// Marks an expectation of check_kernel_shell as not checked.
constexpr int kUnchecked = -1000;

/// The kernel's Shell built from the importer's data: it accepts it, and finds the Euler
/// characteristic and the number of free boundary loops given (known independently; or
/// kUnchecked).
inline void check_kernel_shell(const ShellData& data, int euler, int free_loops) {
  auto shell = Shell::create(data);
  INFO((shell.ok() ? std::string() : exporters::describe(shell.error())));
  REQUIRE(shell.ok());
  CHECK(shell->face_count() == static_cast<std::int32_t>(data.faces.size()));
  CHECK(shell->edge_count() == data.edge_count);
  if (euler != kUnchecked) CHECK(shell->euler_characteristic() == euler);
  if (free_loops != kUnchecked) CHECK(shell->free_loop_count() == free_loops);
}

/// The warnings of sewing faces into a shell among `warnings`.
inline std::vector<Warning> sewing_warnings(const std::vector<Warning>& warnings) {
  return support::with_codes(warnings,
                             {WarningCode::kSeparateShells, WarningCode::kNonManifoldEdges,
                              WarningCode::kFacesReoriented, WarningCode::kShellNotOrientable});
}

/// The one warning of `warnings` with `code`, as the numbers of its values (empty when there
/// is none; a second one fails the test).
inline std::vector<double> the_warning(const std::vector<Warning>& warnings, WarningCode code) {
  const auto found = support::with_code(warnings, code);
  CHECK(found.size() <= 1);
  return found.empty() ? std::vector<double>{} : support::numbers(found.front());
}

}  // namespace plyfit::test
