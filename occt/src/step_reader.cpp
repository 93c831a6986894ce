// STEP importer (AP203, AP214, AP242 through OpenCASCADE's STEPControl_Reader). Everything
// after the shape is read (face walk, listing, conversion) is shared with IGES in occt_mold.

#include "mold_file.hpp"
#include "readers.hpp"

#include <algorithm>
#include <cctype>

#include <HeaderSection_FileSchema.hxx>
#include <Interface_HArray1OfHAsciiString.hxx>
#include <STEPControl_Reader.hxx>
#include <StepData_StepModel.hxx>
#include <StepGeom_Surface.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepShape_FaceSurface.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>

namespace plyfit::importers {

namespace {

// The name of the entity that produced a face: the face's own name, else its surface's.
std::string step_name(const Handle(Standard_Transient) & entity) {
  const auto item = Handle(StepRepr_RepresentationItem)::DownCast(entity);
  if (item.IsNull()) return {};
  std::string name = occt::text(item->Name());
  if (name.empty()) {
    if (const auto face = Handle(StepShape_FaceSurface)::DownCast(entity); !face.IsNull())
      if (!face->FaceGeometry().IsNull()) name = occt::text(face->FaceGeometry()->Name());
  }
  if (name == "NONE" || name == "$") name.clear();
  return name;
}

}  // namespace

Result<occt::ReadOutput> read_step(const std::string& path, occt::Deadline& deadline) {
  STEPControl_Reader reader;
  if (auto st = occt::read_file(reader, path, "STEP"); !st) return st.error();
  occt::ReadOutput out;
  const Handle(StepData_StepModel) model = reader.StepModel();
  if (!model.IsNull()) {
    const auto schema = Handle(HeaderSection_FileSchema)::DownCast(
        model->HeaderEntity(STANDARD_TYPE(HeaderSection_FileSchema)));
    if (!schema.IsNull() && !schema->SchemaIdentifiers().IsNull())
      for (int i = 1; i <= schema->NbSchemaIdentifiers(); ++i)
        out.schema +=
            (out.schema.empty() ? "" : ", ") + occt::text(schema->SchemaIdentifiersValue(i));
  }
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  for (int i = 1; i <= lengths.Length(); ++i) {
    // SI units come named ("millimetre"), conversion-based ones as the file spells them
    // ("INCH"): lower-case both.
    std::string u = lengths(i).ToCString();
    std::transform(u.begin(), u.end(), u.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    if (out.unit.find(u) == std::string::npos) out.unit += (out.unit.empty() ? "" : ", ") + u;
  }
  if (out.unit.empty()) out.unit = "unspecified (millimetre assumed)";

  occt::transfer_roots(reader, deadline, step_name, out);
  return out;
}

}  // namespace plyfit::importers
