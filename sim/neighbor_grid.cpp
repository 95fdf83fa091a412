#include "neighbor_grid.h"

#include <algorithm>

#include "errors.h"

namespace globular {

uint32_t NeighborGrid::bucketOf(int64_t cx, int64_t cy, int64_t cz) const {
    // Teschner et al. 2003 spatial hash primes.
    const uint64_t h = uint64_t(cx) * 73856093u ^ uint64_t(cy) * 19349663u ^
                       uint64_t(cz) * 83492791u;
    return uint32_t(h ^ (h >> 29)) & mMask;
}

void NeighborGrid::build(const float* px, const float* py, const float* pz, std::size_t n,
                         float cellSize) {
    if (!(cellSize > 0) || !std::isfinite(cellSize)) {
        throw Error("neighbour grid: cell size must be a positive finite number");
    }
    mCellSize = cellSize;
    mInvCellSize = 1.0f / cellSize;
    uint32_t buckets = 64;
    while (buckets < 2 * n) buckets *= 2;
    mMask = buckets - 1;

    std::vector<uint32_t> bucketOfPoint(n);
    mBucketStart.assign(buckets + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const uint32_t b = bucketOf(cellCoord(px[i]), cellCoord(py[i]), cellCoord(pz[i]));
        bucketOfPoint[i] = b;
        ++mBucketStart[b + 1];
    }
    for (uint32_t b = 0; b < buckets; ++b) mBucketStart[b + 1] += mBucketStart[b];
    mSorted.resize(n);
    std::vector<uint32_t> fill(mBucketStart.begin(), mBucketStart.end() - 1);
    for (std::size_t i = 0; i < n; ++i) mSorted[fill[bucketOfPoint[i]]++] = uint32_t(i);
}

int NeighborGrid::neighborBuckets(float x, float y, float z,
                                  std::array<uint32_t, 27>& out) const {
    const int64_t cx = cellCoord(x), cy = cellCoord(y), cz = cellCoord(z);
    int count = 0;
    for (int64_t dz = -1; dz <= 1; ++dz)
        for (int64_t dy = -1; dy <= 1; ++dy)
            for (int64_t dx = -1; dx <= 1; ++dx) out[count++] = bucketOf(cx + dx, cy + dy, cz + dz);
    std::sort(out.begin(), out.end());
    return int(std::unique(out.begin(), out.end()) - out.begin());
}

}  // namespace globular
