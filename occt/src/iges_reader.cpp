// IGES importer (5.x, through OpenCASCADE's IGESControl_Reader). Everything after the shape is
// read (face walk, listing, conversion) is shared with STEP in occt_mold.

#include "mold_file.hpp"
#include "readers.hpp"

#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESGeom_CompositeCurve.hxx>
#include <IGESGeom_CurveOnSurface.hxx>
#include <IGESGeom_TrimmedSurface.hxx>
#include <IGESSolid_Face.hxx>
#include <IGESToBRep_BasicCurve.hxx>
#include <IGESToBRep_CurveAndSurface.hxx>
#include <Interface_Check.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <Geom_Curve.hxx>

#include <algorithm>
#include <cstdio>

namespace plyfit::importers {

namespace {

// An entity's name (property 406 form 15) or, failing that, its label and subscript.
std::string label_of(const Handle(IGESData_IGESEntity) & e) {
  if (e.IsNull()) return {};
  if (e->HasName()) {
    const std::string n = occt::text(e->NameValue());
    if (!n.empty()) return n;
  }
  if (e->HasShortLabel()) {
    std::string n = occt::text(e->ShortLabel());
    if (!n.empty() && e->HasSubScriptNumber()) {
      n += '(';
      n += std::to_string(e->SubScriptNumber());
      n += ')';
    }
    return n;
  }
  return {};
}

// The name of the entity that produced a face (a 510 face, a 144 trimmed surface or a bare
// surface), else of the surface it trims.
std::string iges_name(const Handle(Standard_Transient) & entity) {
  const auto e = Handle(IGESData_IGESEntity)::DownCast(entity);
  std::string name = label_of(e);
  if (name.empty()) {
    if (const auto t = Handle(IGESGeom_TrimmedSurface)::DownCast(e); !t.IsNull())
      name = label_of(t->Surface());
    else if (const auto f = Handle(IGESSolid_Face)::DownCast(e); !f.IsNull())
      name = label_of(f->Surface());
  }
  return name;
}

std::string version_name(int flag) {
  static const char* const kNames[] = {"",
                                       "1.0",
                                       "ANSI Y14.26M-1981",
                                       "2.0",
                                       "3.0",
                                       "ASME/ANSI Y14.26M-1987",
                                       "4.0",
                                       "ASME Y14.26M-1989",
                                       "5.0",
                                       "5.1",
                                       "5.2",
                                       "5.3"};
  if (flag >= 1 && flag <= 11) return kNames[flag];
  return "version flag " + std::to_string(flag);
}

std::string unit_name(int flag, const std::string& given) {
  static const char* const kNames[] = {"",     "inch",   "millimetre", "",
                                       "foot", "mile",   "metre",      "kilometre",
                                       "mil",  "micron", "centimetre", "microinch"};
  std::string n = flag >= 1 && flag <= 11 ? kNames[flag] : "";
  if (n.empty()) return given.empty() ? "unit flag " + std::to_string(flag) : given;
  return given.empty() ? n : n + " (" + given + ")";
}

// The widest gap (mm) between consecutive model-space curves of a trim loop made of a
// composite curve (102) of curves the reader can convert; 0 when none is found.
double loop_gap(const Handle(IGESGeom_CurveOnSurface) & loop,
                const Handle(IGESData_IGESModel) & model) {
  const auto composite = Handle(IGESGeom_CompositeCurve)::DownCast(loop->Curve3D());
  if (composite.IsNull() || composite->NbCurves() < 2) return 0.0;
  IGESToBRep_CurveAndSurface cas;
  cas.SetModel(model);
  IGESToBRep_BasicCurve convert(cas);
  std::vector<std::pair<gp_Pnt, gp_Pnt>> ends;
  for (int k = 1; k <= composite->NbCurves(); ++k) {
    const Handle(Geom_Curve) c = convert.TransferBasicCurve(composite->Curve(k));
    if (c.IsNull()) return 0.0;
    ends.emplace_back(c->Value(c->FirstParameter()), c->Value(c->LastParameter()));
  }
  double gap = 0.0;
  for (std::size_t k = 0; k < ends.size(); ++k)
    gap = std::max(gap, ends[k].second.Distance(ends[(k + 1) % ends.size()].first));
  return gap;
}

// A trimmed surface (144) some of whose trim loops the reader skipped: the loop's check failed,
// its curves on the surface could not be made a loop (e.g. model-space curves that do not
// close). The face then comes out bounded by its whole surface.
struct DroppedTrims {
  int face = -1;        // index of the face it made in the listing (-1: none)
  int entity = 0;       // the 144's directory entry (DE) number
  int dropped = 0;      // loops skipped
  int loops = 0;        // loops it has (outer and inner)
  double gap_mm = 0.0;  // widest gap between the skipped loops' model-space curves (0: unknown)
};

std::vector<DroppedTrims> dropped_trims(const IGESControl_Reader& reader,
                                        const TopoDS_Shape& shape) {
  std::vector<DroppedTrims> out;
  const Handle(IGESData_IGESModel) model = reader.IGESModel();
  const Handle(Transfer_TransientProcess) process =
      reader.WS()->TransferReader()->TransientProcess();
  if (model.IsNull() || process.IsNull()) return out;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  for (int i = 1; i <= model->NbEntities(); ++i) {
    const auto t = Handle(IGESGeom_TrimmedSurface)::DownCast(model->Value(i));
    if (t.IsNull()) continue;
    std::vector<Handle(IGESGeom_CurveOnSurface)> loops;
    if (t->HasOuterContour()) loops.push_back(t->OuterContour());
    for (int k = 1; k <= t->NbInnerContours(); ++k) loops.push_back(t->InnerContour(k));
    DroppedTrims d;
    d.entity = 2 * i - 1;
    d.loops = static_cast<int>(loops.size());
    for (const auto& loop : loops) {
      if (loop.IsNull() || !process->Check(loop)->HasFailed()) continue;
      ++d.dropped;
      d.gap_mm = std::max(d.gap_mm, loop_gap(loop, model));
    }
    if (d.dropped == 0) continue;
    for (TopExp_Explorer e(TransferBRep::ShapeResult(process, t), TopAbs_FACE);
         e.More() && d.face < 0; e.Next())
      d.face = faces.FindIndex(e.Current()) - 1;
    out.push_back(d);
  }
  return out;
}

// The listing's warning for d: the face is listed and draped untrimmed, which the user must know.
Warning dropped_trims_warning(const DroppedTrims& d) {
  return {WarningCode::kTrimLoopsDropped,
          {std::int64_t{d.face}, std::int64_t{d.entity}, std::int64_t{d.dropped},
           std::int64_t{d.loops}, d.gap_mm}};
}

}  // namespace

Result<occt::ReadOutput> read_iges(const std::string& path, occt::Deadline& deadline) {
  IGESControl_Reader reader;
  if (auto st = occt::read_file(reader, path, "IGES"); !st) return st.error();
  occt::ReadOutput out;
  const Handle(IGESData_IGESModel) model = reader.IGESModel();
  if (model.IsNull()) return Error{ErrorCode::kIgesNoModel};
  const IGESData_GlobalSection& g = model->GlobalSection();
  out.schema = "IGES " + version_name(g.IGESVersion());
  const std::string system = occt::text(g.SystemId()), product = occt::text(g.SendName()),
                    pre = occt::text(g.InterfaceVersion());
  if (!system.empty()) out.schema += ", system '" + system + "'";
  if (!pre.empty()) out.schema += ", preprocessor '" + pre + "'";
  if (!product.empty()) out.schema += ", product '" + product + "'";
  out.unit = unit_name(g.UnitFlag(), occt::text(g.UnitName()));

  occt::transfer_roots(reader, deadline, iges_name, out);
  // (A transfer stopped by the deadline is an error of the caller's: nothing to look at.)
  if (!deadline.expired() && !out.shape.IsNull())
    for (const DroppedTrims& d : dropped_trims(reader, out.shape))
      out.warnings.push_back(dropped_trims_warning(d));
  return out;
}

}  // namespace plyfit::importers
