#include "cell_schedule.h"

#include <gtest/gtest.h>

#include <vector>

#include "emitter.h"
#include "globules.h"

using namespace globular;

namespace {

/// @p n globules uniformly in a box reaching @p extent either side of the origin in x and
/// @p height in y and z, shifted by @p offset on every axis, in the grid's order once
/// @p grid is built over them.
Globules sortedCloud(std::size_t n, double extent, double height, double offset, uint64_t seed,
                     float cellSize, NeighborGrid& grid) {
    Jitter rng(seed);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        g.add({offset + extent * rng.next(), offset + height * rng.next(),
               offset + height * rng.next()},
              {0, 0, 0}, 1.0f, 1.0f, int32_t(i));
    }
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), cellSize);
    std::vector<float> scratch(g.size());
    g.permute(grid.sortedOrder(), scratch);
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), cellSize);
    return g;
}

CellSchedule scheduleOf(const NeighborGrid& grid, const Globules& g) {
    CellSchedule schedule;
    schedule.build(grid, g.px.data(), g.py.data(), g.pz.data(), g.size());
    return schedule;
}

struct Cloud {
    const char* what;
    std::size_t n;
    double extent, height, offset;
};

// Dense, about the origin (cells of both signs); sparse (rows share buckets); a long thin
// bar (few, long rows).
const Cloud kClouds[] = {{"dense", 4000, 6.0, 6.0, 0.0},
                         {"sparse", 600, 40.0, 40.0, 0.0},
                         {"bar", 3000, 350.0, 3.0, 500.0}};

}  // namespace

TEST(CellSchedule, GroupsAreTheCellsInGridOrder) {
    for (const Cloud& c : kClouds) {
        NeighborGrid grid;
        const Globules g = sortedCloud(c.n, c.extent, c.height, c.offset, 3, 3.0f, grid);
        const CellSchedule schedule = scheduleOf(grid, g);
        const auto cellOf = [&](uint32_t k) { return grid.cellOf(g.px[k], g.py[k], g.pz[k]); };
        uint32_t next = 0;
        for (const CellSchedule::Group& group : schedule.groups()) {
            ASSERT_EQ(group.first, next) << c.what;
            ASSERT_LT(group.first, group.last) << c.what;
            for (uint32_t k = group.first + 1; k < group.last; ++k) {
                ASSERT_EQ(cellOf(k), cellOf(group.first)) << c.what << " globule " << k;
            }
            if (group.last < g.size()) {  // maximal: the next globule is in another cell
                ASSERT_NE(cellOf(group.last), cellOf(group.first)) << c.what;
            }
            next = group.last;
        }
        EXPECT_EQ(next, g.size()) << c.what;
    }
}

// The promise the loop that evaluates each pair once rests on: every group is visited
// once, and no globule lies within a cell edge (the longest reach of any pair) of
// members of two different tasks of one colour, so that the tasks of a colour never write
// one globule. Fails with fewer colours (the z or the y modulus dropped).
TEST(CellSchedule, TasksOfAColourWriteApart) {
    for (const Cloud& c : kClouds) {
        const float cellSize = 3.0f;
        NeighborGrid grid;
        const Globules g = sortedCloud(c.n, c.extent, c.height, c.offset, 9, cellSize, grid);
        const CellSchedule schedule = scheduleOf(grid, g);
        std::vector<int> visits(schedule.groups().size(), 0);
        std::size_t tasksSeen = 0, clashes = 0;
        for (int colour = 0; colour < CellSchedule::kColours; ++colour) {
            const auto [begin, end] = schedule.colourTasks(colour);
            tasksSeen += end - begin;
            std::vector<int64_t> writer(g.size(), -1);  // the task of this colour reaching it
            for (uint32_t task = begin; task < end; ++task) {
                const auto [first, last] = schedule.taskGroups(task);
                ASSERT_LT(first, last) << c.what;
                for (const uint32_t* q = first; q != last; ++q) {
                    ++visits[*q];
                    const CellSchedule::Group& group = schedule.groups()[*q];
                    for (uint32_t i = group.first; i < group.last; ++i) {
                        grid.forEachCandidate(g.px[i], g.py[i], g.pz[i], [&](uint32_t j) {
                            const float dx = g.px[i] - g.px[j], dy = g.py[i] - g.py[j],
                                        dz = g.pz[i] - g.pz[j];
                            if (dx * dx + dy * dy + dz * dz >= cellSize * cellSize) return;
                            if (writer[j] >= 0 && writer[j] != task && clashes++ == 0) {
                                ADD_FAILURE() << c.what << ": globule " << j
                                              << " in reach of tasks " << writer[j] << " and "
                                              << task << " of colour " << colour;
                            }
                            writer[j] = task;
                        });
                    }
                }
            }
        }
        EXPECT_EQ(clashes, 0u) << c.what;
        EXPECT_EQ(tasksSeen, schedule.taskCount()) << c.what;
        for (std::size_t q = 0; q < visits.size(); ++q) {
            ASSERT_EQ(visits[q], 1) << c.what << " group " << q;
        }
    }
}

// The loop queries each group's runs in the schedule's order, row by row and, where rows
// share a bucket, back and forth between them; a cursor carried along must give what a
// fresh query gives.
TEST(CellSchedule, RunCursorAgreesInTheSchedulesOrder) {
    for (const Cloud& c : kClouds) {
        NeighborGrid grid;
        const Globules g = sortedCloud(c.n, c.extent, c.height, c.offset, 5, 3.0f, grid);
        const CellSchedule schedule = scheduleOf(grid, g);
        NeighborGrid::RunCursor cursor;
        std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> fresh, advanced;
        for (uint32_t task = 0; task < schedule.taskCount(); ++task) {
            const auto [first, last] = schedule.taskGroups(task);
            for (const uint32_t* q = first; q != last; ++q) {
                const uint32_t i = schedule.groups()[*q].first;
                const int n = grid.neighborRuns(g.px[i], g.py[i], g.pz[i], fresh);
                ASSERT_EQ(grid.neighborRuns(g.px[i], g.py[i], g.pz[i], cursor, advanced), n);
                for (int r = 0; r < n; ++r) ASSERT_EQ(advanced[r], fresh[r]) << c.what;
            }
        }
    }
}

TEST(CellSchedule, NoGlobulesNoTasks) {
    NeighborGrid grid;
    grid.build(nullptr, nullptr, nullptr, 0, 1.0f);
    CellSchedule schedule;
    schedule.build(grid, nullptr, nullptr, nullptr, 0);
    EXPECT_TRUE(schedule.groups().empty());
    EXPECT_EQ(schedule.taskCount(), 0u);
    for (int colour = 0; colour < CellSchedule::kColours; ++colour) {
        EXPECT_EQ(schedule.colourTasks(colour).first, schedule.colourTasks(colour).second);
    }
}
