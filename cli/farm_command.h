#pragma once
// `globular farm`: sends a shot's stages to a Slurm cluster (farm_scripts.h), reports its
// progress and resubmits what failed. Slurm's commands (sbatch, squeue, sacct, scancel)
// run as programs; when one is missing or fails, the error names it and what it answered.

#include <filesystem>
#include <string>
#include <vector>

#include "farm_scripts.h"

namespace globular {

class Reporter;

struct FarmOptions {
    std::string scene;                   ///< scene file (required to submit)
    std::filesystem::path outDir;        ///< DIR (required)
    std::vector<std::string> overrides;  ///< --set KEY=VALUE
    int chunk = 10;
    int maxRunning = 0;
    std::string partition, account, timeLimit;
    bool dryRun = false;
    bool status = false;    ///< --status DIR
    bool resubmit = false;  ///< --resubmit DIR
};

/// What a program answered.
struct ProgramResult {
    int status = 0;  ///< exit status; 128 + signal when killed by one
    std::string out, err;
};

/// Runs @p program (looked up on PATH) with @p args and waits for it.
/// @throw Error naming the program when it is not on PATH or cannot be started.
ProgramResult runProgram(const std::string& program, const std::vector<std::string>& args);

/// Submits, prints (dry run), reports or resubmits; text for the user goes to stdout.
/// @throw SceneError for bad options or scene; Error naming the Slurm command and its
///        answer when one fails.
void runFarm(const FarmOptions& options, Reporter& reporter);

}  // namespace globular
