// Splatting globules into a sparse metaball field, one OpenVDB leaf at a time.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>

#include "errors.h"
#include "globule_bins.h"
#include "splat_kernel.h"
#include "surface_grids.h"

namespace globular {

namespace {

using openvdb::FloatGrid;
using LeafType = openvdb::FloatTree::LeafNodeType;
static_assert(LeafType::DIM == GlobuleBins::kBlockDim, "bins must match the tree's leaves");
constexpr int kDim = GlobuleBins::kBlockDim;

using VoxelMask = LeafType::NodeMaskType;

/// The voxels of a block's @p sum that some influence sphere reached (sum > 0): the
/// active voxels of its leaves. Built a 64-bit word at a time (its bit order is the voxel
/// order).
VoxelMask reachedVoxels(const float* sum) {
    VoxelMask reached;
    for (openvdb::Index w = 0; w < VoxelMask::WORD_COUNT; ++w) {
        uint64_t bits = 0;
        for (int b = 0; b < 64; ++b) bits |= uint64_t(sum[w * 64 + b] > 0.0f) << b;
        reached.getWord<uint64_t>(w) = bits;
    }
    return reached;
}

/// A leaf holding @p values, active at @p active.
std::unique_ptr<LeafType> makeLeaf(const openvdb::Coord& origin, const float* values,
                                   const VoxelMask& active) {
    // Partial: the buffer is not filled with the background only to be overwritten.
    auto leaf = std::make_unique<LeafType>(openvdb::PartialCreate(), origin, 0.0f, false);
    leaf->buffer().allocate();
    std::memcpy(leaf->buffer().data(), values, LeafType::SIZE * sizeof(float));
    leaf->setValueMask(active);
    return leaf;
}

/// The leaf of one block summed from nearOrder()[0] by @p add (splat_kernel.h), and with kMean the
/// leaves of each channel's sum(w value) in @p weighted[c * blocks + b]; nullptr when no
/// voxel of the block lies inside an influence sphere. @p next: where the sum stopped.
template <bool kMean>
std::unique_ptr<LeafType> splatBlock(const GlobuleBins& bins, std::size_t b, AddGlobules add,
                                     const MetaballKernel& kernel, const SplatChannels& channels,
                                     float deepAbove, std::size_t& next,
                                     std::vector<std::unique_ptr<LeafType>>& weighted) {
    const uint64_t key = bins.candidateBlocks()[b];
    const auto block = GlobuleBins::unpack(key);
    constexpr int kVoxels = kDim * kDim * kDim;
    alignas(sizeof(SplatRow)) float sum[kVoxels] = {};
    alignas(sizeof(SplatRow)) float weightedSum[kMean ? kMaxSplatChannels * kVoxels : 1] = {};
    BlockSums out{sum};
    if constexpr (kMean) {
        out.channels = &channels;
        for (int c = 0; c < channels.count; ++c) out.weighted[c] = weightedSum + c * kVoxels;
    }
    next = add(bins, key, kernel, out, 0, deepAbove, VoxelBox{});
    const VoxelMask reached = reachedVoxels(sum);
    if (reached.isOff()) return nullptr;

    const openvdb::Coord origin(int(block[0] * kDim), int(block[1] * kDim), int(block[2] * kDim));
    if constexpr (kMean) {
        const std::size_t blocks = bins.candidateBlocks().size();
        for (int c = 0; c < channels.count; ++c) {
            weighted[std::size_t(c) * blocks + b] = makeLeaf(origin, out.weighted[c], reached);
        }
    }
    return makeLeaf(origin, sum, reached);
}

/// The voxels of a block within @p depth voxels (Chebyshev) of those of its neighbours
/// @p open holds ([(dx+1)*9 + (dy+1)*3 + dz+1], the block itself at 13 unused): their
/// bounding box, the whole block for a depth of a block or more.
VoxelBox voxelsNear(const std::array<bool, 27>& open, int depth) {
    if (depth >= kDim) return VoxelBox{};
    VoxelBox box;
    for (int a = 0; a < 3; ++a) box.lo[a] = kDim, box.hi[a] = -1;
    for (int n = 0; n < 27; ++n) {
        if (n == 13 || !open[std::size_t(n)]) continue;
        const int d[3] = {n / 9 - 1, n / 3 % 3 - 1, n % 3 - 1};
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = std::min(box.lo[a], d[a] > 0 ? kDim - depth : 0);
            box.hi[a] = std::max(box.hi[a], d[a] < 0 ? depth - 1 : kDim - 1);
        }
    }
    return box;
}

/// Splats every block into @p leaves and, with kMean, each channel's sum(w value) into
/// @p weighted (channel c of block b at c * blocks + b).
template <bool kMean>
void splatAll(const GlobuleBins& bins, const MetaballKernel& kernel, const SplatChannels& channels,
              float deepAbove, int exactDepth, std::vector<std::unique_ptr<LeafType>>& leaves,
              std::vector<std::unique_ptr<LeafType>>& weighted) {
    const AddGlobules add = splatKernels(activeSimdPath()).add[int(kernel.type)][kMean];
    const auto& blocks = bins.candidateBlocks();
    const std::size_t complete = bins.nearOrder().size();
    std::vector<uint32_t> next(blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 16), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            std::size_t n;
            leaves[b] = splatBlock<kMean>(bins, b, add, kernel, channels, deepAbove, n, weighted);
            next[b] = uint32_t(n);
        }
    });
    if (!std::isfinite(deepAbove)) return;
    // A block whose sum stopped early keeps its partial values only when its 26
    // neighbours are above deepAbove everywhere as well: then no voxel within a block of
    // it is at or below, and nothing near the iso surface reads its values. Otherwise
    // its sum goes on where it stopped, in the same order, over its voxels within
    // exactDepth of the neighbours that are not (the only ones that can lie within
    // exactDepth of a voxel at or below): bit-identical to a full sum there.
    auto isAbove = [&](std::size_t b) {
        return next[b] < complete || (leaves[b] && allAbove(leaves[b]->buffer().data(), deepAbove));
    };
    std::vector<uint8_t> above(blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 64), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) above[b] = isAbove(b);
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 16), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            if (next[b] == complete) continue;
            const auto c = GlobuleBins::unpack(blocks[b]);
            std::array<bool, 27> open{};  // neighbours that may hold voxels at or below
            bool deep = true;
            for (int n = 0; n < 27; ++n) {
                if (n == 13) continue;
                const uint64_t key =
                    GlobuleBins::pack(c[0] + n / 9 - 1, c[1] + n / 3 % 3 - 1, c[2] + n % 3 - 1);
                auto it = std::lower_bound(blocks.begin(), blocks.end(), key);
                open[std::size_t(n)] =
                    it == blocks.end() || *it != key || !above[std::size_t(it - blocks.begin())];
                deep &= !open[std::size_t(n)];
            }
            if (deep) continue;
            LeafType& leaf = *leaves[b];
            float* sum = leaf.buffer().data();
            BlockSums out{sum};
            if constexpr (kMean) {
                out.channels = &channels;
                for (int c = 0; c < channels.count; ++c) {
                    out.weighted[c] = weighted[std::size_t(c) * blocks.size() + b]->buffer().data();
                }
            }
            add(bins, blocks[b], kernel, out, next[b], INFINITY, voxelsNear(open, exactDepth));
            // Kernel values are >= 0: the voxels reached so far stay reached.
            const VoxelMask reached = reachedVoxels(sum);
            leaf.setValueMask(reached);
            if constexpr (kMean) {
                for (int c = 0; c < channels.count; ++c) {
                    weighted[std::size_t(c) * blocks.size() + b]->setValueMask(reached);
                }
            }
        }
    });
}

FloatGrid::Ptr gridOf(std::vector<std::unique_ptr<LeafType>>& leaves, double voxelSize,
                      const char* name) {
    auto grid = FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
    grid->setName(name);
    // Inserting finished leaves is a pointer hand-over per leaf: serial and cheap.
    auto& tree = grid->tree();
    for (auto& leaf : leaves) {
        if (leaf) tree.addLeaf(leaf.release());
    }
    return grid;
}

void checkExactDepth(int exactDepth) {
    if (exactDepth < 1) {
        throw Error("splatMetaballs: exactDepth " + std::to_string(exactDepth) +
                    " (at least 1 voxel)");
    }
}

}  // namespace

FloatGrid::Ptr splatMetaballs(const Globules& globules, const MetaballKernel& kernel,
                              double influence, double voxelSize, double deepAbove,
                              int exactDepth) {
    checkExactDepth(exactDepth);
    const GlobuleBins bins(globules, voxelSize, influence);
    std::vector<std::unique_ptr<LeafType>> leaves(bins.candidateBlocks().size()), unused;
    splatAll<false>(bins, kernel, SplatChannels{}, float(deepAbove), exactDepth, leaves, unused);
    return gridOf(leaves, voxelSize, "field");
}

MeanSplat splatMetaballsWithMean(const Globules& globules,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double influence,
                                 double voxelSize, double deepAbove, int exactDepth) {
    return splatMetaballsWithMean(globules, GlobuleBins(globules, voxelSize, influence), values,
                                  kernel, voxelSize, deepAbove, exactDepth);
}

MeanSplat splatMetaballsWithMean(const Globules& globules, const GlobuleBins& bins,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double voxelSize,
                                 double deepAbove, int exactDepth) {
    checkExactDepth(exactDepth);
    if (values.empty() || values.size() > std::size_t(kMaxSplatChannels)) {
        throw Error("splatMetaballsWithMean: " + std::to_string(values.size()) +
                    " value arrays (1 to " + std::to_string(kMaxSplatChannels) + ")");
    }
    SplatChannels channels;
    for (const auto* v : values) {
        if (v->size() != globules.size()) {
            throw Error("splatMetaballsWithMean: " + std::to_string(v->size()) +
                        " values for " + std::to_string(globules.size()) + " globules");
        }
        channels.value[channels.count++] = v->data();
    }
    const std::size_t blocks = bins.candidateBlocks().size();
    std::vector<std::unique_ptr<LeafType>> leaves(blocks), weighted(values.size() * blocks);
    splatAll<true>(bins, kernel, channels, float(deepAbove), exactDepth, leaves, weighted);
    // sum(w value) / sum(w) where the field is; the background elsewhere.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 64), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            if (!leaves[b]) continue;
            const float* sum = leaves[b]->buffer().data();
            for (std::size_t c = 0; c < values.size(); ++c) {
                float* mean = weighted[c * blocks + b]->buffer().data();
                for (openvdb::Index v = 0; v < LeafType::SIZE; ++v) {
                    mean[v] = sum[v] > 0.0f ? mean[v] / sum[v] : 0.0f;
                }
            }
        }
    });
    MeanSplat splat{gridOf(leaves, voxelSize, "field"), {}};
    for (std::size_t c = 0; c < values.size(); ++c) {
        std::vector<std::unique_ptr<LeafType>> channel(
            std::make_move_iterator(weighted.begin() + std::ptrdiff_t(c * blocks)),
            std::make_move_iterator(weighted.begin() + std::ptrdiff_t((c + 1) * blocks)));
        splat.means.push_back(gridOf(channel, voxelSize, "mean"));
    }
    return splat;
}

}  // namespace globular
