#include "face_measure.hpp"

#include "face_measure_parts.hpp"

#include <plyfit/kernel/nurbs.hpp>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <TColStd_Array1OfReal.hxx>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace plyfit::importers::occt {

using namespace measure;

namespace {

// OpenCASCADE's evaluation: analytic, swept, offset and periodic B-spline surfaces.
class OcctEvaluator final : public Evaluator {
 public:
  explicit OcctEvaluator(Handle(Geom_Surface) s) : s_(std::move(s)) {}
  void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const override {
    gp_Pnt P;
    gp_Vec U, V;
    s_->D1(u, v, P, U, V);
    p = Vec3(P.X(), P.Y(), P.Z());
    du = Vec3(U.X(), U.Y(), U.Z());
    dv = Vec3(V.X(), V.Y(), V.Z());
  }

 private:
  Handle(Geom_Surface) s_;
};

// The kernel's evaluation of the same B-spline: OpenCASCADE's span cache is rebuilt at every
// change of span, which the inner integrals make all the time.
class KernelEvaluator final : public Evaluator {
 public:
  explicit KernelEvaluator(std::shared_ptr<const NurbsSurface> s) : s_(std::move(s)) {}
  void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const override {
    const SurfaceEval1 e = s_->eval1(u, v);
    p = e.p;
    du = e.du;
    dv = e.dv;
  }
  const std::shared_ptr<const NurbsSurface>& surface() const { return s_; }

 private:
  bool has_rows() const override { return true; }
  void row_d1(double v, const double* us, int n, SurfaceEval1* out) const override {
    s_->eval1_along_u(v, us, static_cast<std::size_t>(n), out);
  }
  std::shared_ptr<const NurbsSurface> s_;
};

// The kernel copy of a non-periodic B-spline, or nothing.
std::unique_ptr<KernelEvaluator> kernel_evaluator(const Handle(Geom_BSplineSurface) & b) {
  if (b.IsNull() || b->IsUPeriodic() || b->IsVPeriodic()) return nullptr;
  auto s = NurbsSurface::create(nurbs_data(b));
  if (!s) return nullptr;
  return std::make_unique<KernelEvaluator>(
      std::make_shared<const NurbsSurface>(std::move(s).value()));
}

// `box`, or an empty box when a corner is not finite (a point evaluated off a broken face).
BBox3 finite_or_empty(const BBox3& box) {
  return box.empty || (box.min.allFinite() && box.max.allFinite()) ? box : BBox3{};
}

FaceMeasure fallback(const TopoDS_Face& face, double rel_tol, bool with_box) {
  FaceMeasure m;
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props, rel_tol);
  m.area = props.Mass();
  if (with_box) {
    Bnd_Box box;
    BRepBndLib::AddOptimal(face, box, Standard_False, Standard_False);
    if (!box.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      m.bbox.add(Vec3(x0, y0, z0));
      m.bbox.add(Vec3(x1, y1, z1));
    }
  }
  if (!std::isfinite(m.area)) {
    m.area = 0.0;
    m.measured = false;
    m.failure = "OpenCASCADE's integration gave no finite value";
  }
  m.bbox = finite_or_empty(m.bbox);
  return m;
}

}  // namespace

NurbsSurfaceData nurbs_data(const Handle(Geom_BSplineSurface) & b) {
  NurbsSurfaceData d;
  d.degree_u = b->UDegree();
  d.degree_v = b->VDegree();
  d.count_u = b->NbUPoles();
  d.count_v = b->NbVPoles();
  TColStd_Array1OfReal ku(1, d.count_u + d.degree_u + 1), kv(1, d.count_v + d.degree_v + 1);
  b->UKnotSequence(ku);
  b->VKnotSequence(kv);
  d.knots_u.assign(ku.begin(), ku.end());
  d.knots_v.assign(kv.begin(), kv.end());
  const bool rational = b->IsURational() || b->IsVRational();
  d.poles.reserve(static_cast<size_t>(d.count_u) * d.count_v);
  for (int i = 1; i <= d.count_u; ++i)
    for (int j = 1; j <= d.count_v; ++j) {
      const gp_Pnt& p = b->Pole(i, j);
      d.poles.emplace_back(p.X(), p.Y(), p.Z());
      if (rational) d.weights.push_back(b->Weight(i, j));
    }
  return d;
}

FaceMeasure measure_face(const TopoDS_Face& face, double rel_tol, bool with_box, bool transposed) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  if (s.IsNull()) return fallback(face, rel_tol, with_box);
  Handle(Geom_Surface) basis = s;
  while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(basis))
    basis = t->BasisSurface();
  Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(basis);
  if (const auto z = Handle(Geom_BezierSurface)::DownCast(basis); !z.IsNull())
    bspline = GeomConvert::SurfaceToBSplineSurface(z);
  std::unique_ptr<KernelEvaluator> kernel = kernel_evaluator(bspline);
  std::shared_ptr<const NurbsSurface> surface = kernel ? kernel->surface() : nullptr;
  std::unique_ptr<Evaluator> eval = std::move(kernel);
  if (!eval) eval = std::make_unique<OcctEvaluator>(basis);
  eval->transposed = transposed;
  if (!bspline.IsNull())
    eval->budget +=
        kMeasureEvaluationsPerPatch * (bspline->NbUKnots() - 1) * (bspline->NbVKnots() - 1);
  const Handle(Geom_Surface)& geometry = bspline.IsNull() ? basis : bspline;

  std::vector<EdgeRef> edges;
  std::vector<std::pair<double, double>> ranges;
  if (!boundary_of(face, transposed, edges, ranges)) return fallback(face, rel_tol, with_box);
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (transposed) {
    std::swap(u0, v0);
    std::swap(u1, v1);
  }
  const Region region{geometry, transposed, u0, u1, v0, v1, edges, ranges};

  FaceMeasure m;
  try {
    if (with_box) m.bbox = finite_or_empty(face_box(*eval, edges, ranges, u0, u1, v0, v1));
    // The inner share assumes the boundary's rows add up to about the area; where they add up
    // to more (rows of both signs that cancel) and the table's error is what misses the
    // accuracy, the table is made again, tighter by the ratio.
    Pass pass = integrate_pass(*eval, region, rel_tol, kInnerShare * rel_tol);
    const double area = std::abs(pass.total), inner = pass.inner_rel * pass.magnitude;
    if (pass.error + inner > rel_tol * area && inner > kOuterShare * rel_tol * area &&
        pass.magnitude > area)
      pass = integrate_pass(*eval, region, rel_tol, kInnerShare * rel_tol * area / pass.magnitude);
    m.area = std::abs(pass.total);
    m.error = pass.error + pass.inner_rel * pass.magnitude;
    m.converged = m.error <= std::max(rel_tol * m.area, kRoundoffFloor * pass.magnitude);
    if (!std::isfinite(m.area) || !std::isfinite(m.error))
      throw WorkCapReached{"the integration gave no finite value"};
  } catch (const WorkCapReached& e) {
    const BBox3 box = m.bbox;  // the box alone, if made
    m = FaceMeasure{};
    m.bbox = box;
    m.measured = false;
    m.failure = e.what;
  }
  m.evaluations = eval->count;
  m.surface = std::move(surface);
  return m;
}

std::optional<Warning> area_warning(const FaceMeasure& m, double rel, int face,
                                    const std::string& entity) {
  if (!m.measured)
    return Warning{WarningCode::kFaceAreaUnmeasured, {std::int64_t{face}, entity, m.failure}};
  if (m.converged) return std::nullopt;
  Warning w{WarningCode::kFaceAreaShort, {std::int64_t{face}, entity, rel}};
  // Without an estimate (OpenCASCADE's integration, no pcurves) the accuracy is unknown.
  if (m.area > 0.0 && m.error > 0.0) w.values.emplace_back(m.error / m.area);
  return w;
}

}  // namespace plyfit::importers::occt
