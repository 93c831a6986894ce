#include <plyfit/kernel/analytic_surfaces.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include "builtin_params.hpp"

#include <cmath>
#include <sstream>

namespace plyfit {

namespace {
constexpr double kPi = 3.14159265358979323846;
double rad(double deg) {
  return deg * kPi / 180.0;
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
       "when angle = 360",
       {{"R", 10.0, "radius"}, {"H", 20.0, "height"}, {"angle", 90.0, "sector angle, degrees"}}},
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
  };
  return list;
}

Result<FaceData> builtin_mold(const std::string& name,
                              const std::map<std::string, double>& params) {
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
  FaceData fd;
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
  }
  return fd;
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
