// The AVX2 force loops' stand-in for AVX-512's compress (sim/simd_lanes.h): for every lane
// mask, the kept lanes in front and in their order, which is what makes the AVX2 build
// collect each globule's neighbours in the same order as the other builds.
#include <gtest/gtest.h>

#include <cstdint>

#include "left_pack_probe.h"

namespace {

bool runsAvx2() { return __builtin_cpu_supports("avx2"); }

TEST(LeftPack, KeepsTheMaskedLanesInFrontInTheirOrder) {
    if (!runsAvx2()) GTEST_SKIP() << "this CPU lacks AVX2";
    for (unsigned mask = 0; mask < 256; ++mask) {
        float lanes[8];
        leftPackLanes(mask, lanes);
        std::size_t front = 0;
        for (int lane = 0; lane < 8; ++lane) {
            if ((mask >> lane) & 1u) {
                ASSERT_EQ(lanes[front], float(lane)) << "mask " << mask << ", slot " << front;
                ++front;
            }
        }
        EXPECT_EQ(front, std::size_t(__builtin_popcount(mask)));
    }
}

TEST(LeftPack, FirstLanesAndTheLaneSum) {
    if (!runsAvx2()) GTEST_SKIP() << "this CPU lacks AVX2";
    for (uint32_t left = 0; left <= 20; ++left) {
        EXPECT_EQ(firstLanesMask(left), left >= 8 ? 0xFFu : (1u << left) - 1) << left;
    }
    const float v[8] = {1, 2, 4, 8, 16, 32, 64, 128};
    EXPECT_EQ(laneSum(v), 255.0f);
}

}  // namespace
