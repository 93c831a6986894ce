// Mold files written by plyfit: kernel NURBS face -> Geom_BSplineSurface -> TopoDS_Face ->
// STEP (STEPControl_Writer) or IGES (IGESControl_Writer), printed through the writers' own
// model printers so that the real format and the header time stamp can be fixed.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>
#include "occt_geometry.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESBasic_Name.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Precision.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <StepGeom_BSplineSurface.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <mutex>

namespace plyfit::exporters {

namespace {
using occt::to_occt;

/// printf format of every real in the written files: 17 significant digits, so that every
/// double reads back bit for bit. At most 23 characters while the exponent has two digits,
/// within the writers' 24-byte buffers (see kSmallestWritten). Zero suppression is off
/// (OpenCASCADE's only looks at the first 16 characters).
constexpr const char* kRealFormat = "%.16E";
/// Magnitudes outside [kSmallestWritten, kLargestWritten] would need a three-digit exponent:
/// smaller ones are written as 0, larger ones are refused.
constexpr double kSmallestWritten = 1e-99;
constexpr double kLargestWritten = 1e99;
/// Tolerance (model units) asked of OpenCASCADE's 3D edge curves, the approximations of the
/// trims' surface images: 1e-7, its Precision::Confusion(), the tolerance CAD files are written to.
/// Edges record the deviation actually reached as their tolerance.
constexpr double kEdgeCurveTolerance = 1e-7;

// Clears magnitudes below kSmallestWritten; false when one is kLargestWritten or more.
bool fits(double& x) {
  if (std::abs(x) < kSmallestWritten) x = 0.0;
  return std::abs(x) < kLargestWritten;
}

template <typename Point>
bool fits(std::vector<Point>& points, std::vector<double>& weights, std::vector<double>& knots) {
  bool all = true;
  for (auto& p : points)
    for (int k = 0; k < p.size(); ++k) all = fits(p[k]) && all;
  for (auto* v : {&weights, &knots})
    for (double& x : *v) all = fits(x) && all;
  return all;
}

// Twice the signed area of a closed polyline (positive: counter-clockwise).
double signed_area2(const std::vector<Vec2>& pts) {
  double a = 0.0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Vec2& p = pts[k];
    const Vec2& q = pts[(k + 1) % pts.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a;
}

// One loop of exact (u, v) curves as a wire of edges on `surface`, counter-clockwise when
// `ccw` (an outer boundary: the face on its left), clockwise otherwise (a hole).
Result<TopoDS_Wire> make_wire(const std::vector<NurbsCurveData2>& curves,
                              const std::vector<Vec2>& polyline,
                              const Handle(Geom_BSplineSurface) & surface, bool ccw) {
  BRepBuilderAPI_MakeWire mw;
  for (const auto& c : curves) {
    const Handle(Geom2d_BSplineCurve) c2 = occt::to_occt(c);
    BRepBuilderAPI_MakeEdge me(c2, surface, c2->FirstParameter(), c2->LastParameter());
    if (!me.IsDone()) return Error{"could not build an edge on a trim curve"};
    mw.Add(me.Edge());
    if (!mw.IsDone()) return Error{"the trim curves of a loop do not join end to end"};
  }
  TopoDS_Wire w = mw.Wire();
  if ((signed_area2(polyline) > 0.0) != ccw) w.Reverse();
  return w;
}

// The face of `b` on its surface as an OpenCASCADE face with its trims (see write_mold).
Result<TopoDS_Face> make_face(const BuiltinFace& b, const ParamDomain& dom) {
  const Handle(Geom_BSplineSurface) bs = to_occt(b.face.surface);
  TopoDS_Face f;
  size_t first_hole = 0;
  if (b.exact_loops.empty() || b.natural_outer) {
    BRepBuilderAPI_MakeFace make(bs, dom.u0, dom.u1, dom.v0, dom.v1, Precision::Confusion());
    if (!make.IsDone()) return Error{"could not build a face on the surface"};
    f = make.Face();
    first_hole = 1;
  } else {
    auto outer = make_wire(b.exact_loops[0], b.face.loops[0].points, bs, true);
    if (!outer) return outer.error();
    BRepBuilderAPI_MakeFace make(bs, *outer, Standard_True);
    if (!make.IsDone()) return Error{"could not build a face inside the outer trim"};
    f = make.Face();
    first_hole = 1;
  }
  if (b.exact_loops.size() > first_hole) {
    BRepBuilderAPI_MakeFace make(f);
    for (size_t k = first_hole; k < b.exact_loops.size(); ++k) {
      auto hole = make_wire(b.exact_loops[k], b.face.loops[k].points, bs, false);
      if (!hole) return hole.error();
      make.Add(*hole);
    }
    if (!make.IsDone()) return Error{"could not add the holes to the face"};
    f = make.Face();
  }
  if (!b.exact_loops.empty()) {
    if (!BRepLib::BuildCurves3d(f, kEdgeCurveTolerance))
      return Error{"could not build the 3D curves of the trims"};
    BRepLib::SameParameter(f, kEdgeCurveTolerance);
    BRepLib::UpdateTolerances(f);
  }
  // A forward face's normal is Su x Sv, as plyfit's; a reversed face is flipped.
  if (b.face.reversed) f.Reverse();
  return f;
}

Handle(TCollection_HAsciiString) hstr(const std::string& s) {
  return new TCollection_HAsciiString(s.c_str());
}

// "2000-01-01T00:00:00" -> IGES "20000101.000000" (digits kept in order).
std::string iges_date(const std::string& iso) {
  std::string digits;
  for (char c : iso)
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  digits.resize(14, '0');
  return digits.substr(0, 8) + "." + digits.substr(8, 6);
}

Status write_step(const TopoDS_Face& face, const std::string& path, const MoldWriteOptions& o,
                  std::ostream& out) {
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", "MM");
  Interface_Static::SetCVal("write.step.product.name", o.name.empty() ? "mold" : o.name.c_str());
  STEPControl_Writer writer;
  if (writer.Transfer(face, STEPControl_AsIs) != IFSelect_RetDone)
    return Error{path + ": the STEP writer could not transfer the face"};
  const Handle(StepData_StepModel) model = writer.Model();
  // The translator numbers its products per process ("mold 1", "mold 2", ...): name it.
  const std::string product = o.name.empty() ? "mold" : o.name;
  for (int i = 1; i <= model->NbEntities(); ++i) {
    if (const auto p = Handle(StepBasic_Product)::DownCast(model->Value(i)); !p.IsNull()) {
      p->SetId(hstr(product));
      p->SetName(hstr(product));
    }
  }
  if (!o.name.empty()) {
    for (int i = 1; i <= model->NbEntities(); ++i) {
      const Handle(Standard_Transient) e = model->Value(i);
      if (const auto f = Handle(StepShape_AdvancedFace)::DownCast(e); !f.IsNull())
        f->SetName(hstr(o.name));
      if (const auto s = Handle(StepGeom_BSplineSurface)::DownCast(e); !s.IsNull())
        s->SetName(hstr(o.name));
    }
  }
  APIHeaderSection_MakeHeader header(model);
  header.SetName(hstr(std::filesystem::path(path).filename().string()));
  header.SetTimeStamp(hstr(o.timestamp));
  header.SetAuthorValue(1, hstr("plyfit"));
  header.SetOrganizationValue(1, hstr("plyfit"));
  header.SetOriginatingSystem(hstr("plyfit"));
  header.SetAuthorisation(hstr(""));
  const auto protocol = Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol());
  if (protocol.IsNull()) return Error{path + ": no STEP protocol"};
  StepData_StepWriter sw(model);
  sw.FloatWriter().SetFormat(kRealFormat);
  sw.SendModel(protocol);
  if (!sw.Print(out)) return Error{path + ": the STEP writer failed"};
  return ok_status();
}

Status write_iges(const TopoDS_Face& face, const std::string& path, const MoldWriteOptions& o,
                  std::ostream& out) {
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);
  if (!writer.AddShape(face)) return Error{path + ": the IGES writer could not transfer the face"};
  const Handle(IGESData_IGESModel) model = writer.Model();
  if (!o.name.empty()) {
    for (int i = 1; i <= model->NbEntities(); ++i) {
      const auto s = Handle(IGESGeom_BSplineSurface)::DownCast(model->Value(i));
      if (s.IsNull()) continue;
      Handle(IGESBasic_Name) name = new IGESBasic_Name;
      name->Init(1, hstr(o.name));
      s->AddProperty(name);
      writer.AddEntity(name);
    }
  }
  writer.ComputeModel();
  IGESData_GlobalSection gs = model->GlobalSection();
  const std::string date = iges_date(o.timestamp);
  gs.SetDate(hstr(date));
  gs.SetLastChangeDate(hstr(date));
  gs.SetFileName(hstr(std::filesystem::path(path).filename().string()));
  gs.SetAuthorName(hstr("plyfit"));
  gs.SetCompanyName(hstr("plyfit"));
  gs.SetSendName(hstr(o.name.empty() ? "mold" : o.name));
  model->SetGlobalSection(gs);
  IGESData_IGESWriter iw(model);
  iw.FloatWriter().SetFormat(kRealFormat);
  iw.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  if (!iw.Print(out)) return Error{path + ": the IGES writer failed"};
  return ok_status();
}

}  // namespace

std::vector<std::string> mold_formats() {
  return {"step", "iges"};
}

Status write_mold(const BuiltinFace& face, const std::string& path,
                  const MoldWriteOptions& options) {
  std::string format = options.format;
  if (format.empty()) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == "step" || ext == "stp") format = "step";
    if (ext == "iges" || ext == "igs") format = "iges";
    if (format.empty())
      return Error{path + ": unknown mold format '" + ext +
                   "' (supported extensions: step, stp, iges, igs)"};
  }
  if (format != "step" && format != "iges")
    return Error{path + ": unknown mold format '" + format + "' (supported: step, iges)"};
  // Validate with the kernel's own rules first: OpenCASCADE throws on bad data.
  BuiltinFace b = face;
  NurbsSurfaceData& data = b.face.surface;
  bool all_fit = fits(data.poles, data.weights, data.knots_u);
  for (double& x : data.knots_v) all_fit = fits(x) && all_fit;
  for (auto& loop : b.exact_loops)
    for (auto& c : loop) all_fit = fits(c.poles, c.weights, c.knots) && all_fit;
  if (!all_fit) return Error{path + ": a pole, weight or knot is 1e99 or larger: not written"};
  auto surface = NurbsSurface::create(data);
  if (!surface) return Error{path + ": invalid surface: " + surface.error().message};
  const ParamDomain& dom = surface->domain();
  if (b.exact_loops.size() != b.face.loops.size())
    return Error{path + ": " + std::to_string(b.exact_loops.size()) + " exact trim loops for " +
                 std::to_string(b.face.loops.size()) + " trim polylines"};
  for (size_t k = 0; k < b.exact_loops.size(); ++k) {
    if (b.exact_loops[k].empty() || b.face.loops[k].points.size() < 3)
      return Error{path + ": trim loop " + std::to_string(k) + " has fewer than three points"};
    for (const auto& c : b.exact_loops[k])
      if (auto cv = NurbsCurve2::create(c); !cv)
        return Error{path + ": invalid trim curve in loop " + std::to_string(k) + ": " +
                     cv.error().message};
    // The domain, widened by the parameter tolerance: trims on its border are kept.
    const double mu = Tolerances{}.param_rel * dom.width_u(),
                 mv = Tolerances{}.param_rel * dom.width_v();
    for (const Vec2& p : b.face.loops[k].points)
      if (!(p.x() >= dom.u0 - mu && p.x() <= dom.u1 + mu && p.y() >= dom.v0 - mv &&
            p.y() <= dom.v1 + mv))
        return Error{path + ": trim loop " + std::to_string(k) +
                     " leaves the surface's parameter domain"};
  }

  // OpenCASCADE's data exchange keeps global state (static parameters, messenger): one
  // writer at a time.
  static std::mutex occt_mutex;
  const std::lock_guard<std::mutex> lock(occt_mutex);
  static std::once_flag quiet;
  std::call_once(quiet, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
  try {
    auto f = make_face(b, dom);
    if (!f) return Error{path + ": " + f.error().message};
    AtomicFile file(path, true);
    if (!file.ok())
      return Error{path + ": cannot create the file (folder missing or not writable?)"};
    const Status st = format == "step" ? write_step(*f, path, options, file.stream())
                                       : write_iges(*f, path, options, file.stream());
    if (!st) return st;
    return file.commit();
  } catch (const Standard_Failure& e) {
    return Error{path + ": OpenCASCADE failed writing the mold: " +
                 std::string(e.GetMessageString() ? e.GetMessageString() : "unknown error")};
  }
}

Status write_mold(const FaceData& face, const std::string& path, const MoldWriteOptions& options) {
  BuiltinFace b;
  b.face = face;
  b.natural_outer = false;
  for (const auto& loop : face.loops) {
    // One degree-1 B-spline through the loop's points and back to the first, parameter = the
    // index of the point.
    NurbsCurveData2 c;
    c.degree = 1;
    c.poles = loop.points;
    if (!loop.points.empty()) c.poles.push_back(loop.points.front());
    c.knots.push_back(0.0);
    for (size_t k = 0; k < c.poles.size(); ++k) c.knots.push_back(static_cast<double>(k));
    c.knots.push_back(c.knots.back());
    b.exact_loops.push_back({std::move(c)});
  }
  return write_mold(b, path, options);
}

}  // namespace plyfit::exporters
