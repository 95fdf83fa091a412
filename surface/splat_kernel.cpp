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
    SplatRow operator()(SplatRow q) const {
        SplatRow k;
        if constexpr (K == KernelType::Wyvill) {
            k = 1.0f + q * (-22.0f / 9.0f + q * (17.0f / 9.0f - q * (4.0f / 9.0f)));
        } else if constexpr (K == KernelType::Blinn) {
            for (int z = 0; z < kDim; ++z) k[z] = (std::exp(-sharpness * q[z]) - tail) * scale;
        } else {
            const SplatRow s = 1.0f - q;
            k = s * s;
        }
        return q < 1.0f ? k : SplatRow{};
    }
};

/// AddGlobules (splat_kernel.h) for kernel @p K, with means or not.
template <KernelType K, bool kMean>
std::size_t addGlobules(const GlobuleBins& bins, uint64_t key, const MetaballKernel& type,
                        const BlockSums& out, std::size_t from, float deepAbove) {
    const KernelEval<K> kernel(type);
    float* const sum = out.sum;
    const auto block = GlobuleBins::unpack(key);
    const int64_t ox = block[0] * kDim, oy = block[1] * kDim, oz = block[2] * kDim;
    const auto add = [&](uint32_t i) {
        const float r = bins.influenceVoxels(i);
        // Centre relative to the block origin: small numbers, so float is exact enough
        // however far the block lies from the world origin.
        const float cx = float(bins.centreX(i) - double(ox));
        const float cy = float(bins.centreY(i) - double(oy));
        const float cz = float(bins.centreZ(i) - double(oz));
        const int x0 = std::max(0, int(std::ceil(cx - r)));
        const int x1 = std::min(kDim - 1, int(std::floor(cx + r)));
        const int y0 = std::max(0, int(std::ceil(cy - r)));
        const int y1 = std::min(kDim - 1, int(std::floor(cy + r)));
        const int z0 = std::max(0, int(std::ceil(cz - r)));
        const int z1 = std::min(kDim - 1, int(std::floor(cz + r)));
        if (x0 > x1 || y0 > y1 || z0 > z1) return;
        const float invR2 = 1.0f / (r * r);
        // A whole 8-voxel row at a time, voxels outside the sphere adding 0: no branches
        // in the innermost work, and cheaper than clipping each row to its chord, because
        // rows inside a leaf are short.
        SplatRow qz;
        for (int z = 0; z < kDim; ++z) qz[z] = (float(z) - cz) * (float(z) - cz) * invR2;
        for (int x = x0; x <= x1; ++x) {
            const float qx = (float(x) - cx) * (float(x) - cx) * invR2;
            for (int y = y0; y <= y1; ++y) {
                const float qxy = qx + (float(y) - cy) * (float(y) - cy) * invR2;
                if (qxy >= 1.0f) continue;
                const int offset =
                    (x << (2 * GlobuleBins::kBlockLog2)) + (y << GlobuleBins::kBlockLog2);
                const SplatRow k = kernel(qxy + qz);
                SplatRow values;
                std::memcpy(&values, sum + offset, sizeof values);
                values += k;
                std::memcpy(sum + offset, &values, sizeof values);
                if constexpr (kMean) {
                    for (int c = 0; c < out.channels->count; ++c) {
                        std::memcpy(&values, out.weighted[c] + offset, sizeof values);
                        values += k * out.channels->value[c][i];
                        std::memcpy(out.weighted[c] + offset, &values, sizeof values);
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
