#include "surface_stage.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <sstream>

#include "collider_mesh.h"
#include "collider_poses.h"
#include "errors.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "surface_estimate.h"
#include "surface_frame.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

Globules readCache(const fs::path& outDir, int frame) {
    const fs::path path = cacheVdbPath(outDir, frame);
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        throw IoError("missing globule cache " + path.string() + " for frame " +
                      std::to_string(frame) +
                      ": run the sim stage first (globular run SCENE --stages sim)");
    }
    return readGlobuleVdb(path);
}

std::string describeEstimate(int frame, const SurfaceEstimate& e) {
    std::ostringstream out;
    out.precision(3);
    out << "frame " << frame << ": " << e.globules << " globules at voxel size " << e.voxelSize
        << " need up to " << double(e.voxels) << " voxels (~" << formatBytes(e.bytes) << ")";
    return out.str();
}

/// Every frame checked before any is written; the first problem in frame order wins, so
/// the message does not depend on which thread finished first.
SurfaceEstimate checkAllFrames(const SurfaceSettings& settings, const StageContext& ctx,
                               uint64_t budget, int& largestFrame) {
    const int count = ctx.lastFrame - ctx.firstFrame + 1;
    std::vector<std::optional<SurfaceEstimate>> estimates(count);
    std::vector<std::exception_ptr> errors(count);
    tbb::parallel_for(0, count, [&](int k) {
        const int frame = ctx.firstFrame + k;
        try {
            estimates[k] = estimateSurface(readCache(ctx.outDir, frame), settings, budget);
        } catch (const SimulationError& e) {  // a bad globule: say which cache holds it
            errors[k] = std::make_exception_ptr(
                SimulationError(cacheVdbPath(ctx.outDir, frame).string() + ": " + e.what()));
        } catch (const ResourceError& e) {
            errors[k] = std::make_exception_ptr(
                ResourceError(cacheVdbPath(ctx.outDir, frame).string() + ": " + e.what()));
        } catch (...) {
            errors[k] = std::current_exception();
        }
    });
    SurfaceEstimate largest;
    for (int k = 0; k < count; ++k) {
        if (errors[k]) std::rethrow_exception(errors[k]);
        const int frame = ctx.firstFrame + k;
        if (budget > 0 && estimates[k]->bytes > budget) {
            throw ResourceError(
                "cannot surface " + describeEstimate(frame, *estimates[k]) + " but only " +
                formatBytes(budget) + " is available" +
                (settings.memoryLimitGiB > 0 ? " ([surface] memory_limit_gib)" : "") +
                "; raise [surface] voxel_size or lower voxels_per_radius (each doubling of "
                "the voxel size needs about 8 times less)");
        }
        if (estimates[k]->bytes >= largest.bytes) {
            largest = *estimates[k];
            largestFrame = frame;
        }
    }
    return largest;
}

}  // namespace

void runSurfaceStage(const SurfaceSettings& settings, const StageContext& ctx,
                     const ColliderScene& colliders, double fps, bool severalMaterials) {
    settings.validate();
    if (ctx.firstFrame < 1 || ctx.lastFrame < ctx.firstFrame) {
        throw SceneError("surface stage: frame range " + std::to_string(ctx.firstFrame) + "-" +
                         std::to_string(ctx.lastFrame) + " is empty or starts before frame 1");
    }
    Reporter& report = ctx.report();
    ctx.sweepTemporaries("surface");
    const int total = ctx.lastFrame - ctx.firstFrame + 1;
    const uint64_t budget = settings.memoryLimitGiB > 0
                                ? uint64_t(settings.memoryLimitGiB * 1024.0 * 1024.0 * 1024.0)
                                : availableMemoryBytes();
    if (budget == 0) {
        report.warn(
            "surface: cannot tell how much memory is available (no /proc/meminfo); "
            "frames are not checked against it, set [surface] memory_limit_gib");
    }

    const std::vector<ColliderSolid> solids = colliders.solids();
    int largestFrame = ctx.firstFrame;
    const SurfaceEstimate largest = checkAllFrames(settings, ctx, budget, largestFrame);

    const int threads = tbb::this_task_arena::max_concurrency();
    int inFlight = int(settings.framesInFlight);
    if (inFlight == 0) {
        // Frames side by side beat one frame at a time with every thread on it: the
        // steps of one frame are not all parallel (measured, docs/surface.md). Memory
        // bounds how many fit at once.
        const uint64_t fit =
            largest.bytes > 0 && budget > 0 ? budget / largest.bytes : uint64_t(threads);
        inFlight = int(std::clamp<uint64_t>(fit, 1, uint64_t(threads)));
    }
    inFlight = std::min(inFlight, total);
    report.info("surface: frames " + std::to_string(ctx.firstFrame) + "-" +
                std::to_string(ctx.lastFrame) + ", " + std::to_string(inFlight) +
                " at a time; largest " + describeEstimate(largestFrame, largest));

    std::mutex reportMutex;
    long done = 0;
    report.progress("surface", 0, total);
    std::atomic<int> next{ctx.firstFrame};
    std::atomic<bool> failed{false};
    // A failed frame must not throw through parallel_for: TBB would cancel the other
    // frames' nested parallel steps midway and let them run on with half-built grids.
    // The first failure in frame order is reported once every frame in flight is done.
    std::exception_ptr firstError;
    int firstErrorFrame = ctx.lastFrame + 1;
    tbb::parallel_for(0, inFlight, [&](int) {
        for (int f = next++; f <= ctx.lastFrame && !failed; f = next++) {
            try {
                // Isolation keeps a thread that waits inside one frame's parallel steps
                // from starting another frame on top of it (and its memory).
                tbb::this_task_arena::isolate([&] {
                    const Globules globules = readCache(ctx.outDir, f);
                    const std::vector<Pose> poses =
                        colliderPosesOnFrame(colliders.colliders, ctx.outDir, f, fps);
                    std::vector<PlacedSolid> placed;
                    for (std::size_t k = 0; k < poses.size(); ++k) {
                        placed.push_back({&solids[k], poses[k]});
                    }
                    const SurfaceFrame frame =
                        surfaceGlobules(globules, settings, placed, severalMaterials);
                    writeSurfaceVdb(surfaceVdbPath(ctx.outDir, f), frame);
                    writeSurfaceMesh(meshPath(ctx.outDir, f, settings.meshFormat), frame.mesh,
                                     settings.meshFormat);
                    if (!solids.empty()) {
                        writeMeshPly(collidersMeshPath(ctx.outDir, f),
                                     collidersMesh(colliders.colliders, solids, poses));
                    }
                    std::lock_guard lock(reportMutex);
                    if (frame.dropletsRemoved > 0) {
                        report.info("surface: frame " + std::to_string(f) + ": removed " +
                                    std::to_string(frame.dropletsRemoved) + " droplets");
                    }
                    report.progress("surface", ++done, total);
                });
            } catch (...) {
                std::lock_guard lock(reportMutex);
                if (f < firstErrorFrame) {
                    firstError = std::current_exception();
                    firstErrorFrame = f;
                }
                failed = true;
            }
        }
    });
    if (firstError) std::rethrow_exception(firstError);
}

}  // namespace globular
