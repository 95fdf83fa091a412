#pragma once
// The order in which the force loop visits the neighbour grid's cells when it evaluates
// each pair once (Newton's third law, each_pair_once.h). A cell's group of globules then
// writes forces not only to its members but also to their neighbours, all within one
// cell edge. The rows of cells (fixed y and z) are coloured by y and z modulo 3 (9
// colours): two rows of one colour are at least three cells apart in y or z, so what
// their groups write is disjoint. The colours run one after another, the rows of a colour
// in parallel, each row's groups in grid order by one thread: every globule then receives
// its terms in an order that depends only on the positions, never on the threads, and
// sums stay bit-identical on any thread count. Walking a row in grid order also lets the
// neighbour queries move along it (NeighborGrid::RunCursor).
// \see Plimpton, "Fast Parallel Algorithms for Short-Range Molecular Dynamics", J. Comp.
//      Phys. 117 (1995), for the half-neighbour (Newton) lists of molecular dynamics.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "neighbor_grid.h"

namespace globular {

class CellSchedule {
public:
    static constexpr int kColours = 9;

    /// A grid cell's group: a maximal run [first, last) of globules in grid order that
    /// share a cell (NeighborGrid::cellOf). A cell is one group but where hashed rows
    /// share a bucket and interleave.
    struct Group {
        uint32_t first, last;
    };

    /// Finds the groups of the @p n globules at (@p px, @p py, @p pz), which are in
    /// @p grid's order (NeighborGrid::sortedOrder applied), and orders them.
    void build(const NeighborGrid& grid, const float* px, const float* py, const float* pz,
               std::size_t n);

    /// The groups in grid order.
    const std::vector<Group>& groups() const { return mGroups; }

    /// The tasks of colour @p colour, [first, second). A task is the groups of one row,
    /// with those of any other row of its colour that interleave with them in grid order
    /// (a shared bucket), visited in grid order by one thread.
    std::pair<uint32_t, uint32_t> colourTasks(int colour) const {
        return {mColourStart[colour], mColourStart[colour + 1]};
    }
    /// The groups of task @p task: indices into groups(), ascending.
    std::pair<const uint32_t*, const uint32_t*> taskGroups(uint32_t task) const {
        return {mOrder.data() + mTaskStart[task], mOrder.data() + mTaskStart[task + 1]};
    }
    std::size_t taskCount() const { return mTaskStart.empty() ? 0 : mTaskStart.size() - 1; }

private:
    std::vector<Group> mGroups;
    std::vector<uint32_t> mOrder;      ///< group indices, task by task
    std::vector<uint32_t> mTaskStart;  ///< task t is mOrder[mTaskStart[t], mTaskStart[t + 1])
    std::array<uint32_t, kColours + 1> mColourStart{};
    /// Scratch kept between steps: each group's colour and task key.
    struct Keyed {
        uint32_t colour, bucket;
    };
    std::vector<Keyed> mKeyed;
};

}  // namespace globular
