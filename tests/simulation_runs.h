#pragma once
// Test helper: a simulation run to a frame on a given number of threads, for checks that
// results do not depend on the thread count and that a resumed run continues bit for bit.

#include <tbb/global_control.h>

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

}  // namespace globular
