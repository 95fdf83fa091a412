#include "crowded_cell.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace globular {

namespace {

int32_t cubeOf(float v, double inverseCell) {
    // floor(t) clamped to +-(2^31 - 1), NaN to 0; by truncation, not std::floor, which the
    // baseline instruction set has no instruction for.
    const double t = double(v) * inverseCell;
    if (!(t == t)) return 0;  // NaN
    if (t >= 2147483647.0) return 2147483647;
    if (t <= -2147483647.0) return -2147483647;
    const int32_t truncated = int32_t(t);
    return truncated - int32_t(double(truncated) > t);
}

uint64_t hashOf(int32_t x, int32_t y, int32_t z) {
    uint64_t h = uint64_t(uint32_t(x)) * 0x9E3779B97F4A7C15ull;
    h ^= uint64_t(uint32_t(y)) * 0xC2B2AE3D27D4EB4Full;
    h ^= uint64_t(uint32_t(z)) * 0x165667B19E3779F9ull;
    return h ^ (h >> 31);
}

}  // namespace

uint32_t CrowdedCell::most(const float* x, const float* y, const float* z, std::size_t n,
                           double cell) {
    const double inverse = 1.0 / cell;
    // Points in a run of one cube are counted together: in the simulation's grid order
    // (NeighborGrid) a cube's points mostly come together, so the table sees a run per
    // cube and row instead of a probe per point. The runs are found in parallel, a chunk
    // of points each; a run cut by a chunk's end is counted in two parts.
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    if (mRuns.size() < chunks) mRuns.resize(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        std::vector<Run>& runs = mRuns[c];
        runs.clear();
        const std::size_t end = std::min(n, (c + 1) * kChunk);
        Run run{0, 0, 0, 0};
        for (std::size_t i = c * kChunk; i < end; ++i) {
            const int32_t cx = cubeOf(x[i], inverse), cy = cubeOf(y[i], inverse),
                          cz = cubeOf(z[i], inverse);
            if (run.count > 0 && cx == run.x && cy == run.y && cz == run.z) {
                ++run.count;
                continue;
            }
            if (run.count > 0) runs.push_back(run);
            run = {cx, cy, cz, 1};
        }
        if (run.count > 0) runs.push_back(run);
    });
    std::size_t runs = 0;
    for (std::size_t c = 0; c < chunks; ++c) runs += mRuns[c].size();
    // At most half full, so a probe ends after a couple of slots; sized by the runs, which
    // in grid order are far fewer than the points. A call uses the first `size` slots, and
    // slots of earlier calls read as empty (their stamp), so none is cleared.
    const std::size_t size = std::bit_ceil(std::max<std::size_t>(2 * runs, 64));
    if (mSlots.size() < size) mSlots.assign(size, Slot{});
    if (mStamp == UINT32_MAX) {
        std::fill(mSlots.begin(), mSlots.end(), Slot{});
        mStamp = 0;
    }
    ++mStamp;
    const std::size_t mask = size - 1;
    uint32_t most = 0;
    for (std::size_t c = 0; c < chunks; ++c) {
        for (const Run& run : mRuns[c]) {
            for (std::size_t s = hashOf(run.x, run.y, run.z) & mask;; s = (s + 1) & mask) {
                Slot& slot = mSlots[s];
                if (slot.stamp != mStamp) slot = {run.x, run.y, run.z, 0, mStamp};
                if (slot.x == run.x && slot.y == run.y && slot.z == run.z) {
                    slot.count += run.count;
                    most = std::max(most, slot.count);
                    break;
                }
            }
        }
    }
    return most;
}

}  // namespace globular
