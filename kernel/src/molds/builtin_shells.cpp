// The built-in shells: each one's description, parameters and faces sewn along shared edges.
#include <plyfit/kernel/builtin_molds.hpp>

#include "geometry/analytic_surfaces.hpp"
#include "molds/builtin.hpp"

#include <array>
#include <cmath>

namespace plyfit {

namespace {

using detail::BuiltinParams;

constexpr std::int32_t kFree = TrimLoop::kFreeEdge;
// The most faces cylinder-split splits into.
constexpr int kMaxParts = 64;

// A built-in shell: its description and parameters, and how its faces are made.
struct ShellEntry {
  BuiltinInfo info;
  Status (*make)(const BuiltinParams& v, ShellData& sd);
};

// The face of `surface` bounded by its natural boundary, as an explicit loop (the domain's
// corners counter-clockwise in (u, v)) whose sides carry shared edges: side 0 is v = v0
// (from u0 to u1), side 1 u = u1, side 2 v = v1, side 3 u = u0.
FaceData patch(NurbsSurfaceData surface, std::array<std::int32_t, 4> sides, std::string name) {
  FaceData fd;
  TrimLoop loop;
  const auto corners = detail::domain_corners(surface);
  loop.points.assign(corners.begin(), corners.end());
  loop.edges.assign(sides.begin(), sides.end());
  fd.surface = std::move(surface);
  fd.loops.push_back(std::move(loop));
  fd.name = std::move(name);
  return fd;
}

ShellEntry sphere_8() {
  return {
      {"sphere-8",
       "the sphere of radius R about the origin as 8 octant faces (each an exact rational "
       "NURBS with a pole), sewn along the equator and the meridians at 0, 90, 180, 270 degrees",
       {{"R", 20.0, "radius"}}},
      [](const BuiltinParams& v, ShellData& sd) -> Status {
        if (auto s = v.positive({"R"}); !s) return s;
        // Edges: meridian q at longitude 90 q in hemisphere h is edge 4 h + q (between
        // quadrants q - 1 and q); the equator of quadrant q is edge 8 + q. A sphere patch's
        // u runs from its upper latitude down to its lower one, v along the longitude.
        for (int h = 0; h < 2; ++h)
          for (int q = 0; q < 4; ++q) {
            const double lat0 = h == 0 ? -kPi / 2 : 0.0, lat1 = h == 0 ? 0.0 : kPi / 2;
            const std::int32_t left = 4 * h + q, right = 4 * h + (q + 1) % 4, equator = 8 + q;
            // Side 1 (u = u1) is the lower latitude, side 3 (u = u0) the upper one.
            const std::int32_t lower = h == 0 ? kFree : equator, upper = h == 0 ? equator : kFree;
            sd.faces.push_back(
                patch(sphere_patch(v["R"], lat0, lat1, q * kPi / 2, (q + 1) * kPi / 2),
                      {left, lower, right, upper},
                      std::string(h == 0 ? "south" : "north") + "-" + std::to_string(q)));
          }
        sd.edge_count = 12;
        return ok_status();
      }};
}

ShellEntry cylinder_split() {
  return {{"cylinder-split",
           "x^2 + y^2 = R^2, 0 <= z <= H, from the +X axis counter-clockwise by `angle`, split "
           "along generators into `parts` equal faces; closed (a tube) when angle = 360",
           {{"R", 10.0, "radius"},
            {"H", 20.0, "height"},
            {"angle", 180.0, "sector angle, degrees"},
            {"parts", 2.0, "faces (>= 2)"}}},
          [](const BuiltinParams& v, ShellData& sd) -> Status {
            if (auto s = v.positive({"R", "H"}); !s) return s;
            if (auto s = v.angle("angle"); !s) return s;
            if (auto s = v.integer("parts", 2, kMaxParts); !s) return s;
            const int n = static_cast<int>(v["parts"]);
            const bool closed = v["angle"] == 360.0;
            // Generator k (between parts k - 1 and k) is edge k - 1; when closed, the generator
            // at 0 = 360 degrees is edge n - 1. A cylinder patch's u runs from the top down.
            for (int k = 0; k < n; ++k) {
              const double a0 = v.radians("angle") * k / n, a1 = v.radians("angle") * (k + 1) / n;
              const std::int32_t left = k > 0 ? k - 1 : (closed ? n - 1 : kFree);
              const std::int32_t right = k + 1 < n ? k : (closed ? n - 1 : kFree);
              sd.faces.push_back(patch(cylinder_patch(v["R"], a0, a1, 0.0, v["H"]),
                                       {left, kFree, right, kFree}, "part-" + std::to_string(k)));
            }
            sd.edge_count = closed ? n : n - 1;
            return ok_status();
          }};
}

ShellEntry flange_fillet_wall() {
  return {{"flange-fillet-wall",
           "an L-shaped mold, developable: a flange in the plane z = 0 (-L <= x <= 0), a fillet "
           "of radius r about the line x = 0, z = -r, and a wall in the plane x = r down to "
           "z = -r - Hw; 0 <= y <= W; normals on the convex side (+Z, outward, +X)",
           {{"L", 40.0, "flange length"},
            {"r", 10.0, "fillet radius"},
            {"Hw", 40.0, "wall height"},
            {"W", 60.0, "width along Y"}}},
          [](const BuiltinParams& v, ShellData& sd) -> Status {
            if (auto s = v.positive({"L", "r", "Hw", "W"}); !s) return s;
            const double L = v["L"], r = v["r"], Hw = v["Hw"], W = v["W"];
            // Flange: u along +X to the fillet (side 1, u = 1, is edge 0).
            sd.faces.push_back(patch(plane_patch(Vec3(-L, 0, 0), Vec3(L, 0, 0), Vec3(0, W, 0)),
                                     {kFree, 0, kFree, kFree}, "flange"));
            // Fillet: the quarter circle about (0, y, -r) from the top (u = u0, edge 0) to the
            // side (u = u1, edge 1), extruded along +Y.
            NurbsCurveData2 arc = circle_arc(r, kPi / 2, 0.0);
            NurbsCurveData3 prof;
            prof.degree = arc.degree;
            prof.knots = arc.knots;
            prof.weights = arc.weights;
            for (const Vec2& p : arc.poles) prof.poles.push_back(Vec3(p.x(), 0.0, p.y() - r));
            sd.faces.push_back(patch(extrude(prof, Vec3(0, W, 0)), {kFree, 1, kFree, 0}, "fillet"));
            // Wall: u down from the fillet (side 3, u = 0, is edge 1).
            sd.faces.push_back(patch(plane_patch(Vec3(r, 0, -r), Vec3(0, 0, -Hw), Vec3(0, W, 0)),
                                     {kFree, kFree, kFree, 1}, "wall"));
            sd.edge_count = 2;
            return ok_status();
          }};
}

// Every built-in shell, in the order of the help texts.
const std::vector<ShellEntry>& shell_entries() {
  static const std::vector<ShellEntry> list = {sphere_8(), cylinder_split(), flange_fillet_wall()};
  return list;
}

}  // namespace

const std::vector<BuiltinInfo>& builtin_shells() {
  static const std::vector<BuiltinInfo> list = detail::infos_of(shell_entries());
  return list;
}

bool is_builtin_shell(const std::string& name) {
  for (const auto& b : builtin_shells())
    if (b.name == name) return true;
  return false;
}

Result<ShellData> builtin_shell(const std::string& name,
                                const std::map<std::string, double>& params) {
  auto v = BuiltinParams::resolve(builtin_shells(), "shell", name, params);
  if (!v) return v.error();
  ShellData sd;
  for (const ShellEntry& e : shell_entries())
    if (e.info.name == name)
      if (auto st = e.make(*v, sd); !st) return st.error();
  return sd;
}

}  // namespace plyfit
