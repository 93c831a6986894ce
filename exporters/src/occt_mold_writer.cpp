// The OpenCASCADE part of the mold writer (in the OpenCASCADE module, importers/occt_module.hpp):
// kernel NURBS face -> Geom_BSplineSurface -> TopoDS_Face -> STEP (STEPControl_Writer) or IGES
// (IGESControl_Writer), printed through the writers' own model printers so that the real format
// and the header time stamp can be fixed. write_mold() (mold_writer.cpp) validates first.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/importers/occt_module.hpp>
#include <plyfit/kernel/nurbs_surface.hpp>

#include "mold_writer_api.hpp"
#include "occt_geometry.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
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
#include <TopoDS_Face.hxx>
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

Status write(const NurbsSurface& surface, bool reversed, const std::string& format,
             const std::string& path, const MoldWriteOptions& options) {
  // OpenCASCADE's data exchange keeps global state (static parameters, messenger): one
  // writer at a time.
  static std::mutex occt_mutex;
  const std::lock_guard<std::mutex> lock(occt_mutex);
  static std::once_flag quiet;
  std::call_once(quiet, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
  try {
    const Handle(Geom_BSplineSurface) bs = to_occt(surface.data());
    const ParamDomain& dom = surface.domain();
    BRepBuilderAPI_MakeFace make(bs, dom.u0, dom.u1, dom.v0, dom.v1, Precision::Confusion());
    if (!make.IsDone()) return Error{path + ": could not build a face on the surface"};
    TopoDS_Face f = make.Face();
    // A forward face's normal is Su x Sv, as plyfit's; a reversed face is flipped.
    if (reversed) f.Reverse();
    AtomicFile file(path, true);
    if (!file.ok())
      return Error{path + ": cannot create the file (folder missing or not writable?)"};
    const Status st = format == "step" ? write_step(f, path, options, file.stream())
                                       : write_iges(f, path, options, file.stream());
    if (!st) return st;
    return file.commit();
  } catch (const Standard_Failure& e) {
    return Error{path + ": OpenCASCADE failed writing the mold: " +
                 std::string(e.GetMessageString() ? e.GetMessageString() : "unknown error")};
  }
}

const OcctMoldWriterApi kApi{importers::kOcctModuleAbi, &write};

}  // namespace

}  // namespace plyfit::exporters

/// The mold writer's entry point (mold_writer_api.hpp).
extern "C" __attribute__((visibility("default"))) const plyfit::exporters::OcctMoldWriterApi*
plyfit_occt_mold_writer() {
  return &plyfit::exporters::kApi;
}
