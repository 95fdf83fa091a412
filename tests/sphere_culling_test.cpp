#include "sphere_culling.h"

#include <gtest/gtest.h>

#include <limits>

namespace globular::detail {
namespace {

ScreenDisc disc(float x, float y, float half, float nearDepth, float coreRadius, float coreDepth) {
    ScreenDisc d;
    d.x = x;
    d.y = y;
    d.half = half;
    d.reach = half;
    d.nearDepth = nearDepth;
    d.coreRadius = coreRadius;
    d.coreDepth = coreDepth;
    return d;
}

TEST(SphereCulling, ADiscBehindANearerCoreIsCulled) {
    const std::vector<ScreenDisc> discs = {
        disc(50, 50, 10, 1, 30, 2),  // near, its core covers everything within 30 pixels
        disc(50, 50, 5, 3, 3, 4),    // behind it, reaching 5 pixels: hidden
        disc(55, 50, 5, 1.5, 3, 4),  // in front of the core depth: kept
        disc(75, 50, 10, 3, 3, 4),   // behind, but partly beyond the core: kept
    };
    EXPECT_EQ(unoccluded(discs, 100, 100), (std::vector<uint32_t>{0, 2, 3}));
}

TEST(SphereCulling, EqualDepthsNeverHideEachOther) {
    // Two identical spheres: neither's core is nearer than the other's nearest point.
    const std::vector<ScreenDisc> discs = {disc(20, 20, 6, 1, 4, 1.5), disc(20, 20, 6, 1, 4, 1.5)};
    EXPECT_EQ(unoccluded(discs, 40, 40), (std::vector<uint32_t>{0, 1}));
}

TEST(SphereCulling, OffScreenAndUndrawableDiscsAreDroppedUnboundedOnesKept) {
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<ScreenDisc> discs = {
        disc(-20, 10, 5, 1, 2, 2),   // wholly left of the view
        disc(10, 300, 5, 1, 2, 2),   // wholly above
        disc(-3, 10, 5, 1, 2, 2),    // partly in view
        disc(10, 10, -1, 1, 0, 0),   // never drawn (not finite)
        disc(10, 10, inf, 9, 0, 0),  // may cover anything (reaches the near plane)
    };
    EXPECT_EQ(unoccluded(discs, 64, 64), (std::vector<uint32_t>{2, 4}));
}

TEST(SphereCulling, CoresCoverOnlyWholePixels) {
    // A core of radius 0.9 around a pixel corner holds no whole pixel: hides nothing.
    const std::vector<ScreenDisc> discs = {disc(10, 10, 3, 1, 0.9f, 1),
                                           disc(10.5f, 10.5f, 0.4f, 5, 0, 0)};
    EXPECT_EQ(unoccluded(discs, 20, 20), (std::vector<uint32_t>{0, 1}));
    // One of radius 1.5 about a pixel centre holds that pixel wholly: hides a disc there.
    const std::vector<ScreenDisc> centred = {disc(10.5f, 10.5f, 3, 1, 1.5f, 1),
                                             disc(10.5f, 10.5f, 0.4f, 5, 0, 0)};
    EXPECT_EQ(unoccluded(centred, 20, 20), (std::vector<uint32_t>{0}));
}

TEST(SphereCulling, OnlyPixelCentresWithinReachCount) {
    // A core hides the pixel (10, 10) only. A disc reaching 0.6 pixels from that pixel's
    // centre touches no other centre: hidden. Reaching 1.2 pixels, it touches four more.
    std::vector<ScreenDisc> discs = {disc(10.5f, 10.5f, 3, 1, 1.5f, 1),
                                     disc(10.5f, 10.5f, 2, 5, 0, 0)};
    discs[1].reach = 0.6f;
    EXPECT_EQ(unoccluded(discs, 20, 20), (std::vector<uint32_t>{0}));
    discs[1].reach = 1.2f;
    EXPECT_EQ(unoccluded(discs, 20, 20), (std::vector<uint32_t>{0, 1}));
}

}  // namespace
}  // namespace globular::detail
