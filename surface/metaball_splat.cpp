// Splatting globules into a sparse metaball field, one OpenVDB leaf at a time.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "errors.h"
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

/// True when every value of a block's sum exceeds @p threshold.
bool allAbove(const float* sum, float threshold) {
    Row low;
    std::memcpy(&low, sum, sizeof low);
    for (int r = 1; r < kDim * kDim; ++r) {
        Row row;
        std::memcpy(&row, sum + r * kDim, sizeof row);
        low = low < row ? low : row;
    }
    bool result = true;
    for (int z = 0; z < kDim; ++z) result &= low[z] > threshold;
    return result;
}

/// At most this many per-globule values are averaged in one pass (a velocity's three
/// components and a temperature).
constexpr int kMaxChannels = 4;

/// The per-globule values averaged (kMean): one array per channel.
struct Channels {
    int count = 0;
    const float* value[kMaxChannels] = {};
};

/// What one block accumulates: the field's sum and, when per-globule values are
/// averaged (kMean), sum(w value) of each channel beside it, from the same kernel values.
struct BlockSums {
    float* sum;                                ///< 8^3 voxels
    float* weighted[kMaxChannels] = {};        ///< 8^3 voxels per channel; kMean only
    const Channels* channels = nullptr;        ///< kMean only
};

/// Adds the globules of the blocks nearOrder()[from...] into @p out, the 8^3 voxels of
/// one block. With a finite @p deepAbove, stops after a whole shell of blocks (those at
/// one distance) once every voxel exceeds it. @return the index in nearOrder() it
/// stopped at (its size when complete).
template <KernelType K, bool kMean>
std::size_t addGlobules(const GlobuleBins& bins, uint64_t key, const KernelEval<K>& kernel,
                        const BlockSums& out, std::size_t from, float deepAbove) {
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
        Row qz;
        for (int z = 0; z < kDim; ++z) qz[z] = (float(z) - cz) * (float(z) - cz) * invR2;
        for (int x = x0; x <= x1; ++x) {
            const float qx = (float(x) - cx) * (float(x) - cx) * invR2;
            for (int y = y0; y <= y1; ++y) {
                const float qxy = qx + (float(y) - cy) * (float(y) - cy) * invR2;
                if (qxy >= 1.0f) continue;
                const int offset =
                    (x << (2 * GlobuleBins::kBlockLog2)) + (y << GlobuleBins::kBlockLog2);
                const Row k = kernel(qxy + qz);
                Row values;
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

/// A leaf holding @p values, active where @p activeWhere > 0.
std::unique_ptr<LeafType> makeLeaf(const openvdb::Coord& origin, const float* values,
                                   const float* activeWhere) {
    auto leaf = std::make_unique<LeafType>(origin, 0.0f, false);
    std::memcpy(leaf->buffer().data(), values, LeafType::SIZE * sizeof(float));
    for (int v = 0; v < kDim * kDim * kDim; ++v) {
        if (activeWhere[v] > 0.0f) leaf->setValueOn(openvdb::Index(v));
    }
    return leaf;
}

/// The leaf of one block summed from nearOrder()[0] (see addGlobules), and with kMean the
/// leaves of each channel's sum(w value) in @p weighted[c * blocks + b]; nullptr when no
/// voxel of the block lies inside an influence sphere. @p next: where the sum stopped.
template <KernelType K, bool kMean>
std::unique_ptr<LeafType> splatBlock(const GlobuleBins& bins, std::size_t b,
                                     const KernelEval<K>& kernel, const Channels& channels,
                                     float deepAbove, std::size_t& next,
                                     std::vector<std::unique_ptr<LeafType>>& weighted) {
    const uint64_t key = bins.candidateBlocks()[b];
    const auto block = GlobuleBins::unpack(key);
    constexpr int kVoxels = kDim * kDim * kDim;
    alignas(sizeof(Row)) float sum[kVoxels] = {};
    alignas(sizeof(Row)) float weightedSum[kMean ? kMaxChannels * kVoxels : 1] = {};
    BlockSums out{sum};
    if constexpr (kMean) {
        out.channels = &channels;
        for (int c = 0; c < channels.count; ++c) out.weighted[c] = weightedSum + c * kVoxels;
    }
    next = addGlobules<K, kMean>(bins, key, kernel, out, 0, deepAbove);
    bool touched = false;
    for (float v : sum) touched |= v > 0.0f;
    if (!touched) return nullptr;

    const openvdb::Coord origin(int(block[0] * kDim), int(block[1] * kDim), int(block[2] * kDim));
    if constexpr (kMean) {
        const std::size_t blocks = bins.candidateBlocks().size();
        for (int c = 0; c < channels.count; ++c) {
            weighted[std::size_t(c) * blocks + b] = makeLeaf(origin, out.weighted[c], sum);
        }
    }
    return makeLeaf(origin, sum, sum);
}

/// Splats every block into @p leaves and, with kMean, each channel's sum(w value) into
/// @p weighted (channel c of block b at c * blocks + b).
template <KernelType K, bool kMean>
void splatAll(const GlobuleBins& bins, const MetaballKernel& kernel, const Channels& channels,
              float deepAbove, std::vector<std::unique_ptr<LeafType>>& leaves,
              std::vector<std::unique_ptr<LeafType>>& weighted) {
    const KernelEval<K> eval(kernel);
    const auto& blocks = bins.candidateBlocks();
    const std::size_t complete = bins.nearOrder().size();
    std::vector<uint32_t> next(blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 16), [&](auto range) {
        for (std::size_t b = range.begin(); b < range.end(); ++b) {
            std::size_t n;
            leaves[b] = splatBlock<K, kMean>(bins, b, eval, channels, deepAbove, n, weighted);
            next[b] = uint32_t(n);
        }
    });
    if (!std::isfinite(deepAbove)) return;
    // A block whose sum stopped early keeps its partial values only when its 26
    // neighbours are above deepAbove everywhere as well: then no voxel within a block of
    // it is at or below, and nothing near the iso surface reads its values. Otherwise
    // its sum goes on where it stopped, in the same order: bit-identical to a full sum.
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
            bool deep = true;
            for (int dx = -1; dx <= 1 && deep; ++dx) {
                for (int dy = -1; dy <= 1 && deep; ++dy) {
                    for (int dz = -1; dz <= 1 && deep; ++dz) {
                        const uint64_t key = GlobuleBins::pack(c[0] + dx, c[1] + dy, c[2] + dz);
                        auto it = std::lower_bound(blocks.begin(), blocks.end(), key);
                        deep = it != blocks.end() && *it == key &&
                               above[std::size_t(it - blocks.begin())];
                    }
                }
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
            addGlobules<K, kMean>(bins, blocks[b], eval, out, next[b], INFINITY);
            for (int v = 0; v < kDim * kDim * kDim; ++v) {
                if (sum[v] > 0.0f) {
                    leaf.setValueOn(openvdb::Index(v));
                    if constexpr (kMean) {
                        for (int c = 0; c < channels.count; ++c) {
                            weighted[std::size_t(c) * blocks.size() + b]->setValueOn(
                                openvdb::Index(v));
                        }
                    }
                }
            }
        }
    });
}

template <bool kMean>
void splatWithKernel(const GlobuleBins& bins, const MetaballKernel& kernel, const Channels& value,
                     float deepAbove, std::vector<std::unique_ptr<LeafType>>& leaves,
                     std::vector<std::unique_ptr<LeafType>>& weighted) {
    switch (kernel.type) {
        case KernelType::Wyvill:
            return splatAll<KernelType::Wyvill, kMean>(bins, kernel, value, deepAbove, leaves,
                                                       weighted);
        case KernelType::Blinn:
            return splatAll<KernelType::Blinn, kMean>(bins, kernel, value, deepAbove, leaves,
                                                      weighted);
        case KernelType::Murakami:
            return splatAll<KernelType::Murakami, kMean>(bins, kernel, value, deepAbove, leaves,
                                                         weighted);
    }
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

}  // namespace

FloatGrid::Ptr splatMetaballs(const Globules& globules, const MetaballKernel& kernel,
                              double influence, double voxelSize, double deepAbove) {
    const GlobuleBins bins(globules, voxelSize, influence);
    std::vector<std::unique_ptr<LeafType>> leaves(bins.candidateBlocks().size()), unused;
    splatWithKernel<false>(bins, kernel, Channels{}, float(deepAbove), leaves, unused);
    return gridOf(leaves, voxelSize, "field");
}

MeanSplat splatMetaballsWithMean(const Globules& globules,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double influence,
                                 double voxelSize, double deepAbove) {
    return splatMetaballsWithMean(globules, GlobuleBins(globules, voxelSize, influence), values,
                                  kernel, voxelSize, deepAbove);
}

MeanSplat splatMetaballsWithMean(const Globules& globules, const GlobuleBins& bins,
                                 const std::vector<const std::vector<float>*>& values,
                                 const MetaballKernel& kernel, double voxelSize,
                                 double deepAbove) {
    if (values.empty() || values.size() > std::size_t(kMaxChannels)) {
        throw Error("splatMetaballsWithMean: " + std::to_string(values.size()) +
                    " value arrays (1 to " + std::to_string(kMaxChannels) + ")");
    }
    Channels channels;
    for (const auto* v : values) {
        if (v->size() != globules.size()) {
            throw Error("splatMetaballsWithMean: " + std::to_string(v->size()) +
                        " values for " + std::to_string(globules.size()) + " globules");
        }
        channels.value[channels.count++] = v->data();
    }
    const std::size_t blocks = bins.candidateBlocks().size();
    std::vector<std::unique_ptr<LeafType>> leaves(blocks), weighted(values.size() * blocks);
    splatWithKernel<true>(bins, kernel, channels, float(deepAbove), leaves, weighted);
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
