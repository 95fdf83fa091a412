// The splat's inner loop (splat_kernel.h). This file is compiled once per instruction set
// (surface/CMakeLists.txt) with GLOBULAR_SIMD_NAMESPACE naming the build.
#include "splat_kernel.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#ifndef GLOBULAR_SIMD_NAMESPACE
#error \
    "splat_kernel.cpp is built once per path with GLOBULAR_SIMD_NAMESPACE (surface/CMakeLists.txt)"
#endif

namespace globular {

namespace {

constexpr int kDim = GlobuleBins::kBlockDim;

// Rows summed per step. Rows y and y + 1 of a leaf lie side by side in memory, so a build
// with 16-lane vectors does two rows in one: half the instructions per voxel. A row the
// pair adds beyond the sphere's rows gets q >= 1 and adds zeros, as the lanes outside
// the sphere already do, so each voxel sees the same operations, in the same order, in
// every build.
#ifdef __AVX512F__
constexpr int kRowsPerStep = 2;
#else
constexpr int kRowsPerStep = 1;
#endif
constexpr int kLanes = kRowsPerStep * kDim;
using SplatStep = float __attribute__((vector_size(kLanes * sizeof(float))));

/// Kernel values with the kernel chosen at compile time, so the innermost loop of the
/// splat carries no switch.
template <KernelType K>
struct KernelEval {
    float sharpness, tail, scale;
    explicit KernelEval(const MetaballKernel& k)
        : sharpness(k.blinnSharpness),
          tail(std::exp(-k.blinnSharpness)),
          scale(1.0f / (1.0f - std::exp(-k.blinnSharpness))) {}
    /// The kernel at each lane's q, and 0 where q >= 1 (outside the influence sphere).
    SplatStep operator()(SplatStep q) const {
        SplatStep k;
        if constexpr (K == KernelType::Wyvill) {
            k = 1.0f + q * (-22.0f / 9.0f + q * (17.0f / 9.0f - q * (4.0f / 9.0f)));
        } else if constexpr (K == KernelType::Blinn) {
            for (int l = 0; l < kLanes; ++l) k[l] = (std::exp(-sharpness * q[l]) - tail) * scale;
        } else {
            const SplatStep s = 1.0f - q;
            k = s * s;
        }
        return q < 1.0f ? k : SplatStep{};
    }
};

/// AddGlobules (splat_kernel.h) for kernel @p K, with means or not.
template <KernelType K, bool kMean>
std::size_t addGlobules(const GlobuleBins& bins, uint64_t key, const MetaballKernel& type,
                        const BlockSums& out, std::size_t from, float deepAbove,
                        const VoxelBox& exact) {
    const KernelEval<K> kernel(type);
    float* const sum = out.sum;
    // Copies, so that the compiler need not reload them after each store into the sums.
    const int channels = kMean ? out.channels->count : 0;
    float* weighted[kMaxSplatChannels] = {};
    const float* channelValues[kMaxSplatChannels] = {};
    for (int c = 0; c < channels; ++c) {
        weighted[c] = out.weighted[c];
        channelValues[c] = out.channels->value[c];
    }
    // Which row of a step each lane belongs to.
    SplatStep laneRow;
    for (int l = 0; l < kLanes; ++l) laneRow[l] = float(l / kDim);
    const auto block = GlobuleBins::unpack(key);
    const int64_t ox = block[0] * kDim, oy = block[1] * kDim, oz = block[2] * kDim;
    const auto add = [&](uint32_t i) {
        const float r = bins.influenceVoxels(i);
        // Centre relative to the block origin: small numbers, so float is exact enough
        // however far the block lies from the world origin.
        const float cx = float(bins.centreX(i) - double(ox));
        const float cy = float(bins.centreY(i) - double(oy));
        const float cz = float(bins.centreZ(i) - double(oz));
        const int x0 = std::max(exact.lo[0], int(std::ceil(cx - r)));
        const int x1 = std::min(exact.hi[0], int(std::floor(cx + r)));
        const int y0 = std::max(exact.lo[1], int(std::ceil(cy - r)));
        const int y1 = std::min(exact.hi[1], int(std::floor(cy + r)));
        const int z0 = std::max(exact.lo[2], int(std::ceil(cz - r)));
        const int z1 = std::min(exact.hi[2], int(std::floor(cz + r)));
        if (x0 > x1 || y0 > y1 || z0 > z1) return;
        const float invR2 = 1.0f / (r * r);
        // Read once: the stores into the sums below may alias them as far as the
        // compiler knows, so they would be read again for every row.
        float value[kMaxSplatChannels] = {};
        for (int c = 0; c < channels; ++c) value[c] = channelValues[c][i];
        // Whole 8-voxel rows at a time, voxels outside the sphere adding 0: no branches
        // in the innermost work, and cheaper than clipping each row to its chord, because
        // rows inside a leaf are short.
        SplatStep qz;
        for (int l = 0; l < kLanes; ++l) {
            const float z = float(l % kDim);
            qz[l] = (z - cz) * (z - cz) * invR2;
        }
        // The rows in steps: an odd count gains a row beyond the sphere on the side the
        // block has room for.
        int yBegin = y0, yEnd = y1;
        if constexpr (kRowsPerStep == 2) {
            if ((y1 - y0 + 1) % 2 != 0) {
                if (y1 < kDim - 1) {
                    yEnd = y1 + 1;
                } else {
                    yBegin = y0 - 1;
                }
            }
        }
        for (int x = x0; x <= x1; ++x) {
            const float qx = (float(x) - cx) * (float(x) - cx) * invR2;
            for (int y = yBegin; y <= yEnd; y += kRowsPerStep) {
                SplatStep qxy{};
                bool inside = false;
                for (int r = 0; r < kRowsPerStep; ++r) {
                    const int row = y + r;
                    // 1 for an added row: it adds zeros whatever the rounding.
                    const float q = row < y0 || row > y1
                                        ? 1.0f
                                        : qx + (float(row) - cy) * (float(row) - cy) * invR2;
                    inside |= q < 1.0f;
                    qxy = laneRow == float(r) ? SplatStep{} + q : qxy;
                }
                if (!inside) continue;
                const int offset =
                    (x << (2 * GlobuleBins::kBlockLog2)) + (y << GlobuleBins::kBlockLog2);
                const SplatStep k = kernel(qxy + qz);
                SplatStep values;
                std::memcpy(&values, sum + offset, sizeof values);
                values += k;
                std::memcpy(sum + offset, &values, sizeof values);
                if constexpr (kMean) {
                    for (int c = 0; c < channels; ++c) {
                        std::memcpy(&values, weighted[c] + offset, sizeof values);
                        values += k * value[c];
                        std::memcpy(weighted[c] + offset, &values, sizeof values);
                    }
                }
            }
        }
    };
    const auto& order = bins.nearOrder();
    const bool mayStop = std::isfinite(deepAbove);
    for (std::size_t n = from; n < order.size(); ++n) {
        bins.forEachGlobuleIn(key, order[n], add);
        // Checked once the block and its face neighbours are in, then after each shell:
        // a block deep inside is usually above by then.
        const bool shellDone = n + 1 < order.size() && order[n + 1][3] != order[n][3];
        if (mayStop && shellDone && order[n][3] >= 1 && allAbove(sum, deepAbove)) return n + 1;
    }
    return order.size();
}

}  // namespace

// The one symbol this build exports (splat_kernel.h).
namespace GLOBULAR_SIMD_NAMESPACE {
extern const SplatKernels kSplatKernels;
const SplatKernels kSplatKernels{{
    {addGlobules<KernelType::Wyvill, false>, addGlobules<KernelType::Wyvill, true>},
    {addGlobules<KernelType::Blinn, false>, addGlobules<KernelType::Blinn, true>},
    {addGlobules<KernelType::Murakami, false>, addGlobules<KernelType::Murakami, true>},
}};
}  // namespace GLOBULAR_SIMD_NAMESPACE

}  // namespace globular
