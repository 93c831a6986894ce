// The mold writer (mold_writer.hpp), in the OpenCASCADE module (importers/occt_module.hpp):
// kernel NURBS face -> Geom_BSplineSurface -> TopoDS_Face -> STEP (STEPControl_Writer) or IGES
// (IGESControl_Writer), printed through the writers' own model printers so that the real format
// and the header time stamp can be fixed. mold_writer.cpp forwards the public functions here
// through the module's entry point (mold_writer_api.hpp).

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/kernel/nurbs.hpp>
#include <plyfit/kernel/polygon2d.hpp>
#include <plyfit/occt/module.hpp>

#include <plyfit/occt/mold_writer_api.hpp>
#include "nurbs_conversion.hpp"
#include "occt_failure.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESBasic_Name.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <IGESGeom_TrimmedSurface.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <IGESSolid_Face.hxx>
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
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <TransferBRep.hxx>
#include <TransferBRep_ShapeMapper.hxx>
#include <Transfer_FinderProcess.hxx>
#include <XSControl_TransferWriter.hxx>
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

// True when the surface image of a degree-1 (u, v) curve is a point (within
// kEdgeCurveTolerance): a collapsed edge at a pole. Curved trims never collapse.
bool collapses(const NurbsCurveData2& c, const Handle(Geom_BSplineSurface) & surface) {
  if (c.degree != 1) return false;
  double length = 0.0;
  for (size_t k = 0; k + 1 < c.poles.size(); ++k) {
    const gp_Pnt a = surface->Value(c.poles[k].x(), c.poles[k].y());
    length += a.Distance(surface->Value(c.poles[k + 1].x(), c.poles[k + 1].y()));
  }
  return length <= kEdgeCurveTolerance;
}

// One loop of exact (u, v) curves as a wire of edges on `surface`, counter-clockwise when
// `ccw` (an outer boundary: the face on its left), clockwise otherwise (a hole).
Result<TopoDS_Wire> make_wire(const std::vector<NurbsCurveData2>& curves,
                              const std::vector<Vec2>& polyline,
                              const Handle(Geom_BSplineSurface) & surface, bool ccw) {
  BRepBuilderAPI_MakeWire mw;
  for (const auto& c : curves) {
    const Handle(Geom2d_BSplineCurve) c2 = occt::to_occt(c);
    const double t0 = c2->FirstParameter(), t1 = c2->LastParameter();
    if (collapses(c, surface)) {
      // A collapsed edge (a pole): a curve on the surface, no 3D curve, one vertex.
      BRep_Builder bb;
      TopoDS_Edge e;
      bb.MakeEdge(e);
      bb.UpdateEdge(e, c2, surface, TopLoc_Location(), kEdgeCurveTolerance);
      bb.Range(e, t0, t1);
      bb.Degenerated(e, Standard_True);
      const gp_Pnt2d q = c2->Value(t0);
      TopoDS_Vertex v;
      bb.MakeVertex(v, surface->Value(q.X(), q.Y()), kEdgeCurveTolerance);
      bb.Add(e, v.Oriented(TopAbs_FORWARD));
      bb.Add(e, v.Oriented(TopAbs_REVERSED));
      mw.Add(e);
    } else {
      BRepBuilderAPI_MakeEdge me(c2, surface, t0, t1);
      if (!me.IsDone()) return Error{ErrorCode::kWriterEdgeNotBuilt};
      mw.Add(me.Edge());
    }
    if (!mw.IsDone()) return Error{ErrorCode::kWriterLoopNotJoined};
  }
  TopoDS_Wire w = mw.Wire();
  if ((signed_area(polyline) > 0.0) != ccw) w.Reverse();
  return w;
}

// The face of `b` on its surface as an OpenCASCADE face with its trims (see write_mold).
Result<TopoDS_Face> make_face(const BuiltinFace& b, const ParamDomain& dom) {
  const Handle(Geom_BSplineSurface) bs = to_occt(b.face.surface);
  TopoDS_Face f;
  size_t first_hole = 0;
  if (b.exact_loops.empty() || b.natural_outer) {
    BRepBuilderAPI_MakeFace make(bs, dom.u0, dom.u1, dom.v0, dom.v1, Precision::Confusion());
    if (!make.IsDone()) return Error{ErrorCode::kWriterFaceNotBuilt};
    f = make.Face();
    first_hole = 1;
  } else {
    auto outer = make_wire(b.exact_loops[0], b.face.loops[0].points, bs, true);
    if (!outer) return outer.error();
    BRepBuilderAPI_MakeFace make(bs, *outer, Standard_True);
    if (!make.IsDone()) return Error{ErrorCode::kWriterFaceNotInsideTrim};
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
    if (!make.IsDone()) return Error{ErrorCode::kWriterHolesNotAdded};
    f = make.Face();
  }
  if (!b.exact_loops.empty()) {
    // 3D curves for the trim edges (those OpenCASCADE made for a natural boundary, and
    // collapsed edges, need none).
    for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      double t0 = 0, t1 = 0;
      if (BRep_Tool::Degenerated(e) || !BRep_Tool::Curve(e, t0, t1).IsNull()) continue;
      if (!BRepLib::BuildCurve3d(e, kEdgeCurveTolerance))
        return Error{ErrorCode::kWriterTrimCurve3d};
    }
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

// A face of the written shape and the name it gets in the file (empty: none).
struct NamedFace {
  TopoDS_Face face;
  std::string name;
};

// The entity the writer's transfer made of `face`, or null.
Handle(Standard_Transient)
    entity_of(const Handle(Transfer_FinderProcess) & fp, const TopoDS_Face& face) {
  if (fp.IsNull()) return nullptr;
  return fp->FindTransient(TransferBRep::ShapeMapper(fp, face));
}

Status write_step(const TopoDS_Shape& shape, const std::vector<NamedFace>& faces,
                  const std::string& path, const MoldWriteOptions& o, std::ostream& out) {
  STEPControl_Controller::Init();
  Interface_Static::SetCVal("write.step.unit", "MM");
  Interface_Static::SetCVal("write.step.product.name", o.name.empty() ? "mold" : o.name.c_str());
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    return Error{ErrorCode::kWriterNotTransferred, path, {std::string("STEP")}};
  const Handle(StepData_StepModel) model = writer.Model();
  // The translator numbers its products per process ("mold 1", "mold 2", ...): name it.
  const std::string product = o.name.empty() ? "mold" : o.name;
  for (int i = 1; i <= model->NbEntities(); ++i) {
    if (const auto p = Handle(StepBasic_Product)::DownCast(model->Value(i)); !p.IsNull()) {
      p->SetId(hstr(product));
      p->SetName(hstr(product));
    }
  }
  // Each face's ADVANCED_FACE and its surface carry its name. A face written alone is the
  // transfer's root, bound to its representation: it is the model's only face.
  const Handle(Transfer_FinderProcess) fp = writer.WS()->TransferWriter()->FinderProcess();
  for (const auto& [face, name] : faces) {
    if (name.empty()) continue;
    Handle(StepShape_AdvancedFace) f =
        Handle(StepShape_AdvancedFace)::DownCast(entity_of(fp, face));
    for (int i = 1; f.IsNull() && faces.size() == 1 && i <= model->NbEntities(); ++i)
      f = Handle(StepShape_AdvancedFace)::DownCast(model->Value(i));
    if (f.IsNull()) return Error{ErrorCode::kWriterNoFace, path, {std::string("STEP"), name}};
    f->SetName(hstr(name));
    if (const auto s = Handle(StepGeom_BSplineSurface)::DownCast(f->FaceGeometry()); !s.IsNull())
      s->SetName(hstr(name));
  }
  APIHeaderSection_MakeHeader header(model);
  header.SetName(hstr(std::filesystem::path(path).filename().string()));
  header.SetTimeStamp(hstr(o.timestamp));
  header.SetAuthorValue(1, hstr("plyfit"));
  header.SetOrganizationValue(1, hstr("plyfit"));
  header.SetOriginatingSystem(hstr("plyfit"));
  header.SetAuthorisation(hstr(""));
  const auto protocol = Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol());
  if (protocol.IsNull()) return Error{ErrorCode::kWriterNoProtocol, path};
  StepData_StepWriter sw(model);
  sw.FloatWriter().SetFormat(kRealFormat);
  sw.SendModel(protocol);
  if (!sw.Print(out)) return Error{ErrorCode::kWriterFailed, path, {std::string("STEP")}};
  return ok_status();
}

Status write_iges(const TopoDS_Shape& shape, const std::vector<NamedFace>& faces,
                  const std::string& path, const MoldWriteOptions& o, std::ostream& out) {
  IGESControl_Controller::Init();
  // One face: a 144 trimmed surface (faces mode); several: a 514 shell of 510 faces (BRep
  // mode), which keeps the edges the faces share.
  IGESControl_Writer writer("MM", faces.size() > 1 ? 1 : 0);
  if (!writer.AddShape(shape))
    return Error{ErrorCode::kWriterNotTransferred, path, {std::string("IGES")}};
  const Handle(IGESData_IGESModel) model = writer.Model();
  // Each face's surface (a 128, bare or inside the face's 144) carries its name (406 form 15).
  for (const auto& [face, name] : faces) {
    if (name.empty()) continue;
    const Handle(Standard_Transient) e = entity_of(writer.TransferProcess(), face);
    Handle(IGESGeom_BSplineSurface) s = Handle(IGESGeom_BSplineSurface)::DownCast(e);
    // A face written alone (faces mode): the model's only surface.
    for (int i = 1; e.IsNull() && faces.size() == 1 && i <= model->NbEntities(); ++i)
      if (s.IsNull()) s = Handle(IGESGeom_BSplineSurface)::DownCast(model->Value(i));
    if (const auto t = Handle(IGESGeom_TrimmedSurface)::DownCast(e); !t.IsNull())
      s = Handle(IGESGeom_BSplineSurface)::DownCast(t->Surface());
    if (const auto f = Handle(IGESSolid_Face)::DownCast(e); !f.IsNull())
      s = Handle(IGESGeom_BSplineSurface)::DownCast(f->Surface());
    if (s.IsNull()) return Error{ErrorCode::kWriterNoFace, path, {std::string("IGES"), name}};
    Handle(IGESBasic_Name) prop = new IGESBasic_Name;
    prop->Init(1, hstr(name));
    s->AddProperty(prop);
    writer.AddEntity(prop);
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
  if (!iw.Print(out)) return Error{ErrorCode::kWriterFailed, path, {std::string("IGES")}};
  return ok_status();
}

// The format to write: options.format, else from the file extension.
Result<std::string> format_of(const std::string& path, const MoldWriteOptions& options) {
  std::string format = options.format;
  if (format.empty()) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == "step" || ext == "stp") format = "step";
    if (ext == "iges" || ext == "igs") format = "iges";
    if (format.empty()) return Error{ErrorCode::kUnknownMoldFormat, path, {ext}};
  }
  if (format != "step" && format != "iges")
    return Error{ErrorCode::kUnknownMoldFormat, path, {format}};
  return format;
}

// Validates a face with the kernel's own rules (OpenCASCADE throws on bad data) and clears
// magnitudes too small to write; returns the surface's domain. Errors blame nothing: the
// caller names the file and the face.
Result<ParamDomain> checked(BuiltinFace& b) {
  NurbsSurfaceData& data = b.face.surface;
  bool all_fit = fits(data.poles, data.weights, data.knots_u);
  for (double& x : data.knots_v) all_fit = fits(x) && all_fit;
  for (auto& loop : b.exact_loops)
    for (auto& c : loop) all_fit = fits(c.poles, c.weights, c.knots) && all_fit;
  if (!all_fit) return Error{ErrorCode::kWriterValueTooLarge, {}, {kLargestWritten}};
  auto surface = NurbsSurface::create(data);
  if (!surface) return Error{ErrorCode::kWriterSurfaceInvalid}.because(surface.error());
  const ParamDomain dom = surface->domain();
  if (b.exact_loops.size() != b.face.loops.size())
    return Error{ErrorCode::kWriterLoopCount,
                 {},
                 {static_cast<std::int64_t>(b.exact_loops.size()),
                  static_cast<std::int64_t>(b.face.loops.size())}};
  // The domain, widened by the parameter tolerance: trims on its border are kept.
  const double mu = Tolerances{}.param_rel * dom.width_u();
  const double mv = Tolerances{}.param_rel * dom.width_v();
  for (size_t k = 0; k < b.exact_loops.size(); ++k) {
    if (b.exact_loops[k].empty() || b.face.loops[k].points.size() < 3)
      return Error{ErrorCode::kWriterLoopTooFewPoints, {}, {static_cast<std::int64_t>(k)}};
    for (const auto& c : b.exact_loops[k])
      if (auto cv = NurbsCurve2::create(c); !cv)
        return Error{ErrorCode::kWriterTrimCurveInvalid, {}, {static_cast<std::int64_t>(k)}}
            .because(cv.error());
    for (const Vec2& p : b.face.loops[k].points)
      if (!(p.x() >= dom.u0 - mu && p.x() <= dom.u1 + mu && p.y() >= dom.v0 - mv &&
            p.y() <= dom.v1 + mv))
        return Error{ErrorCode::kWriterLoopOffDomain, {}, {static_cast<std::int64_t>(k)}};
  }
  return dom;
}

// True when every segment of the face's only loop runs along one side of its domain's border
// (within the parameter tolerance): the face is bounded by its surface's natural boundary.
bool on_border(const FaceData& f) {
  if (f.loops.size() != 1) return false;
  auto surface = NurbsSurface::create(f.surface);
  if (!surface) return false;
  const ParamDomain& d = surface->domain();
  const double mu = Tolerances{}.param_rel * d.width_u();
  const double mv = Tolerances{}.param_rel * d.width_v();
  const auto& pts = f.loops[0].points;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Vec2& p = pts[k];
    const Vec2& q = pts[(k + 1) % pts.size()];
    const bool side = (std::abs(p.x() - d.u0) <= mu && std::abs(q.x() - d.u0) <= mu) ||
                      (std::abs(p.x() - d.u1) <= mu && std::abs(q.x() - d.u1) <= mu) ||
                      (std::abs(p.y() - d.v0) <= mv && std::abs(q.y() - d.v0) <= mv) ||
                      (std::abs(p.y() - d.v1) <= mv && std::abs(q.y() - d.v1) <= mv);
    if (!side) return false;
  }
  return true;
}

// A face with polyline loops as one with exact degree-1 loops: each loop cut into one curve
// per run of segments on the same shared edge (one curve for a loop without tags), the curve's
// parameter the index of the point. A single loop on the domain's border is the natural one.
BuiltinFace with_polyline_trims(const FaceData& face) {
  BuiltinFace b;
  b.face = face;
  b.natural_outer = on_border(face);
  for (const auto& loop : face.loops) {
    const size_t n = loop.points.size();
    auto tag = [&](size_t k) { return loop.edges.empty() ? TrimLoop::kFreeEdge : loop.edges[k]; };
    // Start where the tag changes, so that no run wraps past the end of the loop.
    size_t start = 0;
    for (size_t k = 0; k < n; ++k)
      if (tag(k) != tag((k + n - 1) % n)) {
        start = k;
        break;
      }
    std::vector<NurbsCurveData2> curves;
    for (size_t done = 0; done < n;) {
      NurbsCurveData2 c;
      c.degree = 1;
      const std::int32_t t = tag((start + done) % n);
      c.poles.push_back(loop.points[(start + done) % n]);
      do {
        ++done;
        c.poles.push_back(loop.points[(start + done) % n]);
      } while (done < n && tag((start + done) % n) == t);
      c.knots.push_back(0.0);
      for (size_t k = 0; k < c.poles.size(); ++k) c.knots.push_back(static_cast<double>(k));
      c.knots.push_back(c.knots.back());
      curves.push_back(std::move(c));
    }
    b.exact_loops.push_back(std::move(curves));
  }
  return b;
}

// OpenCASCADE's data exchange keeps global state (static parameters, messenger): one writer
// at a time.
std::mutex& occt_mutex() {
  static std::mutex m;
  return m;
}

Status write_builtin(const BuiltinFace& face, const std::string& path,
                     const MoldWriteOptions& options) {
  auto format = format_of(path, options);
  if (!format) return format.error();
  BuiltinFace b = face;
  auto dom = checked(b);
  if (!dom) return Error(dom.error()).in(path);
  const std::lock_guard<std::mutex> lock(occt_mutex());
  static std::once_flag quiet;
  std::call_once(quiet, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
  try {
    auto f = make_face(b, *dom);
    if (!f) return Error(f.error()).in(path);
    AtomicFile file(path, true);
    if (!file.ok()) return Error{ErrorCode::kFileNotCreated, path};
    const std::vector<NamedFace> names = {{*f, options.name}};
    const Status st = *format == "step" ? write_step(*f, names, path, options, file.stream())
                                        : write_iges(*f, names, path, options, file.stream());
    if (!st) return st;
    return file.commit();
  } catch (const Standard_Failure& e) {
    return Error{ErrorCode::kWriterOcctFailed, path, occt::failure_values(e)};
  }
}

// `e`, naming the file `path` and its face `i` (of a shell).
Error on_face(Error e, const std::string& path, size_t i) {
  e.face = static_cast<int>(i);
  return std::move(e).in(path);
}

Status write_face(const FaceData& face, const std::string& path, const MoldWriteOptions& options) {
  return write_builtin(with_polyline_trims(face), path, options);
}

Status write_faces(const ShellData& shell, const std::string& path,
                   const MoldWriteOptions& options) {
  auto format = format_of(path, options);
  if (!format) return format.error();
  if (shell.faces.empty()) return Error{ErrorCode::kShellNoFaces, path};
  std::vector<BuiltinFace> faces;
  std::vector<ParamDomain> domains;
  double largest = 0.0;
  for (size_t i = 0; i < shell.faces.size(); ++i) {
    const FaceData& fd = shell.faces[i];
    for (const auto& loop : fd.loops)
      if (!loop.edges.empty() && loop.edges.size() != loop.points.size())
        return on_face(Error{ErrorCode::kWriterEdgeTags,
                             {},
                             {static_cast<std::int64_t>(loop.edges.size()),
                              static_cast<std::int64_t>(loop.points.size())}},
                       path, i);
    BuiltinFace b = with_polyline_trims(fd);
    if (b.face.name.empty()) b.face.name = "face " + std::to_string(i);
    auto dom = checked(b);
    if (!dom) return on_face(dom.error(), path, i);
    auto f = MoldSurface::from_face(b.face);
    if (!f) return on_face(f.error(), path, i);
    largest = std::max(largest, f->size());
    faces.push_back(std::move(b));
    domains.push_back(*dom);
  }
  // Two polylines of one shared edge lie within the trim tolerance of the same curve.
  const double sewing = std::max(shell.tolerance, 2 * Tolerances{}.trim_chord_rel * largest);

  static std::once_flag quiet;
  std::call_once(quiet, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
  const std::lock_guard<std::mutex> lock(occt_mutex());
  try {
    std::vector<NamedFace> named;
    for (size_t i = 0; i < faces.size(); ++i) {
      auto f = make_face(faces[i], domains[i]);
      if (!f) return on_face(f.error(), path, i);
      named.push_back({*f, faces[i].face.name});
    }
    TopoDS_Shape shape = named.front().face;
    if (named.size() > 1) {
      BRepBuilderAPI_Sewing sew(sewing);
      for (const auto& n : named) sew.Add(n.face);
      sew.Perform();
      shape = sew.SewedShape();
      if (shape.IsNull()) return Error{ErrorCode::kSewingNoShape, path};
      for (auto& n : named)
        if (sew.IsModified(n.face)) n.face = TopoDS::Face(sew.Modified(n.face));
    }
    AtomicFile file(path, true);
    if (!file.ok()) return Error{ErrorCode::kFileNotCreated, path};
    const Status st = *format == "step" ? write_step(shape, named, path, options, file.stream())
                                        : write_iges(shape, named, path, options, file.stream());
    if (!st) return st;
    return file.commit();
  } catch (const Standard_Failure& e) {
    return Error{ErrorCode::kWriterOcctFailed, path, occt::failure_values(e)};
  }
}

const OcctMoldWriterApi kApi{plyfit::occt::kOcctModuleAbi, &write_builtin, &write_face,
                             &write_faces};

}  // namespace

}  // namespace plyfit::exporters

/// The mold writer's entry point (mold_writer_api.hpp).
extern "C" __attribute__((visibility("default"))) const plyfit::exporters::OcctMoldWriterApi*
plyfit_occt_mold_writer() {
  return &plyfit::exporters::kApi;
}
