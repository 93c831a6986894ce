#pragma once
// Independent OpenCASCADE checks for the importer tests: the files are read again here with
// OCCT's own readers (not through plyfit), faces are walked in the documented order
// (TopExp::MapShapes), and the converted kernel faces are compared with OCCT's evaluation,
// classification and projection of the original faces.

#include <plyfit/importers/importers.hpp>
#include "nurbs_conversion.hpp"  // occt/src: kernel NURBS as OpenCASCADE geometry
#include "surface/face.hpp"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Plane.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Precision.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "test_util.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace plyfit::test {

using plyfit::occt::to_occt;

/// Converted surfaces must reproduce OCCT's evaluation of the original face to this fraction
/// of the face size (the brief's accuracy for exact conversions).
constexpr double kSurfaceAgreementRel = 1e-9;
/// Normals of the converted and the original face must agree to this cosine (orientation).
constexpr double kNormalAgreementCos = 0.999;
/// Points closer than this fraction of the (u, v) box diagonal to the exact boundary (OCCT's
/// pcurves, sampled finely) are not compared with the classifier: the trim polylines are
/// within trim_chord_rel of the face size of the boundary, far inside this band.
constexpr double kBoundaryBandRel = 1e-3;
/// Deflection of the fine sampling of the exact boundary used for the band, relative to the
/// (u, v) box diagonal.
constexpr double kBoundarySamplingRel = 1e-5;

/// A sample mold written by plyfit (samples/molds, committed).
inline std::string sample_mold(const std::string& name) {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/" + name;
}

/// True for an IGES file name (.igs, .iges).
inline bool is_iges(const std::string& name) {
  return name.find(".igs") != std::string::npos || name.find(".iges") != std::string::npos;
}

/// A file read by OCCT's own reader, its faces in TopExp::MapShapes order.
struct Reference {
  TopoDS_Shape shape;
  TopTools_IndexedMapOfShape faces;
  int count() const { return faces.Extent(); }
  TopoDS_Face face(int index) const { return TopoDS::Face(faces(index + 1)); }
};

inline Reference read_reference(const std::string& path, bool iges) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Reference r;
  if (iges) {
    IGESControl_Reader reader;
    REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
    reader.TransferRoots();
    r.shape = reader.OneShape();
  } else {
    STEPControl_Reader reader;
    REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
    reader.TransferRoots();
    r.shape = reader.OneShape();
  }
  TopExp::MapShapes(r.shape, TopAbs_FACE, r.faces);
  return r;
}

/// Bounding-box diagonal of a face by OCCT (the face size used to scale tolerances).
inline double occt_size(const TopoDS_Face& f) {
  Bnd_Box b;
  BRepBndLib::AddOptimal(f, b, Standard_False, Standard_False);
  return std::sqrt(b.SquareExtent());
}

/// True when OCCT's NURBS conversion keeps the face's (u, v): B-splines and Béziers are kept
/// as they are and a plane becomes a bilinear patch over the same range.
inline bool keeps_parameters(const TopoDS_Face& f) {
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  return s->DynamicType() == STANDARD_TYPE(Geom_BSplineSurface) ||
         s->DynamicType() == STANDARD_TYPE(Geom_BezierSurface) ||
         s->DynamicType() == STANDARD_TYPE(Geom_Plane);
}

/// The exact boundary of a face in (u, v), sampled finely by OCCT, as segments bucketed in a
/// grid of cells as wide as the band, for the "near the boundary" test.
struct Boundary {
  std::vector<std::pair<Vec2, Vec2>> segs;  // in the normalised (u, v) box
  double u0 = 0, v0 = 0, scale_u = 1, scale_v = 1;
  std::unordered_map<int64_t, std::vector<int>> cells;

  explicit Boundary(const TopoDS_Face& f) {
    double u1, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    scale_u = std::max(u1 - u0, Precision::PConfusion());
    scale_v = std::max(v1 - v0, Precision::PConfusion());
    const double defl = kBoundarySamplingRel * std::hypot(u1 - u0, v1 - v0);
    for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
      double a, b;
      const auto c = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), f, a, b);
      if (c.IsNull()) continue;
      Geom2dAdaptor_Curve ad(c, a, b);
      GCPnts_QuasiUniformDeflection pts(ad, defl);
      REQUIRE(pts.IsDone());
      for (int k = 1; k < pts.NbPoints(); ++k) {
        const gp_Pnt2d p = ad.Value(pts.Parameter(k)), q = ad.Value(pts.Parameter(k + 1));
        segs.emplace_back(normal(Vec2(p.X(), p.Y())), normal(Vec2(q.X(), q.Y())));
      }
    }
    for (int s = 0; s < static_cast<int>(segs.size()); ++s) {
      const Vec2 lo = segs[s].first.cwiseMin(segs[s].second).array() - kBoundaryBandRel;
      const Vec2 hi = segs[s].first.cwiseMax(segs[s].second).array() + kBoundaryBandRel;
      for (int64_t i = cell(lo.x()); i <= cell(hi.x()); ++i)
        for (int64_t j = cell(lo.y()); j <= cell(hi.y()); ++j) cells[key(i, j)].push_back(s);
    }
  }
  Vec2 normal(const Vec2& uv) const {
    return Vec2((uv.x() - u0) / scale_u, (uv.y() - v0) / scale_v);
  }
  static int64_t cell(double x) { return static_cast<int64_t>(std::floor(x / kBoundaryBandRel)); }
  static int64_t key(int64_t i, int64_t j) { return (i << 32) ^ (j & 0xffffffff); }
  /// True when uv lies within kBoundaryBandRel of the boundary, in the normalised (u, v) box.
  bool near(const Vec2& uv) const {
    const Vec2 p = normal(uv);
    const auto it = cells.find(key(cell(p.x()), cell(p.y())));
    if (it == cells.end()) return false;
    for (int s : it->second) {
      const Vec2 a = segs[s].first, ab = segs[s].second - a;
      const double t =
          ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((a + t * ab - p).norm() < kBoundaryBandRel) return true;
    }
    return false;
  }
};

/// Random points of a face by OCCT: uniform in its (u, v) bounds, kept when the classifier
/// says IN.
inline std::vector<Vec2> points_inside(const TopoDS_Face& f, int n, Rng& rng) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  std::vector<Vec2> out;
  BRepClass_FaceClassifier cls;
  for (int tries = 0; tries < 50 * n && static_cast<int>(out.size()) < n; ++tries) {
    const Vec2 uv(rng.uniform(u0, u1), rng.uniform(v0, v1));
    cls.Perform(f, gp_Pnt2d(uv.x(), uv.y()), Precision::PConfusion());
    if (cls.State() == TopAbs_IN) out.push_back(uv);
  }
  return out;
}

/// Checks a converted face against the original OCCT face: position (same (u, v) when the
/// conversion keeps parameters, else by projection both ways) to `rel_tol` of the face size,
/// and outward normal. Returns the largest deviation found, relative to the face size.
inline double check_surface(const Face& face, const TopoDS_Face& original, int samples, Rng& rng,
                            double rel_tol = kSurfaceAgreementRel) {
  const Handle(Geom_Surface) os = BRep_Tool::Surface(original);
  const double size = occt_size(original);
  const double tol = rel_tol * size;
  const bool same_uv = keeps_parameters(original);
  const double sign = original.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0;
  const Handle(Geom_BSplineSurface) converted = to_occt(face.surface().data());
  GeomAPI_ProjectPointOnSurf proj_conv;
  double worst = 0.0;
  for (const Vec2& uv : points_inside(original, samples, rng)) {
    const gp_Pnt P = os->Value(uv.x(), uv.y());
    const Vec3 p(P.X(), P.Y(), P.Z());
    Vec2 kuv = uv;
    if (same_uv) {
      const Vec3 q = face.eval1(uv).p;
      worst = std::max(worst, (q - p).norm() / size);
      CHECK((q - p).norm() <= tol);
    } else {
      // Project with OCCT onto the same NURBS rebuilt from the kernel's data, then evaluate
      // the kernel face at the parameters found.
      proj_conv.Init(P, converted);
      REQUIRE(proj_conv.NbPoints() > 0);
      double pu, pv;
      proj_conv.LowerDistanceParameters(pu, pv);
      kuv = Vec2(pu, pv);
      const double dist = (face.eval1(kuv).p - p).norm();
      worst = std::max(worst, dist / size);
      CHECK(dist <= tol);
    }
    GeomLProp_SLProps props(os, uv.x(), uv.y(), 1, Precision::Confusion());
    const SurfaceNormal kn = face.normal(kuv);
    if (props.IsNormalDefined() && !kn.degenerate) {
      const gp_Dir n = props.Normal();
      CHECK(sign * Vec3(n.X(), n.Y(), n.Z()).dot(kn.n) >= kNormalAgreementCos);
    }
  }
  if (!same_uv) {
    // The other way: points of the converted face lie on the original surface.
    const auto& d = face.domain();
    GeomAPI_ProjectPointOnSurf proj;
    int done = 0;
    for (int tries = 0; tries < 50 * samples && done < samples; ++tries) {
      const Vec2 uv(rng.uniform(d.u0, d.u1), rng.uniform(d.v0, d.v1));
      if (!face.contains(uv)) continue;
      const Vec3 q = face.eval1(uv).p;
      proj.Init(gp_Pnt(q.x(), q.y(), q.z()), os);
      REQUIRE(proj.NbPoints() > 0);
      worst = std::max(worst, proj.LowerDistance() / size);
      CHECK(proj.LowerDistance() <= tol);
      ++done;
    }
    CHECK(done == samples);
  }
  return worst;
}

/// Compares Face::contains with OCCT's classifier at `n` random (u, v) of the face's (u, v)
/// box (enlarged by 5% in open directions), skipping the band around the exact boundary.
/// `classified` is the OCCT face in the converted face's parameters (the original when the
/// conversion keeps parameters, else OCCT's own NURBS conversion of it). Returns the number
/// of points compared.
inline int check_contains(const Face& face, const TopoDS_Face& classified, int n, Rng& rng) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(classified, u0, u1, v0, v1);
  const double mu = face.closed_u() ? 0.0 : 0.05 * (u1 - u0);
  const double mv = face.closed_v() ? 0.0 : 0.05 * (v1 - v0);
  const Boundary boundary(classified);
  // OCCT's face classifier with its boundary polygons built once (BRepTopAdaptor_FClass2d);
  // ON answers (within its tolerance of the boundary) are skipped.
  const BRepTopAdaptor_FClass2d cls(classified, Precision::PConfusion());
  int compared = 0, disagree = 0;
  for (int k = 0; k < n; ++k) {
    const Vec2 uv(rng.uniform(u0 - mu, u1 + mu), rng.uniform(v0 - mv, v1 + mv));
    if (boundary.near(uv)) continue;
    const TopAbs_State st = cls.Perform(gp_Pnt2d(uv.x(), uv.y()), Standard_False);
    if (st == TopAbs_ON) continue;
    ++compared;
    if (face.contains(uv) != (st == TopAbs_IN)) {
      ++disagree;
      if (disagree <= 3)
        UNSCOPED_INFO("disagreement at uv (" << uv.x() << ", " << uv.y() << "): contains "
                                             << face.contains(uv) << ", OCCT "
                                             << (st == TopAbs_IN ? "IN" : "OUT"));
    }
  }
  CHECK(disagree == 0);
  return compared;
}

/// The OCCT face whose (u, v) the converted face uses: the original when the conversion keeps
/// parameters, else OCCT's NURBS conversion of it.
inline TopoDS_Face face_in_converted_parameters(const TopoDS_Face& original) {
  if (keeps_parameters(original)) return original;
  BRepBuilderAPI_NurbsConvert nc(original, Standard_True);
  return TopoDS::Face(nc.ModifiedShape(original));
}

/// The surface images of points along the trim polylines of every trimmed face of `path` lie
/// within trim_chord_rel of the face size (plus the edge's own tolerance: OCCT's 3D edge curve
/// and its pcurve agree only to it) of the face's edges, OCCT's 3D curves. Returns the worst
/// distance over the allowed one.
inline double check_trim_accuracy(const std::string& path) {
  INFO(path);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Reference ref = read_reference(path, is_iges(path));
  const Tolerances tol;
  double worst = 0.0;
  for (int i = 0; i < ref.count(); ++i) {
    INFO("face " << i);
    auto data = (*file)->convert_face(i);
    REQUIRE(data.ok());
    if (data->loops.empty()) continue;
    auto face = Face::create(data.value());
    REQUIRE(face.ok());
    struct EdgeCurve {
      Handle(Geom_Curve) c;
      double a, b, tol;
    };
    std::vector<EdgeCurve> edges;
    for (TopExp_Explorer ex(ref.face(i), TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      EdgeCurve ec;
      ec.c = BRep_Tool::Curve(e, ec.a, ec.b);
      ec.tol = BRep_Tool::Tolerance(e);
      if (!ec.c.IsNull()) edges.push_back(ec);
    }
    const double allowed_base = tol.trim_chord_rel * occt_size(ref.face(i));
    GeomAPI_ProjectPointOnCurve proj;
    for (const auto& loop : face->loops()) {
      const size_t n = loop.points.size();
      const size_t stride = std::max<size_t>(1, n / 60);  // about 60 segments per loop
      for (size_t k = 0; k < n; k += stride) {
        const Vec2 mid = 0.5 * (loop.points[k] + loop.points[(k + 1) % n]);
        const Vec3 p = face->eval1(mid).p;
        const gp_Pnt P(p.x(), p.y(), p.z());
        double best = 1e300, best_allowed = allowed_base;
        for (const auto& ec : edges) {
          double d = std::min(P.Distance(ec.c->Value(ec.a)), P.Distance(ec.c->Value(ec.b)));
          proj.Init(P, ec.c, ec.a, ec.b);
          if (proj.NbPoints() > 0) d = std::min(d, proj.LowerDistance());
          if (d < best) {
            best = d;
            best_allowed = allowed_base + ec.tol;
          }
        }
        worst = std::max(worst, best / best_allowed);
        CHECK(best <= best_allowed);
      }
    }
  }
  return worst;
}

// The OpenCASCADE tests' names for the helpers of cli/cli_util.hpp.
using TempDir = Scratch;
using Run = CliRun;

inline std::string read_bytes(const std::string& path) {
  return slurp(path);
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  spit(path, bytes);
}

/// A run of plyfit must end within this many seconds (a corrupted file must not hang it; the
/// largest shared file reads in well under one).
constexpr int kHangLimitSeconds = 60;

/// Runs the built plyfit binary with `args` under kHangLimitSeconds, with the environment
/// variables `env` ("NAME=value ...") set.
inline Run run_plyfit(const std::string& args, const TempDir& dir, const std::string& env = "") {
  return plyfit_run(args, dir, "", env, kHangLimitSeconds);
}

}  // namespace plyfit::test
