#pragma once
// The simulation stage: runs a scene frame by frame and writes, per frame, the globule
// cache (VDB, optionally PLY), a row of stats.csv and a checkpoint for --resume.

#include <cstdint>
#include <string>

#include "simulation.h"
#include "simulation_settings.h"
#include "stage_context.h"

namespace globular {

struct SimStageOptions {
    OutputSettings output;
    bool resume = false;            ///< continue from DIR/state.bin
    uint64_t sceneFingerprint = 0;  ///< of the resolved scene; resume checks it
};

/// Bytes of memory a run of @p globules needs at its peak (state, neighbour grid,
/// cache being written), for refusing impossible scenes up front.
std::size_t estimateSimulationBytes(std::size_t globules);

/// Simulates frames 1..ctx.lastFrame (frame 1 is the initial state).
/// @throw ResourceError when the estimate exceeds the machine's memory;
///        SimulationError on an explosion (frames written before it stay intact);
///        IoError when an output cannot be written or a resume is impossible.
void runSimStage(const SimulationSetup& setup, const SimStageOptions& options,
                 const StageContext& ctx);

}  // namespace globular
