// Sewing faces of a mold file into a shell (MoldFile::convert_shell). Analytic shells written
// with OpenCASCADE first (a box of six loose faces, a cylinder and its seam, two plates with a
// known gap), then the shared files: the deflector's 18 faces (occ22470.igs, a closed shell),
// the 4 parametric-spline patches of surf114.igs and the 4 panels of trj7_c2-td-203.stp.

#include <plyfit/importers/importers.hpp>

#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include <catch2/catch.hpp>

#include "importers/occt_reference.hpp"

#include <set>

using namespace plyfit;
using namespace plyfit::test;

namespace {

/// The trim polylines' accuracy (Tolerances::trim_chord_rel of the face size): a polyline's
/// on-surface chords lie within it of the exact edge.
const double kChordRel = Tolerances{}.trim_chord_rel;
/// The importer's documented cap on the sewing tolerance, relative to the shell's size.
constexpr double kSewingCapRel = 1e-4;
/// Golden-section steps for the nearest point of an on-surface chord (0.618^60 ~ 3e-13 of the
/// segment).
constexpr int kGoldenSteps = 60;
/// Nearest segments (by their straight 3D chords) searched on the surface for each point.
constexpr int kCandidateSegments = 3;

bool have_corpus() {
  if (std::filesystem::is_directory(std::string(PLYFIT_SHARED_DIR) + "/cad")) return true;
  WARN("../shared/cad is absent: test skipped");
  return false;
}

// ---------------------------------------------------------------------------------------------
// The runs of a shell's loops: maximal runs of segments with one tag.

struct EdgeRun {
  int face = 0;
  std::int32_t tag = TrimLoop::kFreeEdge;
  std::vector<Vec2> uv;  // the run's points, its first segment's start to its last one's end
};

std::vector<EdgeRun> edge_runs(const ShellData& shell) {
  std::vector<EdgeRun> runs;
  for (size_t f = 0; f < shell.faces.size(); ++f) {
    for (const auto& loop : shell.faces[f].loops) {
      const size_t n = loop.points.size();
      REQUIRE(n >= 3);
      REQUIRE(loop.edges.size() == n);
      for (auto t : loop.edges) CHECK((t >= TrimLoop::kFreeEdge && t < shell.edge_count));
      size_t start = 0;
      while (start < n && loop.edges[start] == loop.edges[(start + n - 1) % n]) ++start;
      if (start == n) {  // one edge closes the loop alone
        EdgeRun r{static_cast<int>(f), loop.edges[0], loop.points};
        r.uv.push_back(loop.points[0]);
        runs.push_back(std::move(r));
        continue;
      }
      for (size_t k = 0; k < n; ++k) {
        const size_t s = (start + k) % n;
        if (k == 0 || loop.edges[s] != loop.edges[(s + n - 1) % n])
          runs.push_back(EdgeRun{static_cast<int>(f), loop.edges[s], {loop.points[s]}});
        runs.back().uv.push_back(loop.points[(s + 1) % n]);
      }
    }
  }
  return runs;
}

// Distance from p to the on-surface chord S(a + s (b - a)), s in [0, 1] (golden section).
double chord_distance(const Face& face, const Vec3& p, const Vec2& a, const Vec2& b) {
  auto d = [&](double s) { return (face.eval1(a + s * (b - a)).p - p).norm(); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = d(x1), f2 = d(x2);
  for (int i = 0; i < kGoldenSteps; ++i) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = d(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = d(x2);
    }
  }
  return std::min({f1, f2, d(0.0), d(1.0)});
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t =
      ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Largest distance from the points of run `a` (on their face) to run `b` as it lies on its
// face (its on-surface chords).
double run_distance(const EdgeRun& a, const Face& fa, const EdgeRun& b, const Face& fb) {
  std::vector<Vec3> pb;
  for (const Vec2& uv : b.uv) pb.push_back(fb.eval1(uv).p);
  double worst = 0.0;
  for (const Vec2& uv : a.uv) {
    const Vec3 p = fa.eval1(uv).p;
    std::vector<std::pair<double, size_t>> near;
    for (size_t k = 0; k + 1 < pb.size(); ++k)
      near.emplace_back(segment_distance(p, pb[k], pb[k + 1]), k);
    const size_t m = std::min<size_t>(kCandidateSegments, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<long>(m), near.end());
    double best = 1e300;
    for (size_t c = 0; c < m; ++c)
      best = std::min(best, chord_distance(fb, p, b.uv[near[c].second], b.uv[near[c].second + 1]));
    worst = std::max(worst, best);
  }
  return worst;
}

// Direction of a run in 3D at its middle.
Vec3 run_direction(const EdgeRun& r, const Face& f, Vec3& at) {
  const size_t k = (r.uv.size() - 1) / 2;
  at = f.eval1(r.uv[k]).p;
  return f.eval1(r.uv[k + 1]).p - at;
}

struct ShellCheck {
  int shared = 0;          // shared edges, each used once by two faces
  int free_runs = 0;       // runs of free segments
  int vertices = 0;        // distinct 3D points where runs meet
  double worst_ratio = 0;  // largest use-to-use distance over the allowed one
};

// Every shared edge is used by exactly two faces, whose polylines lie on the same 3D curve
// within the shell's tolerance plus the polylines' chord accuracy, and run in opposite
// directions (the faces are oriented alike). `sizes`: each face's size as the importer
// measured it (the listing's bounding-box diagonal), which scales its chord accuracy.
ShellCheck check_shell(const ShellData& shell, const std::vector<Face>& faces,
                       const std::vector<double>& sizes) {
  ShellCheck out;
  const auto runs = edge_runs(shell);
  std::map<std::int32_t, std::vector<const EdgeRun*>> uses;
  std::vector<Vec3> corners;
  double largest = 0.0;
  for (double s : sizes) largest = std::max(largest, s);
  for (const auto& r : runs) {
    if (r.tag == TrimLoop::kFreeEdge)
      ++out.free_runs;
    else
      uses[r.tag].push_back(&r);
    corners.push_back(faces[static_cast<size_t>(r.face)].eval1(r.uv.front()).p);
  }
  CHECK(static_cast<int>(uses.size()) == shell.edge_count);
  for (const auto& [tag, u] : uses) {
    INFO("shared edge " << tag);
    REQUIRE(u.size() == 2);
    CHECK(u[0]->face != u[1]->face);
    const Face &fa = faces[static_cast<size_t>(u[0]->face)],
               &fb = faces[static_cast<size_t>(u[1]->face)];
    const double allowed_ab = shell.tolerance + kChordRel * sizes[static_cast<size_t>(u[1]->face)];
    const double allowed_ba = shell.tolerance + kChordRel * sizes[static_cast<size_t>(u[0]->face)];
    const double ab = run_distance(*u[0], fa, *u[1], fb), ba = run_distance(*u[1], fb, *u[0], fa);
    CHECK(ab <= allowed_ab);
    CHECK(ba <= allowed_ba);
    out.worst_ratio = std::max({out.worst_ratio, ab / allowed_ab, ba / allowed_ba});
    Vec3 at_a, at_b;
    const Vec3 da = run_direction(*u[0], fa, at_a);
    run_direction(*u[1], fb, at_b);
    // The direction of b's polyline next to a's middle point.
    size_t nearest = 0;
    double dn = 1e300;
    for (size_t k = 0; k + 1 < u[1]->uv.size(); ++k) {
      const double d = segment_distance(at_a, fb.eval1(u[1]->uv[k]).p, fb.eval1(u[1]->uv[k + 1]).p);
      if (d < dn) dn = d, nearest = k;
    }
    const Vec3 db = fb.eval1(u[1]->uv[nearest + 1]).p - fb.eval1(u[1]->uv[nearest]).p;
    CHECK(da.dot(db) < 0.0);
    ++out.shared;
  }
  // Run ends closer than the shell's tolerance plus the chord accuracy are one vertex.
  const double merge = shell.tolerance + kChordRel * largest;
  std::vector<Vec3> distinct;
  for (const Vec3& c : corners) {
    bool known = false;
    for (const Vec3& d : distinct) known = known || (c - d).norm() <= merge;
    if (!known) distinct.push_back(c);
  }
  out.vertices = static_cast<int>(distinct.size());
  return out;
}

// The shell's faces as kernel faces, and their sizes from the listing.
std::pair<std::vector<Face>, std::vector<double>> kernel_faces(importers::MoldFile& file,
                                                               const ShellData& shell) {
  std::vector<Face> faces;
  std::vector<double> sizes;
  for (size_t k = 0; k < shell.faces.size(); ++k) {
    auto face = Face::create(shell.faces[k]);
    REQUIRE(face.ok());
    faces.push_back(std::move(face).value());
    auto info = file.describe(shell.source_faces[k]);
    REQUIRE(info.ok());
    sizes.push_back(info->bbox.diagonal());
  }
  return {std::move(faces), std::move(sizes)};
}

// Each face of the shell is the face convert_face gives (same NURBS, closed_u/v), but with
// loops; orientation as convert_face's unless the face is in `reoriented`. contains() agrees
// with OpenCASCADE's classifier on the original face.
void check_faces_like_convert_face(importers::MoldFile& file, const ShellData& shell,
                                   const std::vector<Face>& faces, const Reference& ref,
                                   const std::set<int>& reoriented, int samples) {
  Rng rng(5);
  for (size_t k = 0; k < shell.faces.size(); ++k) {
    const int i = shell.source_faces[k];
    INFO("face " << i);
    auto single = file.convert_face(i);
    REQUIRE(single.ok());
    const FaceData& s = shell.faces[k];
    CHECK(s.surface.knots_u == single->surface.knots_u);
    CHECK(s.surface.knots_v == single->surface.knots_v);
    CHECK(s.surface.weights == single->surface.weights);
    REQUIRE(s.surface.poles.size() == single->surface.poles.size());
    double pole_moved = 0.0;
    for (size_t p = 0; p < s.surface.poles.size(); ++p)
      pole_moved = std::max(pole_moved, (s.surface.poles[p] - single->surface.poles[p]).norm());
    // Exactly the same for B-splines; planes are converted over their (u, v) range, which the
    // sewing's new pcurves can change by round-off.
    CHECK(pole_moved <= kRoundoffRel * faces[k].size());
    CHECK(s.closed_u == single->closed_u);
    CHECK(s.closed_v == single->closed_v);
    CHECK(s.reversed == (single->reversed != (reoriented.count(i) > 0)));
    // Closed loops on the face's boundary: on the original face's edges, which the sewing
    // moved by at most the gap it closed.
    CHECK_FALSE(s.loops.empty());
    check_loops_on_edges(faces[k], ref.face(i), shell.tolerance);
    CHECK(check_contains(faces[k], face_in_converted_parameters(ref.face(i)), samples, rng) >
          samples / 2);
  }
}

// ---------------------------------------------------------------------------------------------
// Analytic shells, written with OpenCASCADE.

// Writes `shape` as STEP or IGES with the file's precision (uncertainty, resolution) `precision`
// in millimetres.
void write_with_precision(const TopoDS_Shape& shape, const std::string& path, double precision) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Interface_Static::SetIVal("write.precision.mode", 2);  // write.precision.val
  Interface_Static::SetRVal("write.precision.val", precision);
  if (path.find(".igs") != std::string::npos) {
    IGESControl_Controller::Init();
    IGESControl_Writer w("MM", 1);
    REQUIRE(w.AddShape(shape));
    w.ComputeModel();
    REQUIRE(w.Write(path.c_str()));
  } else {
    STEPControl_Controller::Init();
    STEPControl_Writer w;
    REQUIRE(w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone);
    REQUIRE(w.Write(path.c_str()) == IFSelect_RetDone);
  }
  Interface_Static::SetIVal("write.precision.mode", 0);
}

// The faces of `shape`, each copied on its own (no edge shared), as one compound.
TopoDS_Shape loose_faces(const TopoDS_Shape& shape, int reverse_face = -1) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  int k = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next(), ++k) {
    TopoDS_Shape f = BRepBuilderAPI_Copy(ex.Current()).Shape();
    if (k == reverse_face) f.Reverse();
    b.Add(c, f);
  }
  return c;
}

// Two 100 x 100 plates side by side along x = 100, the second raised by `gap` (z).
TopoDS_Shape two_plates(double gap) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0, 100, 0, 100).Face());
  b.Add(c, BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, gap), gp::DZ()), 100, 200, 0, 100).Face());
  return c;
}

bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("importers: a box of six loose faces sews into a closed shell, oriented consistently") {
  TempDir dir("shell_box");
  // The file's own orientations: as the box has them (STEP), as IGES 510 faces without a shell
  // keep them (their surfaces' normals, three of them inwards), and with face 2 or face 0 (the
  // one the sewing orients the others by) turned inwards.
  for (const auto& [name, flipped] : std::vector<std::pair<std::string, int>>{
           {"box.step", -1}, {"box.igs", -1}, {"flipped2.step", 2}, {"flipped0.step", 0}}) {
    INFO(name);
    const std::string path = dir.file(name);
    const gp_Pnt corner(-10, 0, 5), centre(10, 15, 15);
    write_with_precision(loose_faces(BRepPrimAPI_MakeBox(corner, 40, 30, 20).Shape(), flipped),
                         path, 1e-6);
    auto file = importers::open_mold(path);
    REQUIRE(file.ok());
    const Reference ref = read_reference(path, name.find(".igs") != std::string::npos);
    REQUIRE(ref.count() == 6);
    // Independently, by OpenCASCADE: which faces' normals point out of the box; a consistent
    // shell reverses the others (ties: those that disagree with face 0).
    std::vector<bool> out(6);
    int outwards = 0;
    for (int i = 0; i < 6; ++i) {
      const TopoDS_Face f = ref.face(i);
      double u0, u1, v0, v1;
      BRepTools::UVBounds(f, u0, u1, v0, v1);
      GeomLProp_SLProps props(BRep_Tool::Surface(f), 0.5 * (u0 + u1), 0.5 * (v0 + v1), 1,
                              Precision::Confusion());
      REQUIRE(props.IsNormalDefined());
      const gp_Vec n = props.Normal().XYZ() * (f.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0);
      out[i] = n.Dot(gp_Vec(centre, props.Value())) > 0;
      outwards += out[i];
    }
    if (flipped >= 0) CHECK(outwards == 5);
    const bool kept = outwards > 3 || (outwards == 3 && out[0]);
    std::set<int> reversed;
    std::string listed;
    for (int i = 0; i < 6; ++i)
      if (out[i] != kept) {
        reversed.insert(i);
        listed += (listed.empty() ? "" : ", ") + std::to_string(i);
      }

    auto shell = (*file)->convert_shell({});  // all faces
    INFO((shell.ok() ? std::string() : shell.error().message));
    REQUIRE(shell.ok());
    CHECK(shell->faces.size() == 6);
    CHECK(shell->source_faces == std::vector<int>({0, 1, 2, 3, 4, 5}));
    CHECK(shell->edge_count == 12);
    // The faces meet exactly: the gap is round-off of the part size.
    CHECK(shell->tolerance <= kRoundoffRel * 50.0);
    const auto& warnings = (*file)->summary().warnings;
    if (reversed.empty())
      CHECK_FALSE(mentions(warnings, "sewing"));
    else
      CHECK(mentions(warnings, (reversed.size() == 1 ? "sewing: face " : "sewing: faces ") +
                                   listed + " reversed to orient the shell consistently"));
    auto [faces, sizes] = kernel_faces(**file, *shell);
    const ShellCheck c = check_shell(*shell, faces, sizes);  // uses opposite everywhere
    CHECK(c.shared == 12);
    CHECK(c.free_runs == 0);
    CHECK(c.vertices - c.shared + 6 == 2);
    check_faces_like_convert_face(**file, *shell, faces, ref, reversed, 300);
    for (const Face& f : faces) {
      const auto& d = f.domain();
      const Vec2 mid(0.5 * (d.u0 + d.u1), 0.5 * (d.v0 + d.v1));
      const Vec3 from_centre = f.eval1(mid).p - Vec3(centre.X(), centre.Y(), centre.Z());
      CHECK((f.normal(mid).n.dot(from_centre) > 0.0) == kept);
    }
  }
}

TEST_CASE("importers: a cylinder's seam is not a shared edge; its two circles are") {
  TempDir dir("shell_cylinder");
  const std::string path = dir.file("cylinder.step");
  write_with_precision(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 10, 25).Shape(),
                       path, 1e-6);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  const Reference ref = read_reference(path, false);
  REQUIRE(ref.count() == 3);
  auto shell = (*file)->convert_shell({2, 0, 1});
  REQUIRE(shell.ok());
  CHECK(shell->source_faces == std::vector<int>({2, 0, 1}));
  CHECK(shell->edge_count == 2);
  auto [faces, sizes] = kernel_faces(**file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  CHECK(c.shared == 2);
  int closed = 0;
  for (const auto& f : shell->faces) closed += f.closed_u || f.closed_v;
  CHECK(closed == 1);
  // The seam: one free run on each side of the lateral face's domain, nothing else free.
  CHECK(c.free_runs == 2);
  check_faces_like_convert_face(**file, *shell, faces, ref, {}, 300);
}

TEST_CASE("importers: the sewing closes a gap below the file's precision and reports it") {
  TempDir dir("shell_gap");
  constexpr double kGap = 2e-3;  // mm, between the plates' edges at x = 100
  // Within round-off of the measured gap: the plates' images along the edge differ by kGap in z.
  const double gap_tol = kRoundoffRel * 200.0;
  for (const std::string ext : {"step", "igs"}) {
    INFO(ext);
    const std::string fine = dir.file("fine." + ext), coarse = dir.file("coarse." + ext),
                      capped = dir.file("capped." + ext);
    write_with_precision(two_plates(kGap), fine, kGap / 10);   // the gap is not closed
    write_with_precision(two_plates(kGap), coarse, kGap * 5);  // the gap is closed
    write_with_precision(two_plates(0.05), capped, 1.0);       // precision above the cap
    auto f = importers::open_mold(fine);
    REQUIRE(f.ok());
    auto s = (*f)->convert_shell({0, 1});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 0);
    CHECK(s->tolerance == 0.0);
    CHECK(mentions((*f)->summary().warnings, "sewing: the 2 faces form 2 separate shells"));
    auto c = importers::open_mold(coarse);
    REQUIRE(c.ok());
    s = (*c)->convert_shell({0, 1});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 1);
    CHECK(std::abs(s->tolerance - kGap) <= gap_tol);
    CHECK_FALSE(mentions((*c)->summary().warnings, "sewing"));
    auto [faces, sizes] = kernel_faces(**c, *s);
    const ShellCheck sc = check_shell(*s, faces, sizes);
    CHECK(sc.shared == 1);
    CHECK(sc.free_runs == 2);
    // A stated precision of 1 mm is capped at 1e-4 of the shell's size (0.022 mm here): a
    // 0.05 mm gap stays open; an explicit sewing tolerance closes it.
    auto k = importers::open_mold(capped);
    REQUIRE(k.ok());
    s = (*k)->convert_shell({});
    REQUIRE(s.ok());
    CHECK(s->edge_count == 0);
    importers::ImportOptions wide;
    wide.sewing_tolerance = 0.1;
    auto shell = importers::load_shell(capped, {}, wide);
    REQUIRE(shell.ok());
    CHECK(shell->edge_count == 1);
    CHECK(std::abs(shell->tolerance - 0.05) <= gap_tol);
  }
}

TEST_CASE("importers: an edge of three faces is non-manifold: free, with a warning") {
  TempDir dir("shell_fan");
  // Three plates on one line (100, y, 0): two flat ones and one standing up, joined there by
  // OpenCASCADE's non-manifold sewing, so that the file holds one edge of three faces.
  auto quad = [](const gp_Pnt& a, const gp_Pnt& b, const gp_Pnt& c, const gp_Pnt& d) {
    return BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire(), true)
        .Face();
  };
  BRepBuilderAPI_Sewing fan(1e-6);
  fan.SetNonManifoldMode(Standard_True);
  fan.Add(quad(gp_Pnt(0, 0, 0), gp_Pnt(100, 0, 0), gp_Pnt(100, 100, 0), gp_Pnt(0, 100, 0)));
  fan.Add(quad(gp_Pnt(100, 0, 0), gp_Pnt(200, 0, 0), gp_Pnt(200, 100, 0), gp_Pnt(100, 100, 0)));
  fan.Add(quad(gp_Pnt(100, 0, 0), gp_Pnt(100, 100, 0), gp_Pnt(100, 100, 100), gp_Pnt(100, 0, 100)));
  fan.Perform();
  const std::string path = dir.file("fan.step");
  write_with_precision(fan.SewedShape(), path, 1e-6);
  const Reference ref = read_reference(path, false);
  REQUIRE(ref.count() == 3);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(ref.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int of_three = 0;
  for (int e = 1; e <= edge_faces.Extent(); ++e) of_three += edge_faces(e).Extent() == 3;
  REQUIRE(of_three == 1);  // the file really holds it
  std::vector<std::string> warnings;
  auto shell = importers::load_shell(path, {}, {}, &warnings);
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == 0);
  CHECK(mentions(warnings,
                 "sewing: 1 edge bounds more than two faces (non-manifold), treated "
                 "as free"));
  CHECK(mentions(warnings, "sewing: the 3 faces form 3 separate shells"));
  for (const auto& f : shell->faces)
    for (const auto& loop : f.loops)
      for (auto t : loop.edges) CHECK(t == TrimLoop::kFreeEdge);
}

TEST_CASE("importers: bad face lists for a shell are one-line errors naming the file and face") {
  TempDir dir("shell_errors");
  const std::string path = dir.file("plates.step");
  write_with_precision(two_plates(0.0), path, 1e-6);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  for (const auto& [faces, text] : std::vector<std::pair<std::vector<int>, std::string>>{
           {{0, 2}, "face 2 out of range"},
           {{-1}, "face -1 out of range"},
           {{1, 0, 1}, "face 1 is listed twice"}}) {
    auto s = (*file)->convert_shell(faces);
    REQUIRE_FALSE(s.ok());
    INFO(s.error().message);
    CHECK(s.error().message.rfind(path + ": ", 0) == 0);
    CHECK(s.error().message.find(text) != std::string::npos);
    CHECK(s.error().message.find('\n') == std::string::npos);
  }
  importers::ImportOptions negative;
  negative.sewing_tolerance = -0.01;
  auto bad = importers::load_shell(path, {}, negative);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.rfind(path + ": sewing faces 0, 1: invalid sewing tolerance", 0) == 0);
  std::vector<std::string> warnings;
  auto missing = importers::load_shell(dir.file("none.step"), {}, {}, &warnings);
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message.find(dir.file("none.step")) != std::string::npos);
  auto ok = importers::load_shell(path, {1, 0}, {}, &warnings);
  REQUIRE(ok.ok());
  CHECK(ok->edge_count == 1);
  CHECK(ok->source_faces == std::vector<int>({1, 0}));
}

// ---------------------------------------------------------------------------------------------
// The shared files.

namespace {

// A shared file opened by plyfit and read by OpenCASCADE's own reader.
struct SharedFile {
  std::unique_ptr<importers::MoldFile> file;
  Reference ref;
  double cap = 0.0;  // the largest sewing tolerance the importer allows on all of it
};

SharedFile open_shared(const std::string& name, int faces) {
  const std::string path = shared_cad(name);
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  SharedFile f{std::move(file).value(), read_reference(path, name.find(".igs") != name.npos)};
  REQUIRE(f.ref.count() == faces);
  Bnd_Box all;
  BRepBndLib::Add(f.ref.shape, all);
  f.cap = kSewingCapRel * std::sqrt(all.SquareExtent());
  return f;
}

// Edges of a shape that bound two different faces, by OpenCASCADE.
int occt_shared_edges(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int shared = 0;
  for (int e = 1; e <= edge_faces.Extent(); ++e)
    shared += edge_faces(e).Extent() == 2 && !edge_faces(e).First().IsSame(edge_faces(e).Last());
  return shared;
}

// Sews every face of a file whose faces share no edge: as many shells as faces, a warning.
ShellCheck sew_apart(SharedFile& f) {
  const int n = f.ref.count();
  auto shell = f.file->convert_shell({});
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == 0);
  CHECK(shell->tolerance == 0.0);
  CHECK(mentions(f.file->summary().warnings, "sewing: the " + std::to_string(n) + " faces form " +
                                                 std::to_string(n) + " separate shells"));
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 1000);
  return c;
}

}  // namespace

TEST_CASE("importers: the deflector's 18 faces (occ22470.igs) sew into one closed shell") {
  if (!have_corpus()) return;
  SharedFile f = open_shared("occ22470.igs", 18);
  // OpenCASCADE's own analysis of the file's shell: every edge bounds two faces, no free
  // boundary, and its Euler characteristic.
  const int occt_shared = occt_shared_edges(f.ref.shape);
  TopTools_IndexedMapOfShape vertices, edges;
  TopExp::MapShapes(f.ref.shape, TopAbs_VERTEX, vertices);
  TopExp::MapShapes(f.ref.shape, TopAbs_EDGE, edges);
  const int occt_euler = vertices.Extent() - edges.Extent() + f.ref.count();
  ShapeAnalysis_FreeBounds free_bounds(f.ref.shape);
  TopTools_IndexedMapOfShape free_edges;
  TopExp::MapShapes(free_bounds.GetClosedWires(), TopAbs_EDGE, free_edges);
  TopExp::MapShapes(free_bounds.GetOpenWires(), TopAbs_EDGE, free_edges);
  CHECK(free_edges.Extent() == 0);
  CHECK(occt_shared == edges.Extent());
  CHECK(occt_euler == 2);  // a closed shell of genus 0

  auto shell = f.file->convert_shell(f.file->all_faces());
  REQUIRE(shell.ok());
  CHECK(shell->faces.size() == 18);
  CHECK(shell->edge_count == occt_shared);
  CHECK_FALSE(mentions(f.file->summary().warnings, "sewing"));
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  CHECK(c.shared == occt_shared);
  CHECK(c.free_runs == free_edges.Extent());
  CHECK(c.vertices - c.shared + 18 == occt_euler);
  // The gap closed is no larger than the tolerances OpenCASCADE's reader gave the edges.
  double edge_tol = 0.0;
  for (int e = 1; e <= edges.Extent(); ++e)
    edge_tol = std::max(edge_tol, BRep_Tool::Tolerance(TopoDS::Edge(edges(e))));
  CHECK(shell->tolerance <= 2 * edge_tol);
  WARN("occ22470: " << c.shared << " shared edges, gap " << shell->tolerance
                    << " mm, worst use-to-use distance " << c.worst_ratio << " of the allowed");
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 1000);
}

TEST_CASE("importers: surf114's four patches cross each other but share no border") {
  if (!have_corpus()) return;
  SharedFile f = open_shared("surf114.igs", 4);
  // Independently: no border of one patch runs along a border of another within the largest
  // sewing tolerance the importer allows (1e-4 of the size), so no edge can be shared.
  for (int i = 0; i < 4; ++i)
    for (TopExp_Explorer ex(f.ref.face(i), TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e)) continue;
      BRepAdaptor_Curve c(e);
      for (int j = 0; j < 4; ++j) {
        if (j == i) continue;
        double far = 0.0;
        for (int s = 0; s <= 10; ++s) {
          const gp_Pnt p =
              c.Value(c.FirstParameter() + s * (c.LastParameter() - c.FirstParameter()) / 10);
          BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(p).Vertex(),
                                       BRepTools::OuterWire(f.ref.face(j)));
          REQUIRE(d.IsDone());
          far = std::max(far, d.Value());
        }
        CHECK(far > f.cap);
      }
    }
  // ... though they cross: every patch touches the tube (face 1).
  for (int i : {0, 2, 3}) {
    BRepExtrema_DistShapeShape d(f.ref.face(1), f.ref.face(i));
    REQUIRE(d.IsDone());
    CHECK(d.Value() <= f.cap);
  }
  CHECK(sew_apart(f).shared == 0);
}

TEST_CASE("importers: trj7's four panels lie apart: four shells, no shared edge") {
  if (!have_corpus()) return;
  SharedFile f = open_shared("trj7_c2-td-203.stp", 4);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      BRepExtrema_DistShapeShape d(f.ref.face(i), f.ref.face(j));
      REQUIRE(d.IsDone());
      CHECK(d.Value() > f.cap);
    }
  CHECK(sew_apart(f).free_runs == 4);  // one loop of free edges per panel
}

TEST_CASE("importers: the cornetta's 110 faces sew into one shell like the file's own", "[slow]") {
  if (!have_corpus()) return;
  SharedFile f = open_shared("bug27693_cornetta-step.stp", 110);
  auto shell = f.file->convert_shell({});
  REQUIRE(shell.ok());
  CHECK(shell->edge_count == occt_shared_edges(f.ref.shape));
  CHECK_FALSE(mentions(f.file->summary().warnings, "sewing"));
  auto [faces, sizes] = kernel_faces(*f.file, *shell);
  const ShellCheck c = check_shell(*shell, faces, sizes);
  WARN("cornetta: " << c.shared << " shared edges, " << c.free_runs << " free runs, gap "
                    << shell->tolerance << " mm, worst use-to-use distance " << c.worst_ratio
                    << " of the allowed");
  check_faces_like_convert_face(*f.file, *shell, faces, f.ref, {}, 300);
}
