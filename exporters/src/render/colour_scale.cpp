#include "render/colour_scale.hpp"

#include "net_util.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace plyfit::exporters::render {

std::string Rgb::hex() const {
  static const char* kDigits = "0123456789abcdef";
  std::string s = "#";
  for (double v : {r, g, b}) {
    const int x = static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    s += kDigits[x / 16];
    s += kDigits[x % 16];
  }
  return s;
}

Rgb Rgb::shaded(double f) const {
  return {r * f, g * f, b * f};
}

Rgb Rgb::linear() const {
  // The sRGB transfer function (IEC 61966-2-1): a linear toe, then a 2.4 power.
  constexpr double kToe = 0.04045, kToeSlope = 12.92, kOffset = 0.055, kGamma = 2.4;
  auto channel = [&](double v) {
    v = std::clamp(v, 0.0, 1.0);
    return v <= kToe ? v / kToeSlope : std::pow((v + kOffset) / (1.0 + kOffset), kGamma);
  };
  return {channel(r), channel(g), channel(b)};
}

Rgb shear_colour(double t) {
  // Viridis sampled at nine points, linearly interpolated.
  static constexpr std::array<std::array<double, 3>, 9> kStops = {{{0.267, 0.005, 0.329},
                                                                   {0.283, 0.141, 0.458},
                                                                   {0.254, 0.265, 0.530},
                                                                   {0.207, 0.372, 0.553},
                                                                   {0.164, 0.471, 0.558},
                                                                   {0.128, 0.567, 0.551},
                                                                   {0.135, 0.659, 0.518},
                                                                   {0.478, 0.821, 0.318},
                                                                   {0.993, 0.906, 0.144}}};
  if (!std::isfinite(t)) t = 0.0;
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(k);
  Rgb c;
  c.r = kStops[k][0] + f * (kStops[k + 1][0] - kStops[k][0]);
  c.g = kStops[k][1] + f * (kStops[k + 1][1] - kStops[k][1]);
  c.b = kStops[k][2] + f * (kStops[k + 1][2] - kStops[k][2]);
  return c;
}

Rgb ShearScale::colour(double shear) const {
  return shear < 0 ? no_shear_colour() : shear_colour(shear / top);
}

ShearScale shear_scale(const DrapeResult& r) {
  double top = 0.0;
  for (const DrapeNode& n : r.nodes) top = std::max(top, detail::node_shear(n));
  const double m = top * detail::kRadToDeg;
  ShearScale s;
  for (const double step : {1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0}) {
    s.step_deg = step;
    const double t = std::max(step, std::ceil(m / step) * step);
    s.top = t / detail::kRadToDeg;
    if (t / step <= kMaxTicks) break;
  }
  return s;
}

}  // namespace plyfit::exporters::render
