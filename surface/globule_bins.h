#pragma once
// Globules binned by the 8x8x8-voxel block their centre lies in. A block is exactly an
// OpenVDB FloatTree leaf, so the splatter can build the field one leaf at a time:
// candidateBlocks() lists every leaf some influence sphere may reach, and
// forEachGlobuleNear(block) visits the globules that may reach that leaf. Each leaf then
// gathers its own sum (never a scatter into shared voxels), in an order that depends only
// on the globules, so the field is bit-identical for any thread count.
//
// The candidate count is also the stage's memory estimate: it bounds the leaves the field
// allocates before any allocation happens. OpenVDB-free.
//
// Index space follows OpenVDB's linear transform: voxel (i, j, k) is centred at world
// (i, j, k) * voxelSize, and block b holds voxels 8b .. 8b + 7 along each axis.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "globules.h"

namespace globular {

class GlobuleBins {
  public:
    static constexpr int kBlockLog2 = 3;  ///< matches openvdb::FloatTree's 8^3 leaves
    static constexpr int kBlockDim = 1 << kBlockLog2;
    /// Block coordinates are packed into 21 bits each, so voxel coordinates must stay
    /// within +-8 million of the origin.
    static constexpr int64_t kMaxBlockCoord = (int64_t(1) << 20) - 1;

    /// Bins @p globules for a field of voxels @p voxelSize (world units) where each globule
    /// reaches @p influence times its radius. Globules with a radius <= 0 add nothing and
    /// are left out.
    /// @throw SimulationError when a globule's position or radius is not finite.
    /// @throw ResourceError when a globule lies beyond the voxel coordinate range.
    GlobuleBins(const Globules& globules, double voxelSize, double influence);

    /// What binning @p globules would take, measured in O(n) without allocating, so a
    /// voxel far smaller than the globules is refused before the bins are built.
    struct Footprint {
        double largestBlocks = 0;  ///< blocks of the largest influence sphere's box: a
                                   ///< lower bound on the field's leaves
        double listedBlocks = 0;   ///< upper bound on the candidate list before merging
        double nearOrderSize = 0;  ///< entries of nearOrder()
        uint64_t bytes() const;    ///< memory the constructor takes at most (saturating)
    };
    static Footprint measure(const Globules& globules, double voxelSize, double influence);

    /// Keys of the blocks some influence sphere may reach, sorted ascending.
    const std::vector<uint64_t>& candidateBlocks() const { return mCandidates; }

    /// Calls visit(i) for each globule i whose influence may reach block @p blockKey: all
    /// globules centred within reach() blocks of it, in a thread-independent order: block
    /// by block in nearOrder(), nearest first (those that cover most of the block).
    template <typename Visit>
    void forEachGlobuleNear(uint64_t blockKey, Visit&& visit) const {
        for (const auto& offset : mOrder) forEachGlobuleIn(blockKey, offset, visit);
    }

    /// Offsets (dx, dy, dz, dx^2 + dy^2 + dz^2) of the blocks within reach() of a block,
    /// by increasing distance (the block itself, its 6 face neighbours, 12 edge
    /// neighbours, ...), then by offset.
    const std::vector<std::array<int, 4>>& nearOrder() const { return mOrder; }

    /// Calls visit(i) for each globule centred in block @p blockKey + @p offset, in index
    /// order.
    template <typename Visit>
    void forEachGlobuleIn(uint64_t blockKey, const std::array<int, 4>& offset,
                          Visit&& visit) const {
        const auto b = unpack(blockKey);
        const auto [begin, end] = cellRange(b[0] + offset[0], b[1] + offset[1], b[2] + offset[2]);
        for (uint32_t k = begin; k < end; ++k) visit(mSorted[k]);
    }

    /// Centre in index space (voxel units) and influence radius in voxels of globule @p i.
    double centreX(std::size_t i) const { return mCentre[3 * i]; }
    double centreY(std::size_t i) const { return mCentre[3 * i + 1]; }
    double centreZ(std::size_t i) const { return mCentre[3 * i + 2]; }
    float influenceVoxels(std::size_t i) const { return mInfluence[i]; }

    /// Blocks searched around a block in each direction: ceil(max influence / 8 voxels).
    int reach() const { return mReach; }
    /// Globules that take part (radius > 0).
    std::size_t binnedCount() const { return mSorted.size(); }

    static uint64_t pack(int64_t bx, int64_t by, int64_t bz);
    /// The packed key of the block holding index-space point (@p x, @p y, @p z).
    static uint64_t blockKeyAt(double x, double y, double z) {
        return pack(int64_t(std::floor(x)) >> kBlockLog2, int64_t(std::floor(y)) >> kBlockLog2,
                    int64_t(std::floor(z)) >> kBlockLog2);
    }
    static std::array<int64_t, 3> unpack(uint64_t key);

  private:
    std::pair<uint32_t, uint32_t> cellRange(int64_t bx, int64_t by, int64_t bz) const;

    std::vector<double> mCentre;       ///< x y z per globule, index space
    std::vector<float> mInfluence;     ///< per globule, voxels (0 when left out)
    std::vector<uint32_t> mSorted;     ///< binned globules ordered by (block, index)
    std::vector<uint64_t> mCellKeys;   ///< distinct centre blocks, ascending
    std::vector<uint32_t> mCellStart;  ///< mSorted range of each cell; size cells + 1
    std::vector<uint64_t> mCandidates;
    std::vector<std::array<int, 4>> mOrder;  ///< dx dy dz, dx^2+dy^2+dz^2: nearest first
    int mReach = 0;
};

}  // namespace globular
