#include "sim_stage.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "atomic_file.h"
#include "collider_poses.h"
#include "errors.h"
#include "frame_paths.h"
#include "frame_stats.h"
#include "globule_cache.h"
#include "simd_path.h"
#include "state_file.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// The run's summary of adaptive steps: what they saved against the fixed step a run
/// would need to be as stable throughout, the shortest adaptive step taken.
std::string adaptiveSummary(int64_t steps, double seconds, double shortest) {
    const double mean = seconds / double(std::max<int64_t>(steps, 1));
    if (!std::isfinite(shortest)) shortest = mean;  // every step ended a frame
    const double fixed = std::ceil(seconds / shortest - 1e-9);
    std::ostringstream out;
    out.precision(3);
    out << "sim: adaptive time steps: " << steps << " steps (mean " << mean << " s, shortest "
        << shortest << " s); a fixed step as short as the shortest would take " << fixed
        << " (" << 100.0 * (fixed - double(steps)) / fixed << "% saved)";
    return out.str();
}

std::size_t physicalMemoryBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
}

std::string statsText(const std::vector<FrameStats>& rows) {
    std::string text = statsCsvHeader() + "\n";
    for (const auto& row : rows) text += statsCsvRow(row) + "\n";
    return text;
}

/// Everything a finished frame leaves on disk. The checkpoint goes last: when it names
/// frame F, every output of frames 1..F is complete.
void writeFrame(const Simulation& sim, int frame, const SimStageOptions& options,
                const StageContext& ctx, std::vector<FrameStats>& stats) {
    const Globules& g = sim.globules();
    writeGlobuleVdb(cacheVdbPath(ctx.outDir, frame), g, CacheInfo{frame, sim.time()});
    if (options.output.ply) writeGlobulePly(cachePlyPath(ctx.outDir, frame), g);
    if (!sim.setup().colliders.empty()) {
        writeColliderPoses(colliderPosesPath(ctx.outDir, frame), frame, sim.time(),
                           sim.setup().colliders, sim.colliders().motions());
    }
    stats.push_back(computeFrameStats(g, frame, sim.time()));
    writeFileAtomically(ctx.outDir / "stats.csv", statsText(stats));
    writeCheckpoint(ctx.outDir / "state.bin",
                    Checkpoint{frame, options.sceneFingerprint, sim.saveState()});
}

/// Restores the run in ctx.outDir; @return the last complete frame.
int resumeFrom(Simulation& sim, const SimulationSetup& setup, const SimStageOptions& options,
               const StageContext& ctx, std::vector<FrameStats>& stats) {
    const fs::path statePath = ctx.outDir / "state.bin";
    if (!fs::exists(statePath)) {
        ctx.report().info("resume: no checkpoint in " + ctx.outDir.string() +
                          "; starting from the first frame");
        return 0;
    }
    Checkpoint checkpoint = readCheckpoint(statePath);
    if (checkpoint.sceneFingerprint != options.sceneFingerprint) {
        throw IoError("cannot resume " + ctx.outDir.string() +
                      ": it was simulated from a different scene (or --set overrides); use "
                      "another --out, or run without --resume to start over");
    }
    // Every frame ends at exactly (frame - 1) / fps (Simulation::advanceFrame): a
    // checkpoint whose time disagrees is damaged, and resuming it would rewrite frames
    // with a state that never existed.
    const double frameTime = double(checkpoint.frame - 1) / setup.simulation.fps;
    if (checkpoint.state.time != frameTime) {
        throw IoError("checkpoint " + statePath.string() + " is damaged: it says frame " +
                      std::to_string(checkpoint.frame) + " at t = " +
                      std::to_string(checkpoint.state.time) + " s, but that frame is at t = " +
                      std::to_string(frameTime) +
                      " s; run without --resume to start over");
    }
    sim.restoreState(checkpoint.state);
    for (const FrameStats& row : readStatsCsv(ctx.outDir / "stats.csv")) {
        if (row.frame <= checkpoint.frame) stats.push_back(row);
    }
    ctx.report().info("resume: continuing after frame " + std::to_string(checkpoint.frame));
    return checkpoint.frame;
}

}  // namespace

std::size_t estimateSimulationBytes(std::size_t globules) {
    // 36 B of globule state, 12 B accelerations (24 with Verlet), 12 B neighbour grid,
    // a saved copy for on_explosion = substep, ~64 B while a cache frame is encoded.
    return 4096 * 1024 + globules * 200;
}

void runSimStage(const SimulationSetup& setup, const SimStageOptions& options,
                 const StageContext& ctx) {
    ensureWritableDirectory(ctx.outDir);
    ctx.sweepTemporaries("sim");
    // All emitters together, before any of them places a globule.
    const auto checkMemory = [&](std::size_t globules) {
        const std::size_t need = globules > SIZE_MAX / 256 ? SIZE_MAX
                                                            : estimateSimulationBytes(globules);
        const std::size_t have = physicalMemoryBytes();
        if (have > 0 && need > have / 10 * 8) {
            std::string perEmitter;
            for (std::size_t k = 0; k < setup.emitters.size(); ++k) {
                perEmitter += (k ? ", " : "") + std::to_string(plannedGlobules(setup.emitters[k]));
            }
            throw ResourceError("the scene's emitters make " + std::to_string(globules) +
                                " globules (per [[emitter]]: " + perEmitter + "), which need about " +
                                std::to_string(need >> 20) + " MiB, more than 80% of this machine's " +
                                std::to_string(have >> 20) + " MiB; lower their count or raise spacing");
        }
    };
    checkMemory(Simulation::plannedCount(setup));
    Simulation sim(setup);
    ctx.report().info(std::string("sim: force kernels ") + simdPathName(sim.simdPath()) +
                      " (this CPU runs " + supportedSimdPathNames() + "; GLOBULAR_SIMD chooses)");
    checkMemory(sim.plannedCount());  // now with the points files' globules
    std::vector<FrameStats> stats;
    int done = options.resume ? resumeFrom(sim, setup, options, ctx, stats) : 0;
    if (done == 0) {
        stats.clear();
        writeFrame(sim, 1, options, ctx, stats);
        done = 1;
    }
    ctx.report().progress("sim", done, ctx.lastFrame);
    const int resumedAt = done;
    const int64_t stepsBefore = sim.stepCount();
    for (int frame = done + 1; frame <= ctx.lastFrame; ++frame) {
        sim.advanceFrame(frame, ctx.report());
        writeFrame(sim, frame, options, ctx, stats);
        ctx.report().progress("sim", frame, ctx.lastFrame);
    }
    if (setup.simulation.adaptive && ctx.lastFrame > resumedAt) {
        ctx.report().info(adaptiveSummary(sim.stepCount() - stepsBefore,
                                          double(ctx.lastFrame - resumedAt) / setup.simulation.fps,
                                          sim.shortestStep()));
    }
}

}  // namespace globular
