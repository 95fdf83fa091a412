#pragma once
// What the force computation hands the integrator for each globule.

#include <cstddef>
#include <vector>

namespace globular {

struct Accelerations {
    std::vector<float> x, y, z;  ///< world units / s^2
    /// Thermal scenes: the rate of change of each globule's temperature, degrees / s
    /// (empty otherwise). The pair loop leaves the heat flowing in there (heat / s); the
    /// sources (thermal_sources.h) turn it into a rate.
    std::vector<float> heat;
    void resize(std::size_t n) {
        x.resize(n);
        y.resize(n);
        z.resize(n);
    }
};

}  // namespace globular
