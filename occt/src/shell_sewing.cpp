// Shells: several faces of a mold file sewn along their shared edges (OpenCASCADE's
// BRepBuilderAPI_Sewing), each face converted as MoldFile::convert_face converts it, with trim
// loops whose segments name the shared edge they lie on (ShellData, TrimLoop::edges).

#include "mold_file.hpp"

#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Static.hxx>
#include <STEPConstruct_UnitContext.hxx>
#include <StepData_StepModel.hxx>
#include <StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx.hxx>
#include <StepRepr_GlobalUncertaintyAssignedContext.hxx>
#include <StepRepr_GlobalUnitAssignedContext.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace plyfit::importers::occt {

namespace {

// The sewing tolerance is never below OpenCASCADE's own point confusion (1e-7 mm: closer
// points are one point to every OCCT algorithm) ...
constexpr double kSewingMinTolerance = 1e-7;
// ... nor above this fraction of the shell's size (0.1 mm on a 1 m part): a file that states a
// coarse precision, or an edge that a reader's repair left with a large tolerance, must not
// merge distinct edges of small features (or make the sewing drop small faces as degenerate).
constexpr double kSewingMaxRel = 1e-4;
// Points per shared edge at which the gap between its two faces is measured, and golden-section
// steps that refine the largest (0.618^40 ~ 4e-9 of two sample intervals).
constexpr int kGapSamples = 32;
constexpr int kGapRefineSteps = 40;
// Face lists in messages name at most this many indices.
constexpr size_t kListedFaces = 12;

// "face 3", "faces 0-17", "faces 3, 4, 9-12": the faces of a message, in the given order.
std::string face_list(const std::vector<int>& faces) {
  std::string s = faces.size() == 1 ? "face " : "faces ";
  size_t k = 0;
  for (size_t shown = 0; k < faces.size() && shown < kListedFaces; ++shown) {
    size_t end = k + 1;
    while (end < faces.size() && faces[end] == faces[end - 1] + 1) ++end;
    if (shown > 0) s += ", ";
    s += std::to_string(faces[k]);
    if (end - k >= 3) {
      s += '-';
      s += std::to_string(faces[end - 1]);
      k = end;
    } else {
      ++k;
    }
  }
  if (k < faces.size()) s += ", ...";
  return s;
}

// Connected parts of the shell (faces joined by shared edges), by union-find.
struct Parts {
  std::vector<int> parent;
  explicit Parts(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[static_cast<size_t>(i)] != i)
      i = parent[static_cast<size_t>(i)] =
          parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    return i;
  }
  void join(int a, int b) { parent[static_cast<size_t>(find(a))] = find(b); }
};

// Largest distance between the two faces' images of the edge, at the same fraction of each
// pcurve's range (sewing leaves shared edges same-parameter): sampled at kGapSamples + 1
// points, then maximised by golden section between the neighbours of the largest sample.
double edge_gap(const TopoDS_Edge& e, const TopoDS_Face& a, const TopoDS_Face& b) {
  double a0 = 0, a1 = 0, b0 = 0, b1 = 0;
  const Handle(Geom2d_Curve) ca = BRep_Tool::CurveOnSurface(e, a, a0, a1);
  const Handle(Geom2d_Curve) cb = BRep_Tool::CurveOnSurface(e, b, b0, b1);
  const Handle(Geom_Surface) sa = BRep_Tool::Surface(a), sb = BRep_Tool::Surface(b);
  if (ca.IsNull() || cb.IsNull() || sa.IsNull() || sb.IsNull()) return 0.0;
  auto gap = [&](double f) {
    const gp_Pnt2d pa = ca->Value(a0 + f * (a1 - a0)), pb = cb->Value(b0 + f * (b1 - b0));
    return sa->Value(pa.X(), pa.Y()).Distance(sb->Value(pb.X(), pb.Y()));
  };
  int best = 0;
  double largest = -1.0;
  for (int k = 0; k <= kGapSamples; ++k) {
    const double g = gap(static_cast<double>(k) / kGapSamples);
    if (g > largest) largest = g, best = k;
  }
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = std::max(0, best - 1) / static_cast<double>(kGapSamples);
  double hi = std::min(kGapSamples, best + 1) / static_cast<double>(kGapSamples);
  double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
  double g1 = gap(x1), g2 = gap(x2);
  for (int i = 0; i < kGapRefineSteps; ++i) {
    if (g1 > g2) {
      hi = x2, x2 = x1, g2 = g1, x1 = hi - golden * (hi - lo), g1 = gap(x1);
    } else {
      lo = x1, x1 = x2, g1 = g2, x2 = lo + golden * (hi - lo), g2 = gap(x2);
    }
  }
  return std::max({largest, g1, g2});
}

// The orientation of each edge of `face` as the face uses it (a seam, used twice, is listed
// twice).
std::vector<std::pair<TopoDS_Shape, TopAbs_Orientation>> edge_uses(const TopoDS_Face& face) {
  std::vector<std::pair<TopoDS_Shape, TopAbs_Orientation>> uses;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
    uses.emplace_back(ex.Current(), ex.Current().Orientation());
  return uses;
}

TopAbs_Orientation use_in(const std::vector<std::pair<TopoDS_Shape, TopAbs_Orientation>>& uses,
                          const TopoDS_Shape& edge) {
  for (const auto& [e, o] : uses)
    if (e.IsSame(edge)) return o;
  return TopAbs_EXTERNAL;
}

// The faces to sew (all of the file's when none are given), described, and their common box.
struct Selection {
  std::vector<int> indices;
  std::vector<FaceInfo> infos;
  BBox3 box;
};

Result<Selection> select_faces(const ShellInput& in, const std::vector<int>& given) {
  Selection sel;
  sel.indices = given;
  if (sel.indices.empty()) {
    sel.indices.resize(static_cast<size_t>(in.faces.Extent()));
    std::iota(sel.indices.begin(), sel.indices.end(), 0);
  }
  std::set<int> seen;
  for (int i : sel.indices) {
    auto info = in.describe(i);  // an index out of range is an error naming the file here
    if (!info) return info.error();
    if (!seen.insert(i).second)
      return Error{ErrorCode::kFaceListedTwice, in.source, {std::int64_t{i}}};
    if (!info->bbox.empty) {
      sel.box.add(info->bbox.min);
      sel.box.add(info->bbox.max);
    }
    sel.infos.push_back(std::move(info).value());
  }
  return sel;
}

// Each face as the sewn shell holds it (orientation included), and every edge's faces.
struct Sewn {
  std::vector<TopoDS_Face> faces;
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
};

// The sewing tolerance: the one asked for, else the file's precision or the largest edge
// tolerance of the faces, within [kSewingMinTolerance, kSewingMaxRel x size].
double sewing_tolerance(const ShellInput& in, const std::vector<int>& indices, double size) {
  double tol = in.options.sewing_tolerance;
  if (tol != 0.0) return tol;
  tol = in.precision;
  for (int i : indices)
    for (TopExp_Explorer ex(in.faces(i + 1), TopAbs_EDGE); ex.More(); ex.Next())
      tol = std::max(tol, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  return std::clamp(tol, kSewingMinTolerance, std::max(kSewingMinTolerance, kSewingMaxRel * size));
}

// Sews the faces (OpenCASCADE calls: run guarded).
Status sew(const ShellInput& in, const std::vector<int>& indices, double size, Sewn& out) {
  const size_t n = indices.size();
  const double tol = sewing_tolerance(in, indices, size);
  BRepBuilderAPI_Sewing sew(tol, Standard_True, Standard_True, Standard_True, Standard_False);
  sew.SetNonManifoldMode(Standard_False);
  for (int i : indices) sew.Add(in.faces(i + 1));
  Handle(Deadline) deadline = new Deadline(in.options.time_limit_s);
  sew.Perform(deadline->Start());
  if (deadline->expired())
    return Error{
        ErrorCode::kSewingTimeLimit, {}, {std::int64_t{static_cast<int>(in.options.time_limit_s)}}};
  const TopoDS_Shape& shape = sew.SewedShape();
  if (shape.IsNull()) return Error{ErrorCode::kSewingNoShape};
  // The faces as the sewn shape holds them: TopExp_Explorer gives each with the orientation
  // the sewing chose for it within its shell.
  TopTools_IndexedMapOfShape oriented;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) oriented.Add(ex.Current());
  for (size_t k = 0; k < n; ++k) {
    const TopoDS_Shape& f = in.faces(indices[k] + 1);
    const TopoDS_Shape g = sew.IsModifiedSubShape(f) ? sew.ModifiedSubShape(f) : f;
    const int found = g.IsNull() ? 0 : oriented.FindIndex(g);
    if (found == 0 || g.ShapeType() != TopAbs_FACE) {
      Error e{ErrorCode::kSewingRemovedFace, in.source, {tol}};
      e.face = indices[k];
      return e;
    }
    out.faces[k] = TopoDS::Face(oriented(found));
  }
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, out.edge_faces);
  return ok_status();
}

// Shared edges: exactly two uses by two different faces, numbered in the order the faces (as
// given) and their edges meet them; an edge of more than two faces is tagged free.
struct SharedEdges {
  TopTools_DataMapOfShapeInteger tag;
  std::vector<TopoDS_Edge> edges;
  std::vector<std::pair<int, int>> faces;  // positions of each shared edge's faces
  int non_manifold = 0;
};

SharedEdges find_shared_edges(const Sewn& sewn, Parts& parts) {
  const size_t n = sewn.faces.size();
  // Which position in the faces each sewn face has.
  TopTools_DataMapOfShapeInteger position;
  for (size_t k = 0; k < n; ++k) position.Bind(sewn.faces[k], static_cast<int>(k));
  SharedEdges shared;
  for (size_t k = 0; k < n; ++k) {
    for (TopExp_Explorer ex(sewn.faces[k], TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (shared.tag.IsBound(e) || BRep_Tool::Degenerated(e)) continue;
      const TopTools_ListOfShape* faces = sewn.edge_faces.Seek(e);
      if (!faces) continue;
      if (faces->Extent() > 2) {
        // Counted once: marked as seen with a free tag.
        shared.tag.Bind(e, TrimLoop::kFreeEdge);
        ++shared.non_manifold;
        continue;
      }
      if (faces->Extent() != 2 || faces->First().IsSame(faces->Last())) continue;  // free, seam
      const int *a = position.Seek(faces->First()), *b = position.Seek(faces->Last());
      if (!a || !b) continue;
      shared.tag.Bind(e, static_cast<int>(shared.edges.size()));
      shared.edges.push_back(e);
      shared.faces.emplace_back(*a, *b);
      parts.join(*a, *b);
    }
  }
  return shared;
}

// What orient_parts() did: the faces it reversed against the file, the number of parts.
struct Orientation {
  std::vector<int> reoriented;
  int part_count = 0;
};

// The sewing oriented each connected part consistently; a part keeps the file's orientation on
// most of its faces (ties: on its first face as given).
Orientation orient_parts(const ShellInput& in, const std::vector<int>& indices, Parts& parts,
                         std::vector<TopoDS_Face>& sewn) {
  const size_t n = indices.size();
  std::vector<int> agree(n, 0), total(n, 0), first(n, -1);
  for (size_t k = 0; k < n; ++k) {
    const int p = parts.find(static_cast<int>(k));
    const TopAbs_Orientation file_o = in.faces(indices[k] + 1).Orientation();
    agree[static_cast<size_t>(p)] += sewn[k].Orientation() == file_o ? 1 : 0;
    total[static_cast<size_t>(p)] += 1;
    if (first[static_cast<size_t>(p)] < 0) first[static_cast<size_t>(p)] = static_cast<int>(k);
  }
  Orientation o;
  for (size_t k = 0; k < n; ++k) {
    const size_t p = static_cast<size_t>(parts.find(static_cast<int>(k)));
    if (static_cast<int>(p) == static_cast<int>(k)) ++o.part_count;
    const int a = agree[p], t = total[p];
    const bool first_agrees = sewn[static_cast<size_t>(first[p])].Orientation() ==
                              in.faces(indices[static_cast<size_t>(first[p])] + 1).Orientation();
    const bool flip = 2 * a < t || (2 * a == t && !first_agrees);
    if (flip) sewn[k].Reverse();
    if (sewn[k].Orientation() != in.faces(indices[k] + 1).Orientation())
      o.reoriented.push_back(indices[k]);
  }
  return o;
}

// A shared edge is used in opposite directions by its two faces when they are oriented alike;
// the sewing guarantees it for the shells it builds. Checked, not assumed: the shared edges
// whose faces use them in the same direction.
int count_disagreeing(const std::vector<TopoDS_Face>& sewn, const SharedEdges& shared) {
  int disagreeing = 0;
  std::vector<std::vector<std::pair<TopoDS_Shape, TopAbs_Orientation>>> uses(sewn.size());
  for (size_t k = 0; k < sewn.size(); ++k) uses[k] = edge_uses(sewn[k]);
  for (size_t s = 0; s < shared.edges.size(); ++s) {
    const auto [a, b] = shared.faces[s];
    if (use_in(uses[static_cast<size_t>(a)], shared.edges[s]) ==
        use_in(uses[static_cast<size_t>(b)], shared.edges[s]))
      ++disagreeing;
  }
  return disagreeing;
}

// The largest gap between the two faces of any shared edge (OpenCASCADE calls: run guarded).
double largest_gap(const std::vector<TopoDS_Face>& sewn, const SharedEdges& shared) {
  double gap = 0.0;
  for (size_t s = 0; s < shared.edges.size(); ++s)
    gap = std::max(gap, edge_gap(shared.edges[s], sewn[static_cast<size_t>(shared.faces[s].first)],
                                 sewn[static_cast<size_t>(shared.faces[s].second)]));
  return gap;
}

// Each sewn face converted, its trim loop segments tagged with the shared edge they lie on.
Status convert_faces(const ShellInput& in, const Selection& sel,
                     const std::vector<TopoDS_Face>& sewn, const SharedEdges& shared,
                     ShellData& shell) {
  const EdgeTag tag = [&](const TopoDS_Edge& e) -> std::int32_t {
    const int* t = shared.tag.Seek(e);
    return t ? *t : TrimLoop::kFreeEdge;
  };
  for (size_t k = 0; k < sewn.size(); ++k) {
    auto fd = guarded({in.source, sel.indices[k], {}}, [&]() -> Result<FaceData> {
      return convert_face(sewn[k], sel.infos[k], in.options.tolerances, &tag);
    });
    if (!fd) return fd.error();
    shell.faces.push_back(std::move(fd).value());
  }
  return ok_status();
}

// The sewing's warnings: separate shells, non-manifold edges, faces reversed, a shell that
// cannot be oriented.
void add_sewing_warnings(size_t n, const Orientation& o, int non_manifold, int disagreeing,
                         std::vector<Warning>& warnings) {
  if (o.part_count > 1)
    warnings.push_back(
        {WarningCode::kSeparateShells, {static_cast<std::int64_t>(n), std::int64_t{o.part_count}}});
  if (non_manifold > 0)
    warnings.push_back({WarningCode::kNonManifoldEdges, {std::int64_t{non_manifold}}});
  if (!o.reoriented.empty()) {
    Warning w{WarningCode::kFacesReoriented, {}};
    for (const int f : o.reoriented) w.values.emplace_back(std::int64_t{f});
    warnings.push_back(std::move(w));
  }
  if (disagreeing > 0)
    warnings.push_back({WarningCode::kShellNotOrientable, {std::int64_t{disagreeing}}});
}

}  // namespace

double file_precision(XSControl_Reader& reader) {
  const Handle(Interface_InterfaceModel) model = reader.Model();
  if (const auto iges = Handle(IGESData_IGESModel)::DownCast(model); !iges.IsNull()) {
    // Resolution in the file's unit; UnitValue() is the file's unit in millimetres (the
    // readers' xstep.cascade.unit).
    const IGESData_GlobalSection& g = iges->GlobalSection();
    const double r = g.Resolution() * g.UnitValue();
    if (std::isfinite(r) && r > 0.0) return r;
  } else if (const auto step = Handle(StepData_StepModel)::DownCast(model); !step.IsNull()) {
    double largest = 0.0;
    for (int i = 1; i <= step->NbEntities(); ++i) {
      const auto ctx =
          Handle(StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx)::DownCast(
              step->Value(i));
      if (ctx.IsNull()) continue;
      STEPConstruct_UnitContext units;
      if (units.ComputeFactors(ctx->GlobalUnitAssignedContext()) != 0) continue;
      if (units.ComputeTolerance(ctx->GlobalUncertaintyAssignedContext()) != 0 ||
          !units.HasUncertainty())
        continue;
      const double u = units.Uncertainty() * units.LengthFactor();
      if (std::isfinite(u) && u > 0.0) largest = std::max(largest, u);
    }
    if (largest > 0.0) return largest;
  }
  return Interface_Static::RVal("read.precision.val");
}

Result<ShellData> sew_faces(const ShellInput& in, const std::vector<int>& given,
                            std::vector<Warning>& warnings) {
  auto selected = select_faces(in, given);
  if (!selected) return selected.error();
  const Selection& sel = selected.value();
  const std::vector<int>& indices = sel.indices;
  const size_t n = indices.size();
  const Blame what{in.source, -1, "sewing " + face_list(indices)};
  const double size = sel.box.diagonal();
  if (!(size > 0.0)) return blamed(Error{ErrorCode::kSewingZeroSize}, what);
  if (!(in.options.sewing_tolerance >= 0.0) || !std::isfinite(in.options.sewing_tolerance))
    return blamed(Error{ErrorCode::kSewingToleranceInvalid, {}, {in.options.sewing_tolerance}},
                  what);

  Sewn sewn;
  sewn.faces.resize(n);
  auto sewing = guarded(what, [&]() -> Status { return sew(in, indices, size, sewn); });
  if (!sewing) return sewing.error();

  Parts parts(n);
  const SharedEdges shared = find_shared_edges(sewn, parts);
  const Orientation orientation = orient_parts(in, indices, parts, sewn.faces);
  const int disagreeing = count_disagreeing(sewn.faces, shared);

  ShellData shell;
  shell.edge_count = static_cast<std::int32_t>(shared.edges.size());
  shell.source_faces = indices;
  auto gap = guarded(what, [&]() -> Result<double> { return largest_gap(sewn.faces, shared); });
  if (!gap) return gap.error();
  shell.tolerance = gap.value();
  if (auto converted = convert_faces(in, sel, sewn.faces, shared, shell); !converted)
    return converted.error();

  add_sewing_warnings(n, orientation, shared.non_manifold, disagreeing, warnings);
  return shell;
}

}  // namespace plyfit::importers::occt
