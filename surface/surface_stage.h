#pragma once
// The surface stage: for each frame of a run, the globule cache in, the surface VDB and
// the mesh out (DESIGN.md). It reads only the cache, so it reruns without re-simulating,
// and each frame is independent, so --frames A-B splits a sequence across machines.
// OpenVDB-free.

#include <vector>

#include "collider_solid.h"
#include "stage_context.h"
#include "surface_settings.h"

namespace globular {

/// For each frame f in [ctx.firstFrame, ctx.lastFrame]: reads cacheVdbPath(outDir, f),
/// writes surfaceVdbPath(outDir, f) (grids "surface" and "density") and
/// meshPath(outDir, f, settings.meshFormat), each atomically, reporting
/// progress("surface", done, total).
///
/// Before writing anything it checks every frame: the cache exists and reads, and its
/// memory estimate (surface_estimate.h) fits the memory available (or
/// settings.memoryLimitGiB). Frames are then surfaced settings.framesInFlight at a time
/// (auto: as many as memory allows, up to the thread count), each with parallel steps.
///
/// @throw SceneError for invalid settings or an empty frame range.
/// @throw IoError naming a missing or unreadable cache (run the sim stage first) or an
///        output that cannot be written.
/// @throw ResourceError when a frame's estimate exceeds the memory, with the estimate.
///
/// With colliders, it cuts their solids out of the liquid (settings.subtractColliders) and
/// writes mesh/colliders.NNNN.ply for each frame: every collider tessellated at its pose
/// on the frame (collider_poses.h: the sim stage's, or the keyframes' at (frame - 1) /
/// @p fps), in world coordinates, so a DCC tool places the set with the liquid as a mesh
/// sequence.
/// @p severalMaterials: the scene has more than one material (surfaceGlobules).
void runSurfaceStage(const SurfaceSettings& settings, const StageContext& ctx,
                     const ColliderScene& colliders = {}, double fps = 25,
                     bool severalMaterials = false);

}  // namespace globular
