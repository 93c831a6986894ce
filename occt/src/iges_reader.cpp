// IGES importer (5.x, through OpenCASCADE's IGESControl_Reader). Everything after the shape is
// read (face walk, listing, conversion) is shared with STEP in occt_mold.

#include "mold_file.hpp"
#include "readers.hpp"

#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESGeom_TrimmedSurface.hxx>
#include <IGESSolid_Face.hxx>

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

}  // namespace

Result<occt::ReadOutput> read_iges(const std::string& path, occt::Deadline& deadline) {
  IGESControl_Reader reader;
  if (auto st = occt::read_file(reader, path, "IGES"); !st) return st.error();
  occt::ReadOutput out;
  const Handle(IGESData_IGESModel) model = reader.IGESModel();
  if (model.IsNull()) return Error{"not a readable IGES file (no model)"};
  const IGESData_GlobalSection& g = model->GlobalSection();
  out.schema = "IGES " + version_name(g.IGESVersion());
  const std::string system = occt::text(g.SystemId()), product = occt::text(g.SendName()),
                    pre = occt::text(g.InterfaceVersion());
  if (!system.empty()) out.schema += ", system '" + system + "'";
  if (!pre.empty()) out.schema += ", preprocessor '" + pre + "'";
  if (!product.empty()) out.schema += ", product '" + product + "'";
  out.unit = unit_name(g.UnitFlag(), occt::text(g.UnitName()));

  occt::transfer_roots(reader, deadline, iges_name, out);
  return out;
}

}  // namespace plyfit::importers
