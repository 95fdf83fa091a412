#pragma once
// The grid force loops (force_kernels.cpp), one build per instruction set (simd_path.h).
// Each build of force_kernels.cpp exports only its table, kForceKernels, in a namespace
// named after its path; everything else it compiled (the inline kernels of
// pair_kernel.h, the neighbour grid, the standard library's templates) is made local
// to it when it is built (cmake/isolated_build.cmake), so the linker never swaps an AVX-512 copy
// of an inline function into the scalar path, or the reverse.

#include "accelerations.h"
#include "cell_schedule.h"
#include "globules.h"
#include "material_pairs.h"
#include "neighbor_grid.h"
#include "pair_force.h"
#include "simd_path.h"

namespace globular {

/// What the grid force loop keeps between steps.
struct NeighborWorkspace {
    NeighborGrid grid;
    CellSchedule schedule;  ///< where the loop evaluates each pair once (force_kernels.cpp)
    float largestRadius = 0;  ///< of the globules the grid was last built over
    /// Globules per task at least. A task's range may cut a grid cell's group anywhere;
    /// tests shrink it to cut groups at other places, which must not change a bit.
    std::size_t grain = 256;
};

/// One path's force loops (forces.h: pairForcesSorting and pairForcesThermal).
struct ForceKernels {
    void (*sorting)(Globules&, const PairForce&, NeighborWorkspace&, Accelerations&);
    void (*sortingTable)(Globules&, const PairTable&, NeighborWorkspace&, Accelerations&);
    void (*thermal)(Globules&, const PairTable&, NeighborWorkspace&, Accelerations&);
};

namespace simd_scalar { extern const ForceKernels kForceKernels; }
namespace simd_avx2 { extern const ForceKernels kForceKernels; }
namespace simd_avx512 { extern const ForceKernels kForceKernels; }

/// The force loops of @p path (which the caller has checked this CPU runs).
inline const ForceKernels& forceKernels(SimdPath path) {
    switch (path) {
        case SimdPath::Avx2: return simd_avx2::kForceKernels;
        case SimdPath::Avx512: return simd_avx512::kForceKernels;
        default: return simd_scalar::kForceKernels;
    }
}

/// The smallest and largest radius of @p globules (1, 1 when there are none).
std::pair<float, float> radiusRange(const Globules& globules);

}  // namespace globular
