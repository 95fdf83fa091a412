#pragma once
// The most points in any one cube of a lattice, counted exactly: the density that the
// adaptive step's contact bound (stable_step.h) follows.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace globular {

/// Counts points per cube of edge @p cell (cubes [k cell, (k + 1) cell) on each axis) in an
/// open-addressed table that keeps each cube's coordinates, so no two cubes share a count.
/// (A table that kept only hashes merged colliding cubes: on the 1e5 pour it reported
/// 1.6-2.0x the true count throughout, and the step followed.) Coordinates past +-2^31
/// cubes, and non-finite ones, share the outermost cube or cube 0: such counts can only
/// grow, never shrink. The result does not depend on the points' order. Consecutive points
/// in one cube are counted as a run (the simulation passes its globules in grid order,
/// where a cube's points mostly come together), chunks of points in parallel, and the table
/// sized by the runs: on the 1e5 block, 0.25 ms a call on two threads instead of 1 ms
/// (docs/performance.md).
class CrowdedCell {
public:
    /// The most of the @p n points (@p x, @p y, @p z) in one cube; 0 when n is 0.
    uint32_t most(const float* x, const float* y, const float* z, std::size_t n, double cell);

private:
    struct Slot {
        int32_t x = 0, y = 0, z = 0;
        uint32_t count = 0;
        uint32_t stamp = 0;  ///< the call that filled it; empty in any other
    };
    struct Run {
        int32_t x, y, z;  ///< the cube
        uint32_t count;   ///< consecutive points in it
    };
    static constexpr std::size_t kChunk = 16384;  ///< points per parallel task
    std::vector<Slot> mSlots;  ///< reused from call to call: no fresh pages each step
    std::vector<std::vector<Run>> mRuns;  ///< per chunk of points, reused likewise
    uint32_t mStamp = 0;       ///< this call's: slots of earlier calls read as empty
};

}  // namespace globular
