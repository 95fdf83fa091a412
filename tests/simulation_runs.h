#pragma once
// Test helpers: a simulation run to a frame on a given number of threads, for checks that
// results do not depend on the thread count and that a resumed run continues bit for bit;
// the momentum of a state, for conservation checks.

#include <tbb/global_control.h>

#include <utility>

#include "reporter.h"
#include "simulation.h"

namespace globular {

/// The state of @p setup after frames 2..@p frames on @p threads threads.
inline SimulationState stateAfter(const SimulationSetup& setup, int threads, int frames) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= frames; ++f) sim.advanceFrame(f, quiet);
    return sim.saveState();
}

/// The total momentum of @p g, and the sum of its globules' momenta' lengths (the scale
/// a conservation error is measured against).
inline std::pair<Vec3, double> momentumOf(const Globules& g) {
    Vec3 p{0, 0, 0};
    double scale = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        p = p + double(g.mass[i]) * g.velocity(i);
        scale += g.mass[i] * length(g.velocity(i));
    }
    return {p, scale};
}

}  // namespace globular
