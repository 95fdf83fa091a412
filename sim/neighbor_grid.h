#pragma once
// Uniform-grid neighbour search (cell lists) over an unbounded domain. Cells of a fixed
// edge are hashed into a table about twice the globule count, and globules are counting-
// sorted by bucket, so a rebuild is O(N) and memory stays O(N) however far globules fly.
// A query visits the distinct buckets of the 27 cells around a point: every globule
// within one cell edge of the point is visited exactly once; hash collisions add
// far-away candidates, which callers reject by distance (the pair force's windows are
// zero beyond the cutoff, so they reject them for free).
// \see Hoetzlein, "Fast Fixed-Radius Nearest Neighbors", GTC 2014 (counting-sort grid).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace globular {

class NeighborGrid {
public:
    /// Bins @p n points into cells of edge @p cellSize (world units, > 0).
    void build(const float* px, const float* py, const float* pz, std::size_t n,
               float cellSize);

    /// Calls visit(j) for every point j in the cells within one cell of (x, y, z), each
    /// exactly once, in an order that depends only on the point set (not on threads).
    template <typename Visit>
    void forEachCandidate(float x, float y, float z, Visit&& visit) const {
        std::array<uint32_t, 27> buckets;
        const int count = neighborBuckets(x, y, z, buckets);
        for (int b = 0; b < count; ++b) {
            const uint32_t begin = mBucketStart[buckets[b]], end = mBucketStart[buckets[b] + 1];
            for (uint32_t k = begin; k < end; ++k) visit(mSorted[k]);
        }
    }

    /// The non-empty buckets around (x, y, z) as [begin, end) ranges of sortedOrder()
    /// positions, each bucket once. @return the number of ranges.
    int neighborRanges(float x, float y, float z,
                       std::array<std::pair<uint32_t, uint32_t>, 27>& out) const {
        std::array<uint32_t, 27> buckets;
        const int count = neighborBuckets(x, y, z, buckets);
        int ranges = 0;
        for (int b = 0; b < count; ++b) {
            const uint32_t begin = mBucketStart[buckets[b]], end = mBucketStart[buckets[b] + 1];
            if (begin != end) out[ranges++] = {begin, end};
        }
        return ranges;
    }
    /// Integer coordinates of the cell holding (x, y, z).
    std::array<int64_t, 3> cellOf(float x, float y, float z) const {
        return {cellCoord(x), cellCoord(y), cellCoord(z)};
    }

    float cellSize() const { return mCellSize; }
    /// Point indices ordered by bucket: a cache-friendly traversal order.
    const std::vector<uint32_t>& sortedOrder() const { return mSorted; }

private:
    uint32_t bucketOf(int64_t cx, int64_t cy, int64_t cz) const;
    int64_t cellCoord(float v) const { return int64_t(std::floor(v * mInvCellSize)); }
    /// The distinct buckets of the 27 surrounding cells, sorted; @return their count.
    int neighborBuckets(float x, float y, float z, std::array<uint32_t, 27>& out) const;

    float mCellSize = 1, mInvCellSize = 1;
    uint32_t mMask = 0;
    std::vector<uint32_t> mBucketStart;  ///< size buckets + 1
    std::vector<uint32_t> mSorted;       ///< point indices grouped by bucket
};

}  // namespace globular
