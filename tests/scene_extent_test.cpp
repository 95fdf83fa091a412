#include "scene_extent.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace globular {
namespace {

Globules line(int n) {
    Globules g;
    for (int i = 0; i < n; ++i) g.add({double(i), 2.0 * i, -double(i)}, {3, 4, 0}, 0.5f, 1, i);
    return g;
}

TEST(SceneExtent, SmallFramesKeepTheirExactBoundsGrownByTheRadius) {
    SceneExtent e;
    e.addFrame(line(10));
    EXPECT_EQ(e.box.min, (Vec3{-0.5, -0.5, -9.5}));
    EXPECT_EQ(e.box.max, (Vec3{9.5, 18.5, 0.5}));
    EXPECT_DOUBLE_EQ(e.speed.min, 5);
    EXPECT_DOUBLE_EQ(e.speed.max, 5);
    EXPECT_DOUBLE_EQ(e.height.min, 0);
    EXPECT_DOUBLE_EQ(e.height.max, 18);
    EXPECT_EQ(e.samples.size(), 10u);
}

TEST(SceneExtent, NonFiniteGlobulesAreIgnored) {
    Globules g = line(4);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1, 99);
    g.px.back() = nan;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1, 100);
    g.py.back() = std::numeric_limits<float>::infinity();
    SceneExtent e;
    e.addFrame(g);
    EXPECT_TRUE(std::isfinite(e.box.min.x) && std::isfinite(e.box.max.y));
    EXPECT_DOUBLE_EQ(e.box.max.y, 6.5);
}

TEST(SceneExtent, AFarStrayDoesNotShrinkThePicture) {
    Globules g;
    for (int i = 0; i < 1000; ++i) g.add({double(i % 10), double(i / 100), 0}, {}, 0.5f, 1, i);
    g.add({1e6, 0, 0}, {}, 0.5f, 1, 1000);  // an exploded globule
    SceneExtent e;
    e.addFrame(g);
    EXPECT_DOUBLE_EQ(e.box.max.x, 9.5);  // the genuine extreme stays in
    EXPECT_DOUBLE_EQ(e.box.max.y, 9.5);
    for (const Vec3& p : e.samples) EXPECT_LT(p.x, 100);
}

TEST(SceneExtent, FramesMerge) {
    SceneExtent e;
    Globules a, b;
    a.add({0, 0, 0}, {1, 0, 0}, 1, 1, 0);
    b.add({10, 5, 0}, {0, 7, 0}, 1, 1, 0);
    e.addFrame(a);
    e.addFrame(b);
    EXPECT_EQ(e.box.min, (Vec3{-1, -1, -1}));
    EXPECT_EQ(e.box.max, (Vec3{11, 6, 1}));
    EXPECT_DOUBLE_EQ(e.speed.min, 1);
    EXPECT_DOUBLE_EQ(e.speed.max, 7);
}

TEST(SceneExtent, SamplesStayBoundedAndExtremesStay) {
    SceneExtent e;
    for (int f = 0; f < 40; ++f) e.addFrame(line(5000));
    EXPECT_LE(e.samples.size(), kMaxFramingSamples);
    EXPECT_GT(e.samples.size(), kMaxFramingSamples / 4);
    ASSERT_EQ(e.extremes.size(), 40u * 6);
    double top = 0;
    for (const Vec3& p : e.extremes) top = std::max(top, p.y);
    EXPECT_DOUBLE_EQ(top, 2.0 * 4999);  // the top globule, however thin the samples
}

TEST(SceneExtent, EmptyFrameLeavesItEmpty) {
    SceneExtent e;
    e.addFrame(Globules{});
    EXPECT_TRUE(e.box.empty);
    EXPECT_TRUE(e.speed.empty);
}

TEST(SceneExtent, MeshPoints) {
    const float positions[] = {0, 0, 0, 1, 2, 3, -1, 5, 0};
    SceneExtent e;
    e.addPoints(positions, 3);
    EXPECT_EQ(e.box.min, (Vec3{-1, 0, 0}));
    EXPECT_EQ(e.box.max, (Vec3{1, 5, 3}));
    EXPECT_DOUBLE_EQ(e.height.max, 5);
}

}  // namespace
}  // namespace globular
