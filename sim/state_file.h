#pragma once
// The checkpoint written after every simulated frame (DIR/state.bin): the exact
// SimulationState in native binary, so `--resume` continues bit for bit. It carries a
// fingerprint of the resolved scene so a run is never resumed with other parameters.

#include <cstdint>
#include <filesystem>
#include <string>

#include "simulation.h"

namespace globular {

struct Checkpoint {
    int frame = 0;                 ///< last frame whose outputs are complete
    uint64_t sceneFingerprint = 0; ///< of the resolved scene text
    SimulationState state;
};

/// FNV-1a of @p text: identifies a resolved scene.
uint64_t fingerprint(const std::string& text);

/// Written atomically. @throw IoError naming @p path.
void writeCheckpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);
/// @throw IoError naming @p path when missing, truncated or not a checkpoint.
Checkpoint readCheckpoint(const std::filesystem::path& path);

}  // namespace globular
