#pragma once
// The pictures' shear colour scale: a viridis-like ramp from 0 to a round top, with its ticks.

#include <plyfit/kernel/drape.hpp>

#include <string>

namespace plyfit::exporters::render {

/// An RGB colour.
struct Rgb {
  double r = 0, g = 0, b = 0;  ///< 0..1
  /// "#rrggbb".
  std::string hex() const;
  /// This colour scaled towards black by `f` (1 = unchanged).
  Rgb shaded(double f) const;
  /// This sRGB colour in linear light (the sRGB transfer function undone): what glTF's vertex
  /// colours and material factors hold, so that a viewer shows the pictures' colours.
  Rgb linear() const;
};

/// The shear colour ramp (viridis-like, dark blue at 0, yellow at the top): t in [0, 1], clamped.
Rgb shear_colour(double t);

/// Colour of cells without a shear value.
inline Rgb no_shear_colour() {
  return {0.75, 0.75, 0.75};
}

/// The shear colour scale of a drape: its top (radians) and the step of its ticks (degrees), a
/// round step with at most kMaxTicks intervals.
struct ShearScale {
  double top = 0.0;
  double step_deg = 5.0;
  /// The colour of a cell of shear `shear` (radians; negative: no shear value).
  Rgb colour(double shear) const;
};
ShearScale shear_scale(const DrapeResult& r);
constexpr double kMaxTicks = 6.0;

}  // namespace plyfit::exporters::render
