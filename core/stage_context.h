#pragma once
// What every stage (sim, surface, render) is given by the CLI: where to write, which
// frames, and how to talk to the user.

#include <filesystem>
#include <string>

#include "reporter.h"

namespace globular {

struct StageContext {
    std::filesystem::path outDir;  ///< the run's output directory (DESIGN.md layout)
    int firstFrame = 1;            ///< inclusive, 1 = initial state
    int lastFrame = 1;             ///< inclusive
    Reporter* reporter = nullptr;  ///< never null when a stage runs

    Reporter& report() const { return *reporter; }
    /// What every stage does first: removes the temporaries a killed run left in outDir
    /// (removeStaleTemporaries) and says how many, as "@p stage: removed N ...".
    void sweepTemporaries(const std::string& stage) const;
};

}  // namespace globular
