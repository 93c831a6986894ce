// The built-in molds: each one's description, parameters and face, and the registry of them.
#include <plyfit/kernel/builtin_molds.hpp>

#include "geometry/analytic_surfaces.hpp"
#include "molds/builtin.hpp"
#include "surface/face.hpp"

#include <cmath>

namespace plyfit {

namespace {

using detail::BuiltinParams;
using detail::MoldEntry;

/// The dish's square domain reaches this many times its trim radius from the axis (the
/// surface extends past the trim so that the trim is a real one, not the natural boundary).
constexpr double kDishDomainMargin = 1.25;
/// The wave's pole count per direction at the most.
constexpr int kWaveMaxPoles = 200;

// The full circle of `radius` about `centre` in (u, v), exact (rational quadratic).
std::vector<NurbsCurveData2> circle2(const Vec2& centre, double radius) {
  NurbsCurveData2 c = circle_arc(radius, 0.0, 2 * kPi);
  for (auto& p : c.poles) p += centre;
  return {c};
}

// The border of a surface's domain, counter-clockwise in (u, v).
std::vector<NurbsCurveData2> domain_border(const NurbsSurfaceData& s) {
  const auto c = detail::domain_corners(s);
  return detail::polygon_curves({c.begin(), c.end()});
}

// The dish: z = (x^2 + y^2) / (2 rho) over [-a, a]^2 as a biquadratic Bezier patch with u = x,
// v = y (its knots are the coordinates); normal towards +Z.
NurbsSurfaceData paraboloid_patch(double a, double rho) {
  const double c[3] = {1.0, -1.0, 1.0};  // Bernstein coefficients of x^2 / a^2 on [-a, a]
  const double x[3] = {-a, 0.0, a};
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  s.knots_u = s.knots_v = {-a, -a, -a, a, a, a};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.poles.emplace_back(x[i], x[j], a * a * (c[i] + c[j]) / (2 * rho));
  return s;
}

// The plate [0, W] x [0, H] with u = x, v = y; normal +Z.
NurbsSurfaceData plate_patch(double w, double h) {
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = {0, 0, w, w};
  s.knots_v = {0, 0, h, h};
  s.poles = {Vec3(0, 0, 0), Vec3(0, h, 0), Vec3(w, 0, 0), Vec3(w, h, 0)};
  return s;
}

MoldEntry sphere_octant_mold() {
  return {{"sphere-octant",
           "first octant x, y, z >= 0 of the sphere of radius R about the origin, as an exact "
           "rational NURBS with its pole at (0, 0, R)",
           {{"R", 20.0, "radius"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"R"}); !s) return s;
            b.face.surface = sphere_octant(v["R"]);
            return ok_status();
          }};
}

MoldEntry hemisphere_mold() {
  return {{"hemisphere",
           "upper half z >= 0 of the sphere of radius R about the origin; closed around Z, pole "
           "at (0, 0, R)",
           {{"R", 1.0, "radius"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"R"}); !s) return s;
            b.face.surface = sphere_patch(v["R"], 0.0, kPi / 2, 0.0, 2 * kPi);
            b.face.closed_v = true;
            return ok_status();
          }};
}

MoldEntry revolution_third_mold() {
  // The profile passes exactly through the paper's (r, z) = (13.75, 7.5).
  const double height = 7.5 / std::sqrt(1.0 - (13.75 / 20.0) * (13.75 / 20.0));
  return {{"revolution-third",
           "sector from the +X axis counter-clockwise by `angle` of the surface of revolution "
           "about Z whose profile is the quarter ellipse r^2/a^2 + z^2/h^2 = 1 (r = a at z = 0, "
           "pole at z = h; h defaults to 10.33, through the paper's (13.75, 7.5))",
           {{"a", 20.0, "radial semi-axis"},
            {"h", height, "height (semi-axis along Z)"},
            {"angle", 120.0, "sector angle, degrees"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"a", "h"}); !s) return s;
            if (auto s = v.angle("angle"); !s) return s;
            b.face.surface =
                revolve(ellipse_arc(v["a"], v["h"], kPi / 2, 0.0), 0.0, v.radians("angle"));
            b.face.closed_v = v["angle"] == 360.0;
            return ok_status();
          }};
}

// The cylinder's window: a hole bounded by two generators and two circles about the middle.
// Its corners in (u, v) (u runs along z, v around the axis) are found by projecting the
// points at its angles onto the face.
Status cut_window(const BuiltinParams& v, const Tolerances& tol, BuiltinFace& b) {
  if (!(v["window_angle"] > 0.0 && v["window_angle"] < v["angle"] && v["window_height"] > 0.0 &&
        v["window_height"] < v["H"]))
    return Error{ErrorCode::kBuiltinCylinderWindow};
  auto face = Face::create(b.face, tol);
  if (!face) return face.error();
  const double r = v["R"], mid = v.radians("angle") / 2, half = v.radians("window_angle") / 2;
  const double z0 = (v["H"] - v["window_height"]) / 2, z1 = z0 + v["window_height"];
  auto uv_at = [&](double a, double z) {
    return face->project(Vec3(r * std::cos(a), r * std::sin(a), z)).at.uv;
  };
  const Vec2 c0 = uv_at(mid - half, z0), c1 = uv_at(mid + half, z1);
  b.exact_loops.push_back(domain_border(b.face.surface));
  b.exact_loops.push_back(
      detail::polygon_curves({c0, Vec2(c0.x(), c1.y()), c1, Vec2(c1.x(), c0.y())}));
  return ok_status();
}

MoldEntry cylinder_mold() {
  return {{"cylinder",
           "x^2 + y^2 = R^2, 0 <= z <= H, from the +X axis counter-clockwise by `angle`; closed "
           "when angle = 360; with window_angle > 0 a window (a hole bounded by two generators and "
           "two circles) of that angle and window_height about the middle (angle / 2, H / 2)",
           {{"R", 10.0, "radius"},
            {"H", 20.0, "height"},
            {"angle", 90.0, "sector angle, degrees"},
            {"window_angle", 0.0, "window angle, degrees (0: no window)"},
            {"window_height", 0.0, "window height"}}},
          [](const BuiltinParams& v, const Tolerances& tol, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"R", "H"}); !s) return s;
            if (auto s = v.angle("angle"); !s) return s;
            b.face.surface = cylinder_patch(v["R"], 0.0, v.radians("angle"), 0.0, v["H"]);
            b.face.closed_v = v["angle"] == 360.0;
            if (v["window_angle"] == 0.0 && v["window_height"] == 0.0) return ok_status();
            return cut_window(v, tol, b);
          }};
}

MoldEntry cone_mold() {
  return {{"cone",
           "cone frustum about Z with radius r0 at z = 0 and r1 at z = H, from the +X axis "
           "counter-clockwise by `angle` (r1 = 0 gives the apex)",
           {{"r0", 20.0, "radius at z = 0"},
            {"r1", 10.0, "radius at z = H"},
            {"H", 15.0, "height"},
            {"angle", 90.0, "sector angle, degrees"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"H"}); !s) return s;
            if (!(v["r0"] >= 0.0) || !(v["r1"] >= 0.0) || !(v["r0"] + v["r1"] > 0.0))
              return Error{ErrorCode::kBuiltinConeRadii};
            if (auto s = v.angle("angle"); !s) return s;
            b.face.surface = cone_patch(v["r0"], v["r1"], 0.0, v["H"], 0.0, v.radians("angle"));
            b.face.closed_v = v["angle"] == 360.0;
            return ok_status();
          }};
}

MoldEntry plane_mold() {
  return {{"plane",
           "rectangle [0, W] x [0, H] in the plane z = 0, normal +Z",
           {{"W", 100.0, "size along X"}, {"H", 100.0, "size along Y"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"W", "H"}); !s) return s;
            b.face.surface = plane_patch(Vec3::Zero(), Vec3(v["W"], 0, 0), Vec3(0, v["H"], 0));
            return ok_status();
          }};
}

MoldEntry plate_mold() {
  return {
      {"plate",
       "rectangle [0, W] x [0, H] in the plane z = 0, normal +Z, u = x and v = y; with hole_r > "
       "0 a circular hole of radius hole_r about (hole_x, hole_y)",
       {{"W", 100.0, "size along X"},
        {"H", 60.0, "size along Y"},
        {"hole_r", 0.0, "hole radius (0: no hole)"},
        {"hole_x", 50.0, "hole centre x"},
        {"hole_y", 30.0, "hole centre y"}}},
      [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
        if (auto s = v.positive({"W", "H"}); !s) return s;
        b.face.surface = plate_patch(v["W"], v["H"]);
        if (v["hole_r"] == 0.0) return ok_status();
        const double r = v["hole_r"], x = v["hole_x"], y = v["hole_y"];
        if (!(r > 0.0 && x - r > 0.0 && x + r < v["W"] && y - r > 0.0 && y + r < v["H"]))
          return Error{ErrorCode::kBuiltinPlateHole};
        b.exact_loops.push_back(domain_border(b.face.surface));
        b.exact_loops.push_back(circle2(Vec2(x, y), r));
        return ok_status();
      }};
}

MoldEntry dish_mold() {
  return {{"dish",
           "paraboloid z = (x^2 + y^2) / (2 rho) trimmed to the disc x^2 + y^2 <= R^2 (a trimmed "
           "face: the surface is the square patch |x|, |y| <= 1.25 R, u = x and v = y), with "
           "hole_r > 0 a central hole of that radius; normal towards +Z",
           {{"R", 30.0, "trim radius"},
            {"rho", 40.0, "radius of curvature at the apex"},
            {"hole_r", 0.0, "central hole radius (0: no hole)"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"R", "rho"}); !s) return s;
            if (!(v["hole_r"] >= 0.0 && v["hole_r"] < v["R"]))
              return Error{ErrorCode::kBuiltinDishHole};
            b.face.surface = paraboloid_patch(kDishDomainMargin * v["R"], v["rho"]);
            b.natural_outer = false;
            b.exact_loops.push_back(circle2(Vec2(0, 0), v["R"]));
            if (v["hole_r"] > 0.0) b.exact_loops.push_back(circle2(Vec2(0, 0), v["hole_r"]));
            return ok_status();
          }};
}

MoldEntry saddle_mold() {
  return {{"saddle",
           "hyperbolic paraboloid z = (x^2 - y^2) / (2 rho) over [-size/2, size/2]^2, normal "
           "towards +Z",
           {{"size", 40.0, "edge length"}, {"rho", 20.0, "radius of curvature at the origin"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"size", "rho"}); !s) return s;
            b.face.surface = saddle_patch(v["size"], v["rho"]);
            return ok_status();
          }};
}

MoldEntry wave_mold() {
  return {{"wave",
           "bicubic free-form over [0, size]^2 with n x n poles at heights "
           "amplitude sin(2 pi x / wavelength) cos(2 pi y / wavelength), normal towards +Z",
           {{"size", 100.0, "edge length"},
            {"amplitude", 5.0, "pole height amplitude"},
            {"wavelength", 60.0, "wavelength"},
            {"n", 12.0, "poles per direction (>= 4)"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"size", "wavelength"}); !s) return s;
            if (auto s = v.integer("n", 4, kWaveMaxPoles); !s) return s;
            b.face.surface =
                wave_surface(v["size"], v["amplitude"], v["wavelength"], static_cast<int>(v["n"]));
            return ok_status();
          }};
}

MoldEntry torus_mold() {
  return {{"torus",
           "torus about Z with major radius R and tube radius r; tube angle t0..t1 (0 = outer "
           "equator, 90 = top), from the +X axis counter-clockwise by `angle`",
           {{"R", 30.0, "major radius"},
            {"r", 10.0, "tube radius"},
            {"t0", -90.0, "tube angle start"},
            {"t1", 90.0, "tube angle end"},
            {"angle", 90.0, "sector angle, degrees"}}},
          [](const BuiltinParams& v, const Tolerances&, BuiltinFace& b) -> Status {
            if (auto s = v.positive({"R", "r"}); !s) return s;
            if (!(v["r"] < v["R"])) return Error{ErrorCode::kBuiltinTorusTube};
            if (!(v["t1"] > v["t0"] && v["t1"] - v["t0"] <= 360.0))
              return Error{ErrorCode::kBuiltinTorusAngles};
            if (auto s = v.angle("angle"); !s) return s;
            b.face.surface = torus_patch(v["R"], v["r"], v.radians("t0"), v.radians("t1"), 0.0,
                                         v.radians("angle"));
            b.face.closed_v = v["angle"] == 360.0;
            b.face.closed_u = v["t1"] - v["t0"] == 360.0;
            return ok_status();
          }};
}

// The propeller blade: a bicubic B-spline sheet with knots clustered at the root and the tip
// (as a CAD blade export has them), trimmed by the blade's outline. Its surface is
// kBladeWidthChords maximum chords wide across the chord: it extends past the leading and
// trailing edges.
constexpr double kBladeWidthChords = 1.25;

// Clamped cubic knots on [0, 1] with `count` poles, the interior knots at the cosine spacing
// 0.5 - 0.5 cos(pi x), x uniform, blended with uniform spacing by `cluster` (0: uniform, 1:
// cosine): clustered at both ends, as a CAD export of a blade fitted through sections that
// crowd at the root and the tip has them.
std::vector<double> clustered_knots(int count, double cluster) {
  std::vector<double> k(4, 0.0);
  const int spans = count - 3;
  for (int i = 1; i < spans; ++i) {
    const double x = static_cast<double>(i) / spans;
    k.push_back((1.0 - cluster) * x + cluster * (0.5 - 0.5 * std::cos(kPi * x)));
  }
  k.insert(k.end(), 4, 1.0);
  return k;
}

// Greville abscissa of pole i of a cubic with knots k.
double greville3(const std::vector<double>& k, int i) {
  return (k[i + 1] + k[i + 2] + k[i + 3]) / 3.0;
}

// Pitch angle of the blade's sections at the root (degrees); the tip's is this less `twist`.
constexpr double kBladeRootPitchDeg = 65.0;

// The blade: a bicubic B-spline sheet along +X (span) over (u, v) in [0, 1]^2, nu x nv poles
// at the Greville abscissae of clustered knots, so that x = span * u exactly; across it
// (v) a cambered section of width kBladeWidthChords * chord, pitched by kBladeRootPitchDeg at
// the root, twisted by `twist` towards the tip (fastest at the root), skewed along -Y...+Y by
// `skew` * (x / span)^2. Normal on the convex side of the camber.
NurbsSurfaceData blade_patch(double span, double chord, double twist_deg, double camber,
                             double skew, int nu, int nv) {
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 3;
  s.count_u = nu;
  s.count_v = nv;
  s.knots_u = clustered_knots(nu, 1.0);
  s.knots_v = clustered_knots(nv, 0.5);
  const double w = kBladeWidthChords * chord;
  for (int i = 0; i < nu; ++i) {
    const double sg = greville3(s.knots_u, i);
    const double beta =
        detail::radians(kBladeRootPitchDeg) - detail::radians(twist_deg) * (2.0 * sg - sg * sg);
    for (int j = 0; j < nv; ++j) {
      const double t = greville3(s.knots_v, j);
      const double eta = (t - 0.5) * w, zeta = camber * w * 4.0 * t * (1.0 - t);
      s.poles.emplace_back(span * sg, eta * std::cos(beta) - zeta * std::sin(beta) + skew * sg * sg,
                           eta * std::sin(beta) + zeta * std::cos(beta));
    }
  }
  return s;
}

// A cubic Bezier curve in (u, v) through the four control points.
NurbsCurveData2 bezier2(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  NurbsCurveData2 k;
  k.degree = 3;
  k.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  k.poles = {a, b, c, d};
  return k;
}

// The blade's trim: the root cut at u = kBladeRootU, the tip's apex at u = kBladeTipU (both
// inside the domain [0, 1], so that the outline is a real trim, as a CAD blade face's is).
constexpr double kBladeRootU = 0.04;
constexpr double kBladeTipU = 0.985;

// The blade's outline in (u, v): the root cut (a line at u = kBladeRootU), the trailing edge
// and the leading edge (cubic Beziers, the chord widest at about a third of the span, arriving
// along u at the tip), and a rounded tip (half an ellipse, about round in 3D).
std::vector<NurbsCurveData2> blade_outline(double span, double chord) {
  const double w = kBladeWidthChords * chord;
  const double tip_half = 0.16;                // half the tip's chord, in v
  const double tip_len = tip_half * w / span;  // the tip's length in u: round in 3D
  const double u0 = kBladeRootU, u1 = kBladeTipU - tip_len, l = u1 - u0;
  const Vec2 le0(u0, 0.5 + 0.26), te0(u0, 0.5 - 0.22);
  const Vec2 le1(u1, 0.5 + tip_half), te1(u1, 0.5 - tip_half);
  NurbsCurveData2 tip = ellipse_arc(tip_len, tip_half, -0.5 * kPi, 0.5 * kPi);
  for (auto& p : tip.poles) p += Vec2(u1, 0.5);
  return {line2(le0, te0),
          bezier2(te0, Vec2(u0 + 0.3 * l, 0.5 - 0.40), Vec2(u0 + 0.7 * l, 0.5 - tip_half), te1),
          tip,
          bezier2(le1, Vec2(u0 + 0.7 * l, 0.5 + tip_half), Vec2(u0 + 0.3 * l, 0.5 + 0.44), le0)};
}

// Largest pole count per direction.
constexpr int kBladeMaxPoles = 2000;

Status make_blade(const BuiltinParams& v, const Tolerances&, BuiltinFace& b) {
  if (auto s = v.positive({"span", "chord"}); !s) return s;
  if (auto s = v.within("twist", -90.0, 90.0); !s) return s;
  if (auto s = v.within("camber", 0.0, 0.25); !s) return s;
  if (auto s = v.integer("nu", 8, kBladeMaxPoles); !s) return s;
  if (auto s = v.integer("nv", 4, kBladeMaxPoles); !s) return s;
  b.face.surface = blade_patch(v["span"], v["chord"], v["twist"], v["camber"], v["skew"],
                               static_cast<int>(v["nu"]), static_cast<int>(v["nv"]));
  b.natural_outer = false;
  b.exact_loops.push_back(blade_outline(v["span"], v["chord"]));
  return ok_status();
}

MoldEntry blade_mold() {
  return {{"blade",
           "propeller blade face along +X from x = 0 (a CAD blade export): a bicubic B-spline of "
           "nu x nv poles over (u, v) in [0, 1]^2 with knots clustered at the root and the tip, "
           "x = span * u; its sections cambered (camber * width, width 1.25 chord), pitched 65 "
           "degrees at the root and twisted by `twist` towards the tip, skewed along Y by skew * "
           "(x / span)^2; trimmed (not at the domain's border) by the blade outline: a root cut at "
           "x = 0.04 span, leading and trailing edges at most `chord` apart, a rounded tip at "
           "x = 0.985 span; normal on the convex side",
           {{"span", 240.0, "length along X of the surface"},
            {"chord", 50.0, "largest chord of the outline"},
            {"twist", 45.0, "twist from root to tip, degrees"},
            {"camber", 0.06, "camber height per section width"},
            {"skew", 30.0, "offset along Y of the tip"},
            {"nu", 242.0, "poles along the span (>= 8)"},
            {"nv", 13.0, "poles across the chord (>= 4)"}}},
          make_blade};
}

// Every built-in mold, in the order of the help texts.
const std::vector<MoldEntry>& mold_entries() {
  static const std::vector<MoldEntry> list = {
      sphere_octant_mold(), hemisphere_mold(), revolution_third_mold(),
      cylinder_mold(),      cone_mold(),       plane_mold(),
      plate_mold(),         dish_mold(),       saddle_mold(),
      wave_mold(),          torus_mold(),      blade_mold()};
  return list;
}

}  // namespace

const std::vector<BuiltinInfo>& builtin_molds() {
  static const std::vector<BuiltinInfo> list = detail::infos_of(mold_entries());
  return list;
}

Result<BuiltinFace> builtin_face(const std::string& name,
                                 const std::map<std::string, double>& params,
                                 const Tolerances& tol) {
  auto v = BuiltinParams::resolve(builtin_molds(), "mold", name, params);
  if (!v) return v.error();
  BuiltinFace b;
  b.face.name = name;
  for (const MoldEntry& e : mold_entries())
    if (e.info.name == name)
      if (auto st = e.make(*v, tol, b); !st) return st.error();
  if (auto st = detail::sample_trims(b, tol); !st)
    return Error{ErrorCode::kBuiltinMold, {}, {name}}.because(st.error());
  return b;
}

Result<FaceData> builtin_mold(const std::string& name,
                              const std::map<std::string, double>& params) {
  auto b = builtin_face(name, params);
  if (!b) return b.error();
  return std::move(b->face);
}

}  // namespace plyfit
