// net.step: the draped threads as 3D B-spline curves in an AP214 (AP214IS) STEP file,
// millimetres. Each maximal run of consecutive mapped nodes of a thread (DrapeResult::
// threads()) is one curve (one edge), and the base path is one curve through its mapped nodes
// in path order. The curves are grouped into three compounds, each a product named `weft`,
// `warp` and `base_path` (XDE document: the names are TDataStd_Name attributes that
// STEPCAFControl_Writer writes as PRODUCT names). A group without curves is left out.
//
// Curves are the kernel's: polyline_curve() (degree 1, through the nodes) by default, or
// interpolate_cubic() for ExportOptions::curve_degree 3; a run the cubic interpolation
// rejects (two coincident nodes) is written as a polyline.
//
// OpenCASCADE writes into the AtomicFile's temporary file, which is then renamed into place.
// Its messages are not printed (the default messenger's printers are removed). The header's
// FILE_NAME time stamp is fixed (2000-01-01T00:00:00), its name is "net.step" and its author
// and organisation are "plyfit", so equal inputs give equal bytes.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/nurbs_curve.hpp>

#include "occt_geometry.hpp"
#include "plugins.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BSplineCurve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_StepModelType.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include <filesystem>
#include <mutex>

namespace plyfit::exporters {

namespace {
using occt::to_occt;

constexpr const char* kFixedTimeStamp = "2000-01-01T00:00:00";

// OpenCASCADE's messages are never printed raw.
void silence_occt() {
  static std::once_flag once;
  std::call_once(once, [] { Message::DefaultMessenger()->ChangePrinters().Clear(); });
}

struct Group {
  const char* name;
  std::vector<std::vector<std::uint32_t>> runs;
};

Status write_step(const ExportContext& ctx, const std::string& path) {
  const DrapeResult& r = ctx.result;
  std::vector<Group> groups = {
      {"weft", r.threads(true)}, {"warp", r.threads(false)}, {"base_path", {}}};
  if (r.base_path.size() >= 2) groups[2].runs.push_back(r.base_path);

  // OpenCASCADE's data exchange keeps global state (Interface_Static): one writer at a time.
  static std::mutex occt_mutex;
  const std::lock_guard<std::mutex> lock(occt_mutex);
  silence_occt();
  try {
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    struct DocCloser {
      Handle(TDocStd_Document) doc;
      ~DocCloser() {
        if (!doc.IsNull() && doc->IsOpened()) XCAFApp_Application::GetApplication()->Close(doc);
      }
    } closer{doc};
    const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    BRep_Builder builder;
    for (const Group& g : groups) {
      if (g.runs.empty()) continue;
      TopoDS_Compound compound;
      builder.MakeCompound(compound);
      for (const auto& run : g.runs) {
        std::vector<Vec3> pts;
        for (const std::uint32_t k : run) pts.push_back(r.nodes[k].point);
        auto curve = ctx.options.curve_degree == 3 ? interpolate_cubic(pts) : polyline_curve(pts);
        if (!curve) curve = polyline_curve(pts);
        if (!curve)
          return Error{path + ": cannot build a " + g.name + " curve: " + curve.error().message};
        BRepBuilderAPI_MakeEdge edge(to_occt(curve->data()));
        if (!edge.IsDone()) return Error{path + ": cannot build a " + g.name + " edge"};
        builder.Add(compound, edge.Edge());
      }
      const TDF_Label label = shapes->AddShape(compound, Standard_False);
      TDataStd_Name::Set(label, TCollection_ExtendedString(g.name));
    }

    Interface_Static::SetCVal("write.step.schema", "AP214IS");
    Interface_Static::SetCVal("write.step.unit", "MM");
    STEPCAFControl_Writer writer;
    writer.SetNameMode(Standard_True);
    writer.SetColorMode(Standard_False);
    writer.SetLayerMode(Standard_False);
    writer.SetPropsMode(Standard_False);
    if (!writer.Transfer(doc, STEPControl_AsIs))
      return Error{path + ": OpenCASCADE could not convert the net to STEP"};
    APIHeaderSection_MakeHeader header(writer.ChangeWriter().Model());
    header.SetName(new TCollection_HAsciiString("net.step"));
    header.SetTimeStamp(new TCollection_HAsciiString(kFixedTimeStamp));
    header.SetAuthorValue(1, new TCollection_HAsciiString("plyfit"));
    header.SetOrganizationValue(1, new TCollection_HAsciiString("plyfit"));
    header.SetOriginatingSystem(new TCollection_HAsciiString("plyfit"));
    header.SetAuthorisation(new TCollection_HAsciiString(""));

    AtomicFile file(path);
    if (!file.ok())
      return Error{path + ": cannot create the file (folder missing or not writable?)"};
    const IFSelect_ReturnStatus st = writer.Write(file.temp_path().c_str());
    if (st != IFSelect_RetDone) {
      file.discard();
      return Error{path + ": OpenCASCADE's STEP writer failed"};
    }
    return file.commit();
  } catch (const Standard_Failure& e) {
    return Error{path + ": OpenCASCADE failed: " + std::string(e.GetMessageString())};
  }
}

}  // namespace

Exporter make_step_exporter() {
  return {"step",
          {"net.step"},
          "net.step: draped weft, warp and base path as 3D curves (AP214)",
          [](const ExportContext& ctx, const std::string& outdir) {
            return write_step(ctx, (std::filesystem::path(outdir) / "net.step").string());
          }};
}

}  // namespace plyfit::exporters
