#include "neighbor_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>


#include "errors.h"
#include "simd_lanes.h"

namespace globular {

namespace {

/// Sorts @p keys (all distinct). Between steps few globules change cell, so a bucket is
/// usually sorted but for a few: insertion sort, which is linear then; std::sort when
/// it meets much disorder (the first step, or a scattered system).
void sortNearlySorted(std::vector<std::pair<int32_t, uint32_t>>& keys) {
    std::size_t moves = 0;
    const std::size_t budget = 8 * keys.size() + 64;
    for (std::size_t i = 1; i < keys.size(); ++i) {
        const auto key = keys[i];
        std::size_t j = i;
        for (; j > 0 && key < keys[j - 1]; --j) keys[j] = keys[j - 1];
        keys[j] = key;
        moves += i - j;
        if (moves > budget) {
            std::sort(keys.begin(), keys.end());
            return;
        }
    }
}

/// The first index in [from, last) whose cell is above @p bound (or last); @p cells is
/// sorted there. Runs move about one cell per query: a few elements, counted 16 at a
/// time with AVX-512 rather than in a loop whose exit the branch predictor misses.
uint32_t skipAtMost(const int32_t* cells, uint32_t from, uint32_t last, int32_t bound) {
#if defined(__AVX512F__)
    const __m512i limit = _mm512_set1_epi32(bound);
    while (from < last) {
        const uint32_t left = last - from;
        const __mmask16 live = firstLanes(left);
        const __m512i v = _mm512_maskz_loadu_epi32(live, cells + from);
        const uint32_t below = uint32_t(__builtin_popcount(_mm512_mask_cmple_epi32_mask(live, v, limit)));
        from += below;
        if (below < 16) break;
    }
#else
    while (from < last && cells[from] <= bound) ++from;
#endif
    return from;
}

}  // namespace

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
    // Half a bucket to one bucket per point. Rows of cells hold tens to hundreds of
    // points in a liquid, so rows seldom share a bucket; in the sparsest case (one point
    // per row, a thin stream) two rows share one and the runs carry some far candidates,
    // which the force loop rejects. The table costs 2-4 bytes per point.
    uint32_t buckets = 64;
    while (2 * buckets < n) buckets *= 2;
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

    // Within a bucket, order by x cell (ties by index: deterministic). Buckets are
    // independent: sorted in parallel.
    mSortedCellX.resize(n);
    mSeveralRows.assign(buckets, 0);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, buckets, 2048),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                          std::vector<std::pair<int32_t, uint32_t>> keyed;
                          for (uint32_t b = range.begin(); b != range.end(); ++b) {
                              const uint32_t begin = mBucketStart[b], end = mBucketStart[b + 1];
                              if (begin == end) continue;
                              keyed.clear();
                              const uint32_t head = mSorted[begin];
                              const int32_t rowY = cellCoord(py[head]), rowZ = cellCoord(pz[head]);
                              bool severalRows = false;
                              for (uint32_t k = begin; k < end; ++k) {
                                  const uint32_t i = mSorted[k];
                                  keyed.emplace_back(cellCoordX(px[i]), i);
                                  severalRows |=
                                      cellCoord(py[i]) != rowY || cellCoord(pz[i]) != rowZ;
                              }
                              mSeveralRows[b] = severalRows;
                              sortNearlySorted(keyed);
                              for (uint32_t k = begin; k < end; ++k) {
                                  mSortedCellX[k] = keyed[k - begin].first;
                                  mSorted[k] = keyed[k - begin].second;
                              }
                          }
                      });
}

int NeighborGrid::neighborRuns(float x, float y, float z, std::array<Run, kMaxRuns>& out) const {
    RunCursor cursor;
    return neighborRuns(x, y, z, cursor, out);
}

int NeighborGrid::neighborRuns(float x, float y, float z, RunCursor& cursor,
                               std::array<Run, kMaxRuns>& out) const {
    const int32_t cx = cellCoordX(x), cy = cellCoord(y), cz = cellCoord(z);
    const int32_t* cells = mSortedCellX.data();
    RunCursor& c = cursor;
    if (c.valid && c.cy == cy && c.cz == cz && cx >= c.cx) {
        // Further along the same row of cells: the runs only move forward.
        for (int b = 0; b < c.count; ++b) {
            const uint32_t last = mBucketStart[c.bucket[b] + 1];
            const uint32_t lo = skipAtMost(cells, c.run[b].first, last, cx - kXSplit - 1);
            const uint32_t hi = skipAtMost(cells, std::max(lo, c.run[b].second), last, cx + kXSplit);
            c.run[b] = {lo, hi};
        }
    } else {
        int count = 0;
        for (int32_t dz = -1; dz <= 1; ++dz)
            for (int32_t dy = -1; dy <= 1; ++dy) c.bucket[count++] = rowBucket(cy + dy, cz + dz);
        std::sort(c.bucket.begin(), c.bucket.end());
        c.count = int(std::unique(c.bucket.begin(), c.bucket.end()) - c.bucket.begin());
        for (int b = 0; b < c.count; ++b) {
            const int32_t* first = cells + mBucketStart[c.bucket[b]];
            const int32_t* last = cells + mBucketStart[c.bucket[b] + 1];
            const int32_t* lo = std::lower_bound(first, last, cx - kXSplit);
            const int32_t* hi = std::upper_bound(lo, last, cx + kXSplit);
            c.run[b] = {uint32_t(lo - cells), uint32_t(hi - cells)};
        }
        c.valid = true;
        c.cy = cy;
        c.cz = cz;
    }
    c.cx = cx;
    int runs = 0;
    for (int b = 0; b < c.count; ++b) {
        if (c.run[b].first != c.run[b].second) out[runs++] = c.run[b];
    }
    return runs;
}

}  // namespace globular
