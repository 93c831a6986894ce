// plyfit-bench stress-mold OUT.igs|OUT.step [--faces N] [--poles P] [--holes H]: writes a large
// mold file with OpenCASCADE for the import benchmarks (we have no large real CAD file): N
// trimmed B-spline faces side by side, each a bicubic P x P-pole surface (every third one
// rational, with smoothly varying weights) with a wavy height field, trimmed by a periodic B-spline
// outer loop and H circular holes. The IGES file holds 144 trimmed surfaces (OpenCASCADE's default
// "faces" mode), the STEP file one AP214 compound of advanced faces. The content is a function of
// the arguments alone (a fixed pseudo-random sequence), so the file can be rebuilt anywhere.

#include "bench.hpp"
#include "tables.hpp"

#include <plyfit/kernel/types.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Face.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>

namespace plyfit::bench {

namespace {

// Side of one face's square in the plane (mm) and the height of its waves.
constexpr double kFaceSide = 100.0;
constexpr double kWaveHeight = 12.0;
// Random part of the pole heights, relative to the wave height: smooth, as fitted CAD surfaces
// are.
constexpr double kRoughness = 0.01;
// Points the outer trim loop interpolates (periodic cubic), its mean radius in (u, v) and the
// amplitude of its wobble; the holes' radius.
constexpr int kLoopPoints = 24;
constexpr double kLoopRadius = 0.4, kLoopWobble = 0.05, kHoleRadius = 0.045;

// A fixed pseudo-random sequence (64-bit LCG, Knuth's constants) in [0, 1).
struct Lcg {
  std::uint64_t s;
  double next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) * (1.0 / 9007199254740992.0);
  }
};

Handle(Geom_BSplineSurface) wavy_surface(int k, int poles, double x0, Lcg& rng) {
  const int degree = 3;
  TColgp_Array2OfPnt p(1, poles, 1, poles);
  TColStd_Array2OfReal w(1, poles, 1, poles);
  const bool rational = k % 3 == 2;
  for (int i = 1; i <= poles; ++i)
    for (int j = 1; j <= poles; ++j) {
      const double s = (i - 1.0) / (poles - 1.0), t = (j - 1.0) / (poles - 1.0);
      const double z = kWaveHeight * (std::sin(2 * kPi * (s + 0.1 * k)) * std::cos(3 * kPi * t) +
                                      kRoughness * (rng.next() - 0.5));
      p(i, j) = gp_Pnt(x0 + kFaceSide * s, kFaceSide * t, z);
      // Smooth weights (as the conics of real rational faces have), not random ones.
      w(i, j) = rational ? 1.0 + 0.2 * std::sin(kPi * s) * std::sin(kPi * t) : 1.0;
    }
  // Uniform clamped knots.
  const int nk = poles - degree + 1;
  TColStd_Array1OfReal knots(1, nk);
  TColStd_Array1OfInteger mults(1, nk);
  for (int i = 1; i <= nk; ++i) {
    knots(i) = (i - 1.0) / (nk - 1.0);
    mults(i) = (i == 1 || i == nk) ? degree + 1 : 1;
  }
  if (rational) return new Geom_BSplineSurface(p, w, knots, knots, mults, mults, degree, degree);
  return new Geom_BSplineSurface(p, knots, knots, mults, mults, degree, degree);
}

TopoDS_Wire wire_of(const Handle(Geom2d_Curve) & c, const Handle(Geom_BSplineSurface) & s) {
  BRepBuilderAPI_MakeEdge edge(c, s);
  BRepBuilderAPI_MakeWire wire(edge.Edge());
  return wire.Wire();
}

// Face k: the wavy surface trimmed by a wobbly outer loop and `holes` circles.
TopoDS_Face stress_face(int k, int poles, int holes, Lcg& rng) {
  const Handle(Geom_BSplineSurface) s = wavy_surface(k, poles, k * kFaceSide * 1.05, rng);
  Handle(TColgp_HArray1OfPnt2d) pts = new TColgp_HArray1OfPnt2d(1, kLoopPoints);
  for (int i = 1; i <= kLoopPoints; ++i) {
    const double a = 2 * kPi * (i - 1) / kLoopPoints;
    const double r = kLoopRadius + kLoopWobble * std::sin(3 * a + k) * (0.5 + rng.next());
    pts->SetValue(i, gp_Pnt2d(0.5 + r * std::cos(a), 0.5 + r * std::sin(a)));
  }
  Geom2dAPI_Interpolate interp(pts, Standard_True, 1e-9);
  interp.Perform();
  BRepBuilderAPI_MakeFace make(s, wire_of(interp.Curve(), s), Standard_True);
  for (int h = 0; h < holes; ++h) {
    const double a = 2 * kPi * (h + 0.5) / std::max(holes, 1);
    const double r = holes == 1 ? 0.0 : 0.18;
    // Clockwise: a hole.
    const gp_Ax2d axis(gp_Pnt2d(0.5 + r * std::cos(a), 0.5 + r * std::sin(a)), gp_Dir2d(1, 0));
    make.Add(wire_of(new Geom2d_Circle(axis, kHoleRadius, Standard_False), s));
  }
  TopoDS_Face f = make.Face();
  BRepLib::BuildCurves3d(f);
  ShapeFix_Face fix(f);
  fix.Perform();
  return fix.Face();
}

int run_stress_mold(const std::vector<std::string>& args) {
  if (args.empty() || args[0].rfind("--", 0) == 0) {
    std::cerr << "usage: plyfit-bench stress-mold OUT.igs|OUT.step [--faces N] [--poles P] "
                 "[--holes H]\n";
    return 2;
  }
  const std::string out = args[0];
  const int faces = std::stoi(option_value(args, "--faces", "25"));
  const int poles = std::stoi(option_value(args, "--poles", "30"));
  const int holes = std::stoi(option_value(args, "--holes", "3"));
  if (faces < 1 || poles < 4 || holes < 0) {
    std::cerr << "plyfit-bench: stress-mold: need --faces >= 1, --poles >= 4, --holes >= 0\n";
    return 2;
  }
  if (!write_stress_mold(out, faces, poles, holes)) {
    std::cerr << "plyfit-bench: stress-mold: could not write " << out
              << " (the extension must be .igs, .iges, .stp or .step)\n";
    return 1;
  }
  std::error_code ec;
  std::printf("%s: %d trimmed faces, %dx%d poles, %d holes each, %.2f MB\n", out.c_str(), faces,
              poles, poles, holes,
              static_cast<double>(std::filesystem::file_size(out, ec)) / (1024.0 * 1024.0));
  return 0;
}

const BenchmarkRegistrar kRegisterStressMold{
    Benchmark{"stress-mold",
              "write a large mold file of trimmed B-spline faces: OUT.igs|OUT.step [--faces N] "
              "[--poles P] [--holes H]",
              run_stress_mold}};

}  // namespace

bool write_stress_mold(const std::string& path, int faces, int poles, int holes) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Lcg rng{12345};
  TopoDS_Compound compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  for (int k = 0; k < faces; ++k) builder.Add(compound, stress_face(k, poles, holes, rng));
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".igs" || ext == ".iges") {
    IGESControl_Controller::Init();
    IGESControl_Writer writer("MM", 0);
    return writer.AddShape(compound) && writer.Write(path.c_str());
  }
  if (ext == ".stp" || ext == ".step") {
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("write.step.unit", "MM");
    STEPControl_Writer writer;
    return writer.Transfer(compound, STEPControl_AsIs) == IFSelect_RetDone &&
           writer.Write(path.c_str()) == IFSelect_RetDone;
  }
  return false;
}

}  // namespace plyfit::bench
