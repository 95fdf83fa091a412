#include "color_ramp.h"

#include <algorithm>
#include <cmath>

namespace globular {

const RampStops& rampStops() {
    // matplotlib's viridis sampled at 0, 0.1, ..., 1.
    static const RampStops stops = {{
        {0.267, 0.005, 0.329},
        {0.283, 0.141, 0.458},
        {0.254, 0.265, 0.530},
        {0.207, 0.372, 0.553},
        {0.164, 0.471, 0.558},
        {0.128, 0.567, 0.551},
        {0.135, 0.659, 0.518},
        {0.267, 0.749, 0.441},
        {0.478, 0.821, 0.318},
        {0.741, 0.873, 0.150},
        {0.993, 0.906, 0.144},
    }};
    return stops;
}

const RampStops& blackbodyStops() {
    // Moreland's black body map sampled at 0, 0.1, ..., 1 (CIELAB interpolation of its
    // five control points, converted back to sRGB).
    static const RampStops stops = {{
        {0.000, 0.000, 0.000},
        {0.189, 0.074, 0.053},
        {0.353, 0.105, 0.085},
        {0.530, 0.125, 0.110},
        {0.708, 0.153, 0.131},
        {0.809, 0.305, 0.095},
        {0.896, 0.447, 0.021},
        {0.919, 0.610, 0.037},
        {0.932, 0.763, 0.066},
        {0.984, 0.887, 0.495},
        {1.000, 1.000, 1.000},
    }};
    return stops;
}

Vec3 rampColor(const RampStops& stops, double t) {
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (kRampStops - 1);
    const int i = std::min(int(x), kRampStops - 2);
    const double f = x - i;
    return stops[i] * (1 - f) + stops[i + 1] * f;
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linearToSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

Vec3 srgbToLinear(Vec3 c) { return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)}; }

}  // namespace globular
