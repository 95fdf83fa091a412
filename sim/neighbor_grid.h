#pragma once
// Uniform-grid neighbour search (cell lists) over an unbounded domain. Rows of cells
// (fixed y and z) are hashed into a table of 0.5-1 bucket per point; points are
// counting-sorted by row bucket and, within a bucket, by x cell. The three x-adjacent
// cells of a row are then one contiguous run, so a query is at most 9 runs — long,
// contiguous loops for the vectorised force kernel — and a rebuild is O(N) (plus small
// per-bucket sorts) with O(N) memory however far points fly.
// Every point within one cell edge of a query point is visited exactly once; hash
// collisions add far-away candidates, which callers reject by distance (the force loop
// tests every candidate against the reach anyway).
// \see Hoetzlein, "Fast Fixed-Radius Nearest Neighbors", GTC 2014 (counting-sort grid).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace globular {

class NeighborGrid {
public:
    using Run = std::pair<uint32_t, uint32_t>;  ///< [begin, end) in sortedOrder()
    static constexpr int kMaxRuns = 9;
    /// x cells are this many times narrower than a cell: a run then spans 2.5 cells of x
    /// instead of 3 (17% fewer candidates) and stays one contiguous run. Measured faster;
    /// splitting y and z as well (25 short runs) measured slower.
    static constexpr int kXSplit = 2;

    /// Bins @p n points into cells of edge @p cellSize (world units, > 0).
    void build(const float* px, const float* py, const float* pz, std::size_t n,
               float cellSize);

    /// The runs of sortedOrder() holding every point in the 27 cells around (x, y, z),
    /// each point at most once. @return the number of runs.
    int neighborRuns(float x, float y, float z, std::array<Run, kMaxRuns>& out) const;

    /// The last query's rows and runs. A query further along the same row of cells (the
    /// order in which the force loop visits cells) advances the runs instead of hashing
    /// and searching again.
    struct RunCursor {
        bool valid = false;
        int32_t cx = 0, cy = 0, cz = 0;
        int count = 0;
        std::array<uint32_t, 9> bucket{};
        std::array<Run, 9> run{};
    };
    /// neighborRuns, the same result, faster for queries in grid order.
    int neighborRuns(float x, float y, float z, RunCursor& cursor,
                     std::array<Run, kMaxRuns>& out) const;

    /// Calls visit(j) for every point j in the cells within one cell of (x, y, z), each
    /// exactly once, in an order that depends only on the point set (not on threads).
    template <typename Visit>
    void forEachCandidate(float x, float y, float z, Visit&& visit) const {
        std::array<Run, kMaxRuns> runs;
        const int count = neighborRuns(x, y, z, runs);
        for (int r = 0; r < count; ++r) {
            for (uint32_t k = runs[r].first; k < runs[r].second; ++k) visit(mSorted[k]);
        }
    }

    /// Calls visit(first, last, bucket) for the run [first, last) of sortedOrder() of each
    /// cell's points, in grid order: a maximal run of points that share a cell (cellOf).
    /// @p py, @p pz: the points' y and z in grid order (for the rare bucket whose points
    /// lie in several rows of cells). @p bucket: the hashed row's, which no other row of
    /// cells shares unless their points interleave in it.
    template <typename Visit>
    void forEachCellRun(const float* py, const float* pz, Visit&& visit) const {
        const int32_t* cellX = mSortedCellX.data();
        for (uint32_t b = 0; b + 1 < mBucketStart.size(); ++b) {
            const uint32_t begin = mBucketStart[b], end = mBucketStart[b + 1];
            if (begin == end) continue;
            uint32_t first = begin;
            for (uint32_t k = begin + 1; k < end; ++k) {
                const bool newCell =
                    cellX[k] != cellX[k - 1] ||
                    (mSeveralRows[b] && (cellCoord(py[k]) != cellCoord(py[k - 1]) ||
                                         cellCoord(pz[k]) != cellCoord(pz[k - 1])));
                if (newCell) {
                    visit(first, k, b);
                    first = k;
                }
            }
            visit(first, end, b);
        }
    }

    /// Integer coordinates of the cell holding (x, y, z).
    std::array<int32_t, 3> cellOf(float x, float y, float z) const {
        return {cellCoordX(x), cellCoord(y), cellCoord(z)};
    }
    float cellSize() const { return mCellSize; }
    /// Point indices in grid order: a cache-friendly traversal order.
    const std::vector<uint32_t>& sortedOrder() const { return mSorted; }

private:
    uint32_t rowBucket(int32_t cy, int32_t cz) const;
    /// Cell coordinate; non-finite values map to cell 0 and absurd ones (beyond 2^30
    /// cells, ~1e9 world units) to the last cell (the simulation stops on non-finite or
    /// runaway state anyway, but the grid must not invoke undefined behaviour).
    int32_t cellCoord(float v) const { return toCell(v * mInvCellSize); }
    int32_t cellCoordX(float v) const { return toCell(v * (mInvCellSize * kXSplit)); }
    static int32_t toCell(float scaled) {
        constexpr float kLimit = 1 << 30;
        const float c = std::floor(scaled);
        if (!(c == c)) return 0;
        return int32_t(std::clamp(c, -kLimit, kLimit));
    }

    float mCellSize = 1, mInvCellSize = 1;
    uint32_t mMask = 0;
    std::vector<uint32_t> mBucketStart;  ///< size buckets + 1
    std::vector<uint32_t> mSorted;       ///< point indices grouped by bucket, then x cell
    std::vector<int32_t> mSortedCellX;   ///< x sub-cell (cellCoordX) of each sorted point
    std::vector<uint8_t> mSeveralRows;   ///< per bucket: its points lie in several rows
};

}  // namespace globular
