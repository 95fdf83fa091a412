// The splat's inner loop (surface/splat_kernel.h): every build gives the same bits, for
// each kernel, with and without per-globule means, and the sums are the kernel's values.
#include "splat_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace globular {
namespace {

Globules randomGlobules(int count, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> at(-1.5, 1.5), radius(0.3, 0.9), speed(-2, 2);
    Globules g;
    for (int i = 0; i < count; ++i) {
        g.add({at(random), at(random), at(random)}, {speed(random), speed(random), speed(random)},
              float(radius(random)), 1, i);
    }
    return g;
}

/// Every candidate block's sums (and, with @p means, sum(w vx)) from @p path's build.
std::vector<float> splatBlocks(SimdPath path, const GlobuleBins& bins, const Globules& g,
                               const MetaballKernel& kernel, bool means) {
    constexpr int kVoxels = 512;
    const AddGlobules add = splatKernels(path).add[int(kernel.type)][means];
    SplatChannels channels;
    channels.value[channels.count++] = g.vx.data();
    std::vector<float> out;
    for (uint64_t key : bins.candidateBlocks()) {
        alignas(32) float sum[kVoxels] = {}, weighted[kVoxels] = {};
        BlockSums sums{sum};
        if (means) {
            sums.channels = &channels;
            sums.weighted[0] = weighted;
        }
        EXPECT_EQ(add(bins, key, kernel, sums, 0, INFINITY, VoxelBox{}), bins.nearOrder().size());
        out.insert(out.end(), sum, sum + kVoxels);
        if (means) out.insert(out.end(), weighted, weighted + kVoxels);
    }
    return out;
}

TEST(SplatKernel, EveryBuildGivesTheSameBits) {
    const Globules g = randomGlobules(60, 3);
    const GlobuleBins bins(g, 0.1, 2.0);
    for (KernelType type : {KernelType::Wyvill, KernelType::Blinn, KernelType::Murakami}) {
        const MetaballKernel kernel{type, 3.0f};
        for (bool means : {false, true}) {
            const std::vector<float> scalar = splatBlocks(SimdPath::Scalar, bins, g, kernel, means);
            ASSERT_GT(scalar.size(), 512u);
            for (SimdPath path : supportedSimdPaths()) {
                const std::vector<float> other = splatBlocks(path, bins, g, kernel, means);
                ASSERT_EQ(other.size(), scalar.size());
                EXPECT_EQ(std::memcmp(other.data(), scalar.data(), scalar.size() * sizeof(float)),
                          0)
                    << simdPathName(path) << " kernel " << int(type) << " means " << means;
            }
        }
    }
}

TEST(SplatKernel, SumsAreTheKernelValuesOfTheGlobulesInReach) {
    const Globules g = randomGlobules(12, 9);
    const double voxel = 0.1, influence = 2.0;
    const GlobuleBins bins(g, voxel, influence);
    const MetaballKernel kernel{KernelType::Blinn, 3.0f};
    for (SimdPath path : supportedSimdPaths()) {
        const std::vector<float> sums = splatBlocks(path, bins, g, kernel, false);
        double worst = 0;
        for (std::size_t b = 0; b < bins.candidateBlocks().size(); b += 7) {
            const auto block = GlobuleBins::unpack(bins.candidateBlocks()[b]);
            for (int v = 0; v < 512; v += 13) {
                const double p[3] = {double(block[0] * 8 + (v >> 6)) * voxel,
                                     double(block[1] * 8 + ((v >> 3) & 7)) * voxel,
                                     double(block[2] * 8 + (v & 7)) * voxel};
                double exact = 0;
                for (std::size_t i = 0; i < g.size(); ++i) {
                    const double dx = p[0] - g.px[i], dy = p[1] - g.py[i], dz = p[2] - g.pz[i];
                    const double reach = influence * g.radius[i];
                    exact += kernel.value(float((dx * dx + dy * dy + dz * dz) / (reach * reach)));
                }
                worst = std::max(worst, std::abs(sums[b * 512 + std::size_t(v)] - exact));
            }
        }
        EXPECT_LT(worst, 1e-4) << simdPathName(path);
    }
}

TEST(SplatKernel, GivesTheFullSumsWithinTheBoxAsked) {
    const Globules g = randomGlobules(60, 5);
    const GlobuleBins bins(g, 0.1, 2.0);
    const MetaballKernel kernel{KernelType::Wyvill};
    SplatChannels channels;
    channels.value[channels.count++] = g.vy.data();
    std::mt19937 random(11);
    std::size_t skipped = 0;
    for (SimdPath path : supportedSimdPaths()) {
        const AddGlobules add = splatKernels(path).add[int(kernel.type)][1];
        for (uint64_t key : bins.candidateBlocks()) {
            // A random box, from a random place in the order (a sum taken up again where
            // it stopped).
            VoxelBox box;
            for (int a = 0; a < 3; ++a) {
                box.lo[a] = int(random() % 8);
                box.hi[a] = box.lo[a] + int(random() % std::size_t(8 - box.lo[a]));
            }
            const std::size_t from = random() % bins.nearOrder().size();
            alignas(64) float sum[512], weighted[512], fullSum[512], fullWeighted[512];
            std::fill(sum, sum + 512, 0.5f);
            std::fill(fullSum, fullSum + 512, 0.5f);
            std::fill(weighted, weighted + 512, 0.5f);
            std::fill(fullWeighted, fullWeighted + 512, 0.5f);
            BlockSums part{sum}, full{fullSum};
            part.channels = full.channels = &channels;
            part.weighted[0] = weighted;
            full.weighted[0] = fullWeighted;
            add(bins, key, kernel, full, from, INFINITY, VoxelBox{});
            add(bins, key, kernel, part, from, INFINITY, box);
            for (int v = 0; v < 512; ++v) {
                const int p[3] = {v >> 6, (v >> 3) & 7, v & 7};
                bool inside = true;
                for (int a = 0; a < 3; ++a) inside &= p[a] >= box.lo[a] && p[a] <= box.hi[a];
                if (inside) {
                    ASSERT_EQ(std::memcmp(&sum[v], &fullSum[v], sizeof(float)), 0);
                    ASSERT_EQ(std::memcmp(&weighted[v], &fullWeighted[v], sizeof(float)), 0);
                } else {
                    skipped += sum[v] != fullSum[v];
                }
            }
        }
    }
    EXPECT_GT(skipped, 0u);  // the others were left out
}

}  // namespace
}  // namespace globular
