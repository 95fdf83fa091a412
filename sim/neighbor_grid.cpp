#include "neighbor_grid.h"

#include <algorithm>

#include "errors.h"

namespace globular {

uint32_t NeighborGrid::rowBucket(int32_t cy, int32_t cz) const {
    // Teschner et al. 2003 spatial hash primes.
    const uint64_t h = uint64_t(int64_t(cy)) * 19349663u ^ uint64_t(int64_t(cz)) * 83492791u;
    return uint32_t(h ^ (h >> 29)) & mMask;
}

void NeighborGrid::build(const float* px, const float* py, const float* pz, std::size_t n,
                         float cellSize) {
    if (!(cellSize > 0) || !std::isfinite(cellSize)) {
        throw Error("neighbour grid: cell size must be a positive finite number");
    }
    mCellSize = cellSize;
    mInvCellSize = 1.0f / cellSize;
    // One bucket per point at most (a point per row, e.g. a thin falling stream): rows
    // rarely share a bucket, yet the table costs at most 8 bytes per point.
    uint32_t buckets = 64;
    while (buckets < n) buckets *= 2;
    mMask = buckets - 1;

    // Counting sort by bucket. The fill pointers are the bucket starts themselves: after
    // the fill each holds its bucket's end, i.e. the next bucket's start, and one shift
    // restores them. Hashes are recomputed rather than stored: no per-point scratch.
    mBucketStart.assign(buckets + 1, 0);
    const auto bucketOf = [&](std::size_t i) { return rowBucket(cellCoord(py[i]), cellCoord(pz[i])); };
    for (std::size_t i = 0; i < n; ++i) ++mBucketStart[bucketOf(i) + 1];
    for (uint32_t b = 0; b < buckets; ++b) mBucketStart[b + 1] += mBucketStart[b];
    mSorted.resize(n);
    for (std::size_t i = 0; i < n; ++i) mSorted[mBucketStart[bucketOf(i)]++] = uint32_t(i);
    std::copy_backward(mBucketStart.begin(), mBucketStart.end() - 1, mBucketStart.end());
    mBucketStart[0] = 0;

    // Within a bucket, order by x cell (ties by index: deterministic).
    std::vector<std::pair<int32_t, uint32_t>> keyed;
    mSortedCellX.resize(n);
    for (uint32_t b = 0; b < buckets; ++b) {
        const uint32_t begin = mBucketStart[b], end = mBucketStart[b + 1];
        if (end - begin > 1) {
            keyed.clear();
            for (uint32_t k = begin; k < end; ++k) {
                keyed.emplace_back(cellCoordX(px[mSorted[k]]), mSorted[k]);
            }
            std::sort(keyed.begin(), keyed.end());
            for (uint32_t k = begin; k < end; ++k) {
                mSortedCellX[k] = keyed[k - begin].first;
                mSorted[k] = keyed[k - begin].second;
            }
        } else if (end == begin + 1) {
            mSortedCellX[begin] = cellCoordX(px[mSorted[begin]]);
        }
    }
}

int NeighborGrid::neighborRuns(float x, float y, float z, std::array<Run, kMaxRuns>& out) const {
    const int32_t cx = cellCoordX(x), cy = cellCoord(y), cz = cellCoord(z);
    std::array<uint32_t, 9> buckets;
    int count = 0;
    for (int32_t dz = -1; dz <= 1; ++dz)
        for (int32_t dy = -1; dy <= 1; ++dy) buckets[count++] = rowBucket(cy + dy, cz + dz);
    std::sort(buckets.begin(), buckets.end());
    count = int(std::unique(buckets.begin(), buckets.end()) - buckets.begin());
    int runs = 0;
    const int32_t* cells = mSortedCellX.data();
    for (int b = 0; b < count; ++b) {
        const int32_t* first = cells + mBucketStart[buckets[b]];
        const int32_t* last = cells + mBucketStart[buckets[b] + 1];
        const int32_t* lo = std::lower_bound(first, last, cx - kXSplit);
        const int32_t* hi = std::upper_bound(lo, last, cx + kXSplit);
        if (lo != hi) out[runs++] = {uint32_t(lo - cells), uint32_t(hi - cells)};
    }
    return runs;
}

}  // namespace globular
