#pragma once
// Colour helpers shared by the renderer and its tests: the sRGB transfer curve, and the
// legend-free ramp used by color_by = speed | height (viridis: perceptually uniform,
// readable by colour-blind viewers and in greyscale print).
// \see van der Walt & Smith, "A Better Default Colormap for Matplotlib", SciPy 2015.

#include <array>

#include "vec3.h"

namespace globular {

inline constexpr int kRampStops = 11;

/// The ramp's stops in sRGB, evenly spaced over [0, 1].
const std::array<Vec3, kRampStops>& rampStops();

/// The ramp at @p t (clamped to [0, 1]), interpolated between stops in sRGB.
Vec3 rampColor(double t);

double srgbToLinear(double c);  ///< display value in [0, 1] -> linear light
double linearToSrgb(double c);  ///< linear light, clamped to [0, 1] -> display value
Vec3 srgbToLinear(Vec3 c);

}  // namespace globular
