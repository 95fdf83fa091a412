#pragma once
// Colour helpers shared by the renderer and its tests: the sRGB transfer curve, the
// legend-free ramp used by color_by = speed | height (viridis: perceptually uniform,
// readable by colour-blind viewers and in greyscale print), and the blackbody ramp of
// color_by = temperature (black, red, orange, yellow, white: what hot matter looks like,
// with lightness rising evenly).
// \see van der Walt & Smith, "A Better Default Colormap for Matplotlib", SciPy 2015.
// \see Moreland, "Why We Use Bad Color Maps and What You Can Do About It", Electronic
//      Imaging 2016 (the "black body" map: black, (178, 34, 34), (227, 105, 5),
//      (238, 210, 20), white at 0, 0.39, 0.58, 0.84, 1, interpolated in CIELAB, so that
//      L* / 100 equals the position).

#include <array>

#include "vec3.h"

namespace globular {

inline constexpr int kRampStops = 11;

using RampStops = std::array<Vec3, kRampStops>;

/// The viridis ramp's stops in sRGB, evenly spaced over [0, 1].
const RampStops& rampStops();
/// The blackbody ramp's stops in sRGB, evenly spaced over [0, 1].
const RampStops& blackbodyStops();

/// The ramp of @p stops at @p t (clamped to [0, 1]; NaN gives the start), interpolated
/// between stops in sRGB, as the shaders do.
Vec3 rampColor(const RampStops& stops, double t);
/// Viridis at @p t.
inline Vec3 rampColor(double t) { return rampColor(rampStops(), t); }
/// The blackbody ramp at @p t.
inline Vec3 blackbodyColor(double t) { return rampColor(blackbodyStops(), t); }

double srgbToLinear(double c);  ///< display value in [0, 1] -> linear light
double linearToSrgb(double c);  ///< linear light, clamped to [0, 1] -> display value
Vec3 srgbToLinear(Vec3 c);

}  // namespace globular
