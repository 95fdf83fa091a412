#include "cell_schedule.h"

namespace globular {

namespace {

/// @p v modulo 3, in [0, 3) for negative @p v too.
uint32_t mod3(int32_t v) { return uint32_t(((v % 3) + 3) % 3); }

}  // namespace

void CellSchedule::build(const NeighborGrid& grid, const float* px, const float* py,
                         const float* pz, std::size_t n) {
    mGroups.clear();
    mTaskStart.clear();
    mColourStart.fill(0);
    if (n == 0) {
        mOrder.clear();
        return;
    }
    // Each group's colour, from its row of cells, and task key, its row's bucket: a task
    // takes the groups of one colour in one bucket, a row's groups and those of any other
    // row of its colour that shares the bucket and so interleaves with it in grid order.
    mKeyed.clear();
    std::array<uint32_t, kColours + 1> fill{};
    grid.forEachCellRun(py, pz, [&](uint32_t first, uint32_t last, uint32_t bucket) {
        const auto cell = grid.cellOf(px[first], py[first], pz[first]);
        const uint32_t colour = mod3(cell[1]) * 3 + mod3(cell[2]);
        mKeyed.push_back({colour, bucket});
        mGroups.push_back({first, last});
        ++fill[colour + 1];
    });
    // Counting sort by colour, grid order kept within a colour: a task's groups are then
    // consecutive, and in grid order.
    for (int c = 0; c < kColours; ++c) fill[c + 1] += fill[c];
    mColourStart = fill;  // (in groups for now)
    mOrder.resize(mGroups.size());
    for (uint32_t g = 0; g < mGroups.size(); ++g) mOrder[fill[mKeyed[g].colour]++] = g;
    for (int c = 0; c < kColours; ++c) {
        const uint32_t begin = mColourStart[c], end = mColourStart[c + 1];
        mColourStart[c] = uint32_t(mTaskStart.size());
        for (uint32_t q = begin; q < end; ++q) {
            const Keyed& key = mKeyed[mOrder[q]];
            if (q == begin || key.bucket != mKeyed[mOrder[q - 1]].bucket) {
                mTaskStart.push_back(q);
            }
        }
    }
    mColourStart[kColours] = uint32_t(mTaskStart.size());
    mTaskStart.push_back(uint32_t(mOrder.size()));
}

}  // namespace globular
