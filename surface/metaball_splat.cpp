// Splatting globules into a sparse metaball field, one OpenVDB leaf at a time.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "globule_bins.h"
#include "surface_grids.h"

namespace globular {

namespace {

using openvdb::FloatGrid;
using LeafType = openvdb::FloatTree::LeafNodeType;
static_assert(LeafType::DIM == GlobuleBins::kBlockDim, "bins must match the tree's leaves");
constexpr int kDim = GlobuleBins::kBlockDim;

/// One row of a leaf along z: 8 floats as one vector value (the GCC/Clang vector
/// extension: a single code path, the compiler picks SSE, AVX or AVX-512 registers).
using Row = float __attribute__((vector_size(kDim * sizeof(float))));

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
    Row operator()(Row q) const {
        Row k;
        if constexpr (K == KernelType::Wyvill) {
            k = 1.0f + q * (-22.0f / 9.0f + q * (17.0f / 9.0f - q * (4.0f / 9.0f)));
        } else if constexpr (K == KernelType::Blinn) {
            for (int z = 0; z < kDim; ++z) k[z] = (std::exp(-sharpness * q[z]) - tail) * scale;
        } else {
            const Row s = 1.0f - q;
            k = s * s;
        }
        return q < 1.0f ? k : Row{};
    }
};

/// Sums every reaching globule into the 8^3 voxels of one block; @return a new leaf, or
/// nullptr when no voxel of the block lies inside an influence sphere.
template <KernelType K>
std::unique_ptr<LeafType> splatBlock(const GlobuleBins& bins, uint64_t key,
                                     const KernelEval<K>& kernel) {
    const auto block = GlobuleBins::unpack(key);
    const int64_t ox = block[0] * kDim, oy = block[1] * kDim, oz = block[2] * kDim;
    alignas(sizeof(Row)) float sum[kDim * kDim * kDim] = {};

    bins.forEachGlobuleNear(key, [&](uint32_t i) {
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
        Row qz;
        for (int z = 0; z < kDim; ++z) qz[z] = (float(z) - cz) * (float(z) - cz) * invR2;
        for (int x = x0; x <= x1; ++x) {
            const float qx = (float(x) - cx) * (float(x) - cx) * invR2;
            for (int y = y0; y <= y1; ++y) {
                const float qxy = qx + (float(y) - cy) * (float(y) - cy) * invR2;
                if (qxy >= 1.0f) continue;
                float* row =
                    sum + (x << (2 * GlobuleBins::kBlockLog2)) + (y << GlobuleBins::kBlockLog2);
                Row values;
                std::memcpy(&values, row, sizeof values);
                values += kernel(qxy + qz);
                std::memcpy(row, &values, sizeof values);
            }
        }
    });
    bool touched = false;
    for (float v : sum) touched |= v > 0.0f;
    if (!touched) return nullptr;

    auto leaf = std::make_unique<LeafType>(openvdb::Coord(int(ox), int(oy), int(oz)), 0.0f, false);
    float* values = leaf->buffer().data();
    for (int v = 0; v < kDim * kDim * kDim; ++v) {
        values[v] = sum[v];
        if (sum[v] > 0.0f) leaf->setValueOn(openvdb::Index(v));
    }
    return leaf;
}

template <KernelType K>
void splatAll(const GlobuleBins& bins, const MetaballKernel& kernel,
              std::vector<std::unique_ptr<LeafType>>& leaves) {
    const KernelEval<K> eval(kernel);
    const auto& blocks = bins.candidateBlocks();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 16), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            leaves[b] = splatBlock<K>(bins, blocks[b], eval);
        }
    });
}

}  // namespace

FloatGrid::Ptr splatMetaballs(const Globules& globules, const MetaballKernel& kernel,
                              double influence, double voxelSize) {
    const GlobuleBins bins(globules, voxelSize, influence);
    std::vector<std::unique_ptr<LeafType>> leaves(bins.candidateBlocks().size());
    switch (kernel.type) {
        case KernelType::Wyvill:
            splatAll<KernelType::Wyvill>(bins, kernel, leaves);
            break;
        case KernelType::Blinn:
            splatAll<KernelType::Blinn>(bins, kernel, leaves);
            break;
        case KernelType::Murakami:
            splatAll<KernelType::Murakami>(bins, kernel, leaves);
            break;
    }

    auto grid = FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
    grid->setName("field");
    // Inserting finished leaves is a pointer hand-over per leaf: serial and cheap.
    auto& tree = grid->tree();
    for (auto& leaf : leaves) {
        if (leaf) tree.addLeaf(leaf.release());
    }
    return grid;
}

}  // namespace globular
