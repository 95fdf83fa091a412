#include "color_ramp.h"

#include <algorithm>
#include <cmath>

namespace globular {

const std::array<Vec3, kRampStops>& rampStops() {
    // matplotlib's viridis sampled at 0, 0.1, ..., 1.
    static const std::array<Vec3, kRampStops> stops = {{
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

Vec3 rampColor(double t) {
    const auto& stops = rampStops();
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
