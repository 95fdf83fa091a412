#pragma once
// How much memory surfacing a frame will take, known before any grid is allocated, so a
// scene that asks for too fine a voxel size is refused up front with the numbers instead
// of dying halfway through a sequence. OpenVDB-free.

#include <cstdint>
#include <string>

#include "globules.h"
#include "surface_settings.h"

namespace globular {

struct SurfaceEstimate {
    double voxelSize = 0;  ///< world units, as resolved for the frame
    std::size_t globules = 0;
    std::size_t fieldLeaves = 0;  ///< upper bound on the metaball field's 8^3 leaves
    uint64_t voxels = 0;          ///< fieldLeaves * 512: voxels the field allocates
    uint64_t bytes = 0;           ///< estimated peak memory of surfacing the frame
};

/// Bins the globules (GlobuleBins) and counts the leaves their influence spheres reach.
/// Costs about a tenth of a second per million globules. The bins' own memory counts
/// too: globules of very different radii, or a voxel far smaller than they are, would
/// take more to bin than to surface.
/// @param budget bytes available (0 = unknown). When the largest globule alone, or the
///        binning, would exceed it, returns at once without binning, with bytes above
///        @p budget and fieldLeaves the lower bound of the largest globule.
/// @throw as GlobuleBins (non-finite or out-of-range globules).
SurfaceEstimate estimateSurface(const Globules& globules, const SurfaceSettings& settings,
                                uint64_t budget = 0);

/// Memory this process may still allocate: MemAvailable of /proc/meminfo, lowered to the
/// headroom of the cgroup limit when one is set. 0 when neither can be read.
uint64_t availableMemoryBytes();

/// "1.5 GiB", "320 MiB".
std::string formatBytes(uint64_t bytes);

}  // namespace globular
