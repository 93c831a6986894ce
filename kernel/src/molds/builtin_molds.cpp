#include <plyfit/kernel/builtin_molds.hpp>
#include "geometry/analytic_surfaces.hpp"

#include "molds/builtin_params.hpp"
#include "surface/face.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace plyfit {

namespace {
constexpr double kPi = 3.14159265358979323846;
/// The dish's square domain reaches this many times its trim radius from the axis (the
/// surface extends past the trim so that the trim is a real one, not the natural boundary).
constexpr double kDishDomainMargin = 1.25;
/// Trim polylines: a chord is halved at most this many times (2^20 pieces of a knot span is
/// far below any tolerance reachable in double precision).
constexpr int kMaxTrimRefineDepth = 20;
/// Interior fractions of a trim chord where its distance from the curve is measured.
constexpr double kTrimChordFractions[3] = {0.25, 0.5, 0.75};

double rad(double deg) {
  return deg * kPi / 180.0;
}

// A straight segment from a to b in (u, v), as a degree-1 curve.
NurbsCurveData2 line2(const Vec2& a, const Vec2& b) {
  NurbsCurveData2 c;
  c.degree = 1;
  c.knots = {0.0, 0.0, 1.0, 1.0};
  c.poles = {a, b};
  return c;
}

// The closed polygon through `corners` as degree-1 curves.
std::vector<NurbsCurveData2> polygon2(const std::vector<Vec2>& corners) {
  std::vector<NurbsCurveData2> loop;
  for (size_t k = 0; k < corners.size(); ++k)
    loop.push_back(line2(corners[k], corners[(k + 1) % corners.size()]));
  return loop;
}

// The full circle of `radius` about `centre` in (u, v), exact (rational quadratic).
std::vector<NurbsCurveData2> circle2(const Vec2& centre, double radius) {
  NurbsCurveData2 c = circle_arc(radius, 0.0, 2 * kPi);
  for (auto& p : c.poles) p += centre;
  return {c};
}

// The border of a surface's domain, counter-clockwise in (u, v).
std::vector<NurbsCurveData2> domain_border(const NurbsSurfaceData& s) {
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  return polygon2({Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)});
}

// Samples the curves of one loop as a polyline whose chords' surface images lie within tol3d of
// the surface images of the curves (checked at interior fractions, chords halved until they do).
Result<TrimLoop> sample_loop(const NurbsSurface& surface,
                             const std::vector<NurbsCurveData2>& curves, double tol3d) {
  TrimLoop loop;
  for (const auto& data : curves) {
    auto curve = NurbsCurve2::create(data);
    if (!curve) return Error{"invalid trim curve"}.because(curve.error());
    const auto at = [&](double t) { return Vec2(curve->point(t)); };
    const auto on_surface = [&](const Vec2& uv) { return surface.point(uv.x(), uv.y()); };
    std::vector<double> ts;  // the distinct knots inside the domain, ends included
    for (double k : data.knots)
      if (k >= curve->t0() && k <= curve->t1() && (ts.empty() || k > ts.back())) ts.push_back(k);
    const std::function<void(double, const Vec2&, double, const Vec2&, int)> refine =
        [&](double t0, const Vec2& p0, double t1, const Vec2& p1, int depth) {
          double err = 0.0;
          for (double f : kTrimChordFractions)
            err = std::max(
                err, (on_surface(at(t0 + f * (t1 - t0))) - on_surface(p0 + f * (p1 - p0))).norm());
          if (err > tol3d && depth < kMaxTrimRefineDepth) {
            const double tm = 0.5 * (t0 + t1);
            const Vec2 pm = at(tm);
            refine(t0, p0, tm, pm, depth + 1);
            refine(tm, pm, t1, p1, depth + 1);
          } else {
            loop.points.push_back(p1);
          }
        };
    Vec2 p = at(ts.front());
    if (loop.points.empty()) loop.points.push_back(p);
    for (size_t k = 0; k + 1 < ts.size(); ++k) {
      const Vec2 q = at(ts[k + 1]);
      refine(ts[k], p, ts[k + 1], q, 0);
      p = q;
    }
  }
  loop.points.pop_back();  // the loop's end is its start
  if (loop.points.size() < 3) return Error{"a trim loop has fewer than three points"};
  return loop;
}

// Fills face.loops from the exact loops: sampled once against the untrimmed face's size, then
// again against the trimmed face's (smaller) size.
Status sample_loops(BuiltinFace& b, const Tolerances& tol) {
  if (b.exact_loops.empty()) return ok_status();
  auto surface = NurbsSurface::create(b.face.surface, tol);
  if (!surface) return surface.error();
  FaceData probe = b.face;
  probe.area = 1.0;  // only the size is needed here: no area integration (a second or more on
                     // a trimmed face of many spans)
  for (int pass = 0; pass < 2; ++pass) {
    auto face = Face::create(probe, tol);
    if (!face) return face.error();
    const double tol3d = tol.trim_chord_rel * face->size();
    probe.loops.clear();
    for (const auto& curves : b.exact_loops) {
      auto loop = sample_loop(*surface, curves, tol3d);
      if (!loop) return loop.error();
      probe.loops.push_back(std::move(loop).value());
    }
  }
  b.face.loops = std::move(probe.loops);
  return ok_status();
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

// The blade's trim: the root cut at u = kBladeRootU, the tip's apex at u = kBladeTipU (both
// inside the domain [0, 1], so that the outline is a real trim, as a CAD blade face's is).
constexpr double kBladeRootU = 0.04;
constexpr double kBladeTipU = 0.985;
// Width of the blade's surface across the chord, in maximum chords: the surface extends past
// the leading and trailing edges.
constexpr double kBladeWidthChords = 1.25;
// Pitch angle of the blade's sections at the root (degrees); the tip's is this less `twist`.
constexpr double kBladeRootPitchDeg = 65.0;

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
    const double beta = rad(kBladeRootPitchDeg) - rad(twist_deg) * (2.0 * sg - sg * sg);
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
}  // namespace

const std::vector<BuiltinInfo>& builtin_molds() {
  // The revolution-third profile passes exactly through the paper's (r, z) = (13.75, 7.5).
  static const double kRevolutionHeight = 7.5 / std::sqrt(1.0 - (13.75 / 20.0) * (13.75 / 20.0));
  static const std::vector<BuiltinInfo> list = {
      {"sphere-octant",
       "first octant x, y, z >= 0 of the sphere of radius R about the origin, as an exact "
       "rational NURBS with its pole at (0, 0, R)",
       {{"R", 20.0, "radius"}}},
      {"hemisphere",
       "upper half z >= 0 of the sphere of radius R about the origin; closed around Z, pole "
       "at (0, 0, R)",
       {{"R", 1.0, "radius"}}},
      {"revolution-third",
       "sector from the +X axis counter-clockwise by `angle` of the surface of revolution "
       "about Z whose profile is the quarter ellipse r^2/a^2 + z^2/h^2 = 1 (r = a at z = 0, "
       "pole at z = h; h defaults to 10.33, through the paper's (13.75, 7.5))",
       {{"a", 20.0, "radial semi-axis"},
        {"h", kRevolutionHeight, "height (semi-axis along Z)"},
        {"angle", 120.0, "sector angle, degrees"}}},
      {"cylinder",
       "x^2 + y^2 = R^2, 0 <= z <= H, from the +X axis counter-clockwise by `angle`; closed "
       "when angle = 360; with window_angle > 0 a window (a hole bounded by two generators and "
       "two circles) of that angle and window_height about the middle (angle / 2, H / 2)",
       {{"R", 10.0, "radius"},
        {"H", 20.0, "height"},
        {"angle", 90.0, "sector angle, degrees"},
        {"window_angle", 0.0, "window angle, degrees (0: no window)"},
        {"window_height", 0.0, "window height"}}},
      {"cone",
       "cone frustum about Z with radius r0 at z = 0 and r1 at z = H, from the +X axis "
       "counter-clockwise by `angle` (r1 = 0 gives the apex)",
       {{"r0", 20.0, "radius at z = 0"},
        {"r1", 10.0, "radius at z = H"},
        {"H", 15.0, "height"},
        {"angle", 90.0, "sector angle, degrees"}}},
      {"plane",
       "rectangle [0, W] x [0, H] in the plane z = 0, normal +Z",
       {{"W", 100.0, "size along X"}, {"H", 100.0, "size along Y"}}},
      {"plate",
       "rectangle [0, W] x [0, H] in the plane z = 0, normal +Z, u = x and v = y; with hole_r > "
       "0 a circular hole of radius hole_r about (hole_x, hole_y)",
       {{"W", 100.0, "size along X"},
        {"H", 60.0, "size along Y"},
        {"hole_r", 0.0, "hole radius (0: no hole)"},
        {"hole_x", 50.0, "hole centre x"},
        {"hole_y", 30.0, "hole centre y"}}},
      {"dish",
       "paraboloid z = (x^2 + y^2) / (2 rho) trimmed to the disc x^2 + y^2 <= R^2 (a trimmed "
       "face: the surface is the square patch |x|, |y| <= 1.25 R, u = x and v = y), with "
       "hole_r > 0 a central hole of that radius; normal towards +Z",
       {{"R", 30.0, "trim radius"},
        {"rho", 40.0, "radius of curvature at the apex"},
        {"hole_r", 0.0, "central hole radius (0: no hole)"}}},
      {"saddle",
       "hyperbolic paraboloid z = (x^2 - y^2) / (2 rho) over [-size/2, size/2]^2, normal "
       "towards +Z",
       {{"size", 40.0, "edge length"}, {"rho", 20.0, "radius of curvature at the origin"}}},
      {"wave",
       "bicubic free-form over [0, size]^2 with n x n poles at heights "
       "amplitude sin(2 pi x / wavelength) cos(2 pi y / wavelength), normal towards +Z",
       {{"size", 100.0, "edge length"},
        {"amplitude", 5.0, "pole height amplitude"},
        {"wavelength", 60.0, "wavelength"},
        {"n", 12.0, "poles per direction (>= 4)"}}},
      {"torus",
       "torus about Z with major radius R and tube radius r; tube angle t0..t1 (0 = outer "
       "equator, 90 = top), from the +X axis counter-clockwise by `angle`",
       {{"R", 30.0, "major radius"},
        {"r", 10.0, "tube radius"},
        {"t0", -90.0, "tube angle start"},
        {"t1", 90.0, "tube angle end"},
        {"angle", 90.0, "sector angle, degrees"}}},
      {"blade",
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
  };
  return list;
}

Result<BuiltinFace> builtin_face(const std::string& name,
                                 const std::map<std::string, double>& params,
                                 const Tolerances& tol) {
  auto resolved = detail::builtin_params(builtin_molds(), "mold", name, params);
  if (!resolved) return resolved.error();
  std::map<std::string, double>& v = resolved->second;
  auto positive = [&](const char* k) -> Status {
    if (!(v[k] > 0.0))
      return Error{"parameter '" + std::string(k) + "' of '" + name + "' must be positive"};
    return ok_status();
  };
  auto angle = [&](const char* k) -> Status {
    if (!(v[k] > 0.0 && v[k] <= 360.0))
      return Error{"parameter '" + std::string(k) + "' of '" + name + "' must be in (0, 360]"};
    return ok_status();
  };
  BuiltinFace b;
  FaceData& fd = b.face;
  fd.name = name;
  if (name == "sphere-octant") {
    if (auto s = positive("R"); !s) return s.error();
    fd.surface = sphere_octant(v["R"]);
  } else if (name == "hemisphere") {
    if (auto s = positive("R"); !s) return s.error();
    fd.surface = sphere_patch(v["R"], 0.0, kPi / 2, 0.0, 2 * kPi);
    fd.closed_v = true;
  } else if (name == "revolution-third") {
    for (const char* k : {"a", "h"})
      if (auto s = positive(k); !s) return s.error();
    if (auto s = angle("angle"); !s) return s.error();
    fd.surface = revolve(ellipse_arc(v["a"], v["h"], kPi / 2, 0.0), 0.0, rad(v["angle"]));
    fd.closed_v = v["angle"] == 360.0;
  } else if (name == "cylinder") {
    for (const char* k : {"R", "H"})
      if (auto s = positive(k); !s) return s.error();
    if (auto s = angle("angle"); !s) return s.error();
    fd.surface = cylinder_patch(v["R"], 0.0, rad(v["angle"]), 0.0, v["H"]);
    fd.closed_v = v["angle"] == 360.0;
    if (v["window_angle"] != 0.0 || v["window_height"] != 0.0) {
      if (!(v["window_angle"] > 0.0 && v["window_angle"] < v["angle"] && v["window_height"] > 0.0 &&
            v["window_height"] < v["H"]))
        return Error{
            "the window of 'cylinder' needs 0 < window_angle < angle and 0 < "
            "window_height < H"};
      // The window's corners in (u, v): u runs along z, v around the axis; the v of an angle
      // is found by projecting the point at that angle onto the face.
      auto face = Face::create(fd, tol);
      if (!face) return face.error();
      const double r = v["R"], mid = rad(v["angle"]) / 2, half = rad(v["window_angle"]) / 2;
      const double z0 = (v["H"] - v["window_height"]) / 2, z1 = z0 + v["window_height"];
      auto uv_at = [&](double a, double z) {
        return face->project(Vec3(r * std::cos(a), r * std::sin(a), z)).at.uv;
      };
      const Vec2 c0 = uv_at(mid - half, z0), c1 = uv_at(mid + half, z1);
      b.exact_loops.push_back(domain_border(fd.surface));
      b.exact_loops.push_back(polygon2({c0, Vec2(c0.x(), c1.y()), c1, Vec2(c1.x(), c0.y())}));
    }
  } else if (name == "cone") {
    if (auto s = positive("H"); !s) return s.error();
    if (!(v["r0"] >= 0.0) || !(v["r1"] >= 0.0) || !(v["r0"] + v["r1"] > 0.0))
      return Error{"radii r0, r1 of 'cone' must be >= 0 and not both 0"};
    if (auto s = angle("angle"); !s) return s.error();
    fd.surface = cone_patch(v["r0"], v["r1"], 0.0, v["H"], 0.0, rad(v["angle"]));
    fd.closed_v = v["angle"] == 360.0;
  } else if (name == "plane") {
    for (const char* k : {"W", "H"})
      if (auto s = positive(k); !s) return s.error();
    fd.surface = plane_patch(Vec3::Zero(), Vec3(v["W"], 0, 0), Vec3(0, v["H"], 0));
  } else if (name == "plate") {
    for (const char* k : {"W", "H"})
      if (auto s = positive(k); !s) return s.error();
    fd.surface = plate_patch(v["W"], v["H"]);
    if (v["hole_r"] != 0.0) {
      const double r = v["hole_r"], x = v["hole_x"], y = v["hole_y"];
      if (!(r > 0.0 && x - r > 0.0 && x + r < v["W"] && y - r > 0.0 && y + r < v["H"]))
        return Error{"the hole of 'plate' (hole_r, hole_x, hole_y) must lie inside the plate"};
      b.exact_loops.push_back(domain_border(fd.surface));
      b.exact_loops.push_back(circle2(Vec2(x, y), r));
    }
  } else if (name == "dish") {
    for (const char* k : {"R", "rho"})
      if (auto s = positive(k); !s) return s.error();
    if (!(v["hole_r"] >= 0.0 && v["hole_r"] < v["R"]))
      return Error{"the hole radius hole_r of 'dish' must be in [0, R)"};
    fd.surface = paraboloid_patch(kDishDomainMargin * v["R"], v["rho"]);
    b.natural_outer = false;
    b.exact_loops.push_back(circle2(Vec2(0, 0), v["R"]));
    if (v["hole_r"] > 0.0) b.exact_loops.push_back(circle2(Vec2(0, 0), v["hole_r"]));
  } else if (name == "saddle") {
    for (const char* k : {"size", "rho"})
      if (auto s = positive(k); !s) return s.error();
    fd.surface = saddle_patch(v["size"], v["rho"]);
  } else if (name == "wave") {
    for (const char* k : {"size", "wavelength"})
      if (auto s = positive(k); !s) return s.error();
    if (!(v["n"] >= 4.0 && v["n"] <= 200.0 && v["n"] == std::floor(v["n"])))
      return Error{"parameter 'n' of 'wave' must be an integer from 4 to 200"};
    fd.surface = wave_surface(v["size"], v["amplitude"], v["wavelength"], static_cast<int>(v["n"]));
  } else if (name == "torus") {
    for (const char* k : {"R", "r"})
      if (auto s = positive(k); !s) return s.error();
    if (!(v["r"] < v["R"])) return Error{"tube radius r of 'torus' must be smaller than R"};
    if (!(v["t1"] > v["t0"] && v["t1"] - v["t0"] <= 360.0))
      return Error{"tube angles of 'torus' need t0 < t1 <= t0 + 360"};
    if (auto s = angle("angle"); !s) return s.error();
    fd.surface = torus_patch(v["R"], v["r"], rad(v["t0"]), rad(v["t1"]), 0.0, rad(v["angle"]));
    fd.closed_v = v["angle"] == 360.0;
    fd.closed_u = v["t1"] - v["t0"] == 360.0;
  } else if (name == "blade") {
    for (const char* k : {"span", "chord"})
      if (auto s = positive(k); !s) return s.error();
    if (!(std::abs(v["twist"]) <= 90.0))
      return Error{"parameter 'twist' of 'blade' must be in [-90, 90]"};
    if (!(v["camber"] >= 0.0 && v["camber"] <= 0.25))
      return Error{"parameter 'camber' of 'blade' must be in [0, 0.25]"};
    const auto count = [&](const char* k, double lo) {
      return v[k] >= lo && v[k] <= 2000.0 && v[k] == std::floor(v[k]);
    };
    if (!count("nu", 8.0) || !count("nv", 4.0))
      return Error{"parameters 'nu', 'nv' of 'blade' must be integers from 8 (nu), 4 (nv) to 2000"};
    fd.surface = blade_patch(v["span"], v["chord"], v["twist"], v["camber"], v["skew"],
                             static_cast<int>(v["nu"]), static_cast<int>(v["nv"]));
    b.natural_outer = false;
    b.exact_loops.push_back(blade_outline(v["span"], v["chord"]));
  }
  if (auto st = sample_loops(b, tol); !st)
    return Error{"built-in mold '" + name + "'"}.because(st.error());
  return b;
}

Result<FaceData> builtin_mold(const std::string& name,
                              const std::map<std::string, double>& params) {
  auto b = builtin_face(name, params);
  if (!b) return b.error();
  return std::move(b->face);
}

Result<std::pair<std::string, std::map<std::string, double>>> parse_builtin_spec(
    const std::string& spec) {
  const auto colon = spec.find(':');
  std::pair<std::string, std::map<std::string, double>> out;
  out.first = spec.substr(0, colon);
  if (out.first.empty()) return Error{"built-in mold name missing in 'builtin:" + spec + "'"};
  if (colon == std::string::npos) return out;
  std::stringstream ss(spec.substr(colon + 1));
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      return Error{"built-in mold parameter '" + item + "' is not key=value"};
    const std::string key = item.substr(0, eq), val = item.substr(eq + 1);
    try {
      std::size_t used = 0;
      const double x = std::stod(val, &used);
      if (used != val.size() || !std::isfinite(x)) throw std::invalid_argument(val);
      out.second[key] = x;
    } catch (const std::exception&) {
      return Error{"built-in mold parameter '" + key + "' has a malformed value '" + val + "'"};
    }
  }
  return out;
}

}  // namespace plyfit
