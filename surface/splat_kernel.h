#pragma once
// The splat's inner loop (metaball_splat.cpp): the kernel values of the globules near one
// 8^3 block, summed into the block's voxels. Built once per instruction set, like the
// force loops (sim/simd_path.h), and picked from the same GLOBULAR_SIMD choice: the
// baseline build does each 8-voxel row as two SSE halves, the AVX2 one as one 8-lane
// vector, the AVX-512 one two neighbouring rows as one 16-lane vector. Every build keeps
// each multiply and add separate (no fused multiply-add), so they give the same bits: a
// frame's field does not depend on the node that made it.
// OpenVDB-free; each build exports only its table (surface/CMakeLists.txt).

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "globule_bins.h"
#include "metaball_kernel.h"
#include "simd_path.h"

namespace globular {

/// One row of a block along z: 8 floats as one vector value (the GCC/Clang vector
/// extension: the compiler picks the registers each build has).
using SplatRow = float __attribute__((vector_size(GlobuleBins::kBlockDim * sizeof(float))));

/// At most this many per-globule values are averaged in one pass (a velocity's three
/// components and a temperature).
constexpr int kMaxSplatChannels = 4;

/// The per-globule values averaged (kMean): one array per channel.
struct SplatChannels {
    int count = 0;
    const float* value[kMaxSplatChannels] = {};
};

/// What one block accumulates: the field's sum and, when per-globule values are
/// averaged, sum(w value) of each channel beside it, from the same kernel values.
struct BlockSums {
    float* sum;                               ///< 8^3 voxels
    float* weighted[kMaxSplatChannels] = {};  ///< 8^3 voxels per channel; means only
    const SplatChannels* channels = nullptr;  ///< means only
};

/// True when every value of a block's sum exceeds @p threshold.
inline bool allAbove(const float* sum, float threshold) {
    constexpr int kDim = GlobuleBins::kBlockDim;
    SplatRow low;
    std::memcpy(&low, sum, sizeof low);
    for (int r = 1; r < kDim * kDim; ++r) {
        SplatRow row;
        std::memcpy(&row, sum + r * kDim, sizeof row);
        low = low < row ? low : row;
    }
    bool result = true;
    for (int z = 0; z < kDim; ++z) result &= low[z] > threshold;
    return result;
}

/// A box of a block's voxels, bounds inclusive (local coordinates 0-7).
struct VoxelBox {
    int lo[3] = {0, 0, 0};
    int hi[3] = {GlobuleBins::kBlockDim - 1, GlobuleBins::kBlockDim - 1,
                 GlobuleBins::kBlockDim - 1};
};

/// Adds the globules of the blocks bins.nearOrder()[from...] into @p out, the voxels of
/// block @p key: the full sums within @p exact, in the same order as over the whole
/// block (voxels beyond it may receive some of the additions or none). With a finite
/// @p deepAbove, stops after a whole shell of blocks (those at one distance) once every
/// voxel exceeds it. @return the index in nearOrder() it stopped at (its size when
/// complete).
using AddGlobules = std::size_t (*)(const GlobuleBins& bins, uint64_t key,
                                    const MetaballKernel& kernel, const BlockSums& out,
                                    std::size_t from, float deepAbove, const VoxelBox& exact);

/// One build's loops: [kernel type][with means].
struct SplatKernels {
    AddGlobules add[3][2];
};

namespace simd_scalar { extern const SplatKernels kSplatKernels; }
namespace simd_avx2 { extern const SplatKernels kSplatKernels; }
namespace simd_avx512 { extern const SplatKernels kSplatKernels; }

/// The splat's loops for @p path.
inline const SplatKernels& splatKernels(SimdPath path) {
    switch (path) {
        case SimdPath::Scalar: return simd_scalar::kSplatKernels;
        case SimdPath::Avx2: return simd_avx2::kSplatKernels;
        case SimdPath::Avx512: return simd_avx512::kSplatKernels;
    }
    return simd_scalar::kSplatKernels;
}

}  // namespace globular
