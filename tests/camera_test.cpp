#include "camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "transform.h"

namespace globular {
namespace {

Vec4 project(const ViewCamera& cam, double aspect, Vec3 p) {
    const Mat4 m = perspective(cam.fov, aspect, 0.01, 1000) * lookAt(cam.position, cam.target);
    Vec4 c = transformPoint(m, p);
    return {c.x / c.w, c.y / c.w, c.z / c.w, c.w};
}

TEST(Transform, LookAtPutsTheTargetOnTheAxis) {
    const Mat4 view = lookAt({3, 4, 5}, {1, 1, 1});
    const Vec4 t = transformPoint(view, {1, 1, 1});
    EXPECT_NEAR(t.x, 0, 1e-5);
    EXPECT_NEAR(t.y, 0, 1e-5);
    EXPECT_NEAR(t.z, -std::sqrt(4 + 9 + 16), 1e-5);
}

TEST(Transform, LookAtStraightDownStaysFinite) {
    const Mat4 view = lookAt({0, 10, 0}, {0, 0, 0});
    for (float v : view.m) EXPECT_TRUE(std::isfinite(v));
    EXPECT_NEAR(transformPoint(view, {0, 0, 0}).z, -10, 1e-5);
}

TEST(Transform, PerspectiveMapsNearAndFarToTheDepthRange) {
    const Mat4 p = perspective(90, 2.0, 1, 100);
    Vec4 n = transformPoint(p, {0, 0, -1}), f = transformPoint(p, {0, 0, -100});
    EXPECT_NEAR(n.z / n.w, -1, 1e-6);
    EXPECT_NEAR(f.z / f.w, 1, 1e-5);
    // 90 degrees vertical: y = depth reaches the top edge; x = 2 depth the right edge.
    Vec4 corner = transformPoint(p, {20, 10, -10});
    EXPECT_NEAR(corner.x / corner.w, 1, 1e-6);
    EXPECT_NEAR(corner.y / corner.w, 1, 1e-6);
}

TEST(Transform, OrthographicMapsTheBoxToTheCube) {
    const Mat4 o = orthographic(-2, 2, -1, 1, 1, 11);
    Vec4 a = transformPoint(o, {-2, -1, -1}), b = transformPoint(o, {2, 1, -11});
    EXPECT_NEAR(a.x, -1, 1e-6);
    EXPECT_NEAR(a.y, -1, 1e-6);
    EXPECT_NEAR(a.z, -1, 1e-6);
    EXPECT_NEAR(b.x, 1, 1e-6);
    EXPECT_NEAR(b.y, 1, 1e-6);
    EXPECT_NEAR(b.z, 1, 1e-6);
}

TEST(AutoFrame, EveryCornerOfTheContentIsInsideTheImage) {
    SceneExtent extent;
    extent.box.add(Vec3{-3, 0, -1});
    extent.box.add(Vec3{5, 12, 2});
    const double aspect = 16.0 / 9.0;
    const ViewCamera cam = autoFrame(extent, 0, 40, aspect);
    double largest = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? 5.0 : -3.0, corner & 2 ? 12.0 : 0.0, corner & 4 ? 2.0 : -1.0};
        const Vec4 c = project(cam, aspect, p);
        EXPECT_LE(std::abs(c.x), 0.9 + 1e-6);
        EXPECT_LE(std::abs(c.y), 0.9 + 1e-6);
        largest = std::max({largest, std::abs(c.x), std::abs(c.y)});
    }
    EXPECT_GT(largest, 0.85);                 // tight: the content fills the frame
    EXPECT_GT(cam.position.y, cam.target.y);  // from above, as in the paper
}

TEST(AutoFrame, SamplesAreCentredAndFitWithTheirRadius) {
    SceneExtent extent;
    extent.samples = {{0, 1, 0}, {10, 1, 0}, {0, 1, 10}, {5, 8, 5}};
    extent.maxRadius = 1;
    for (const Vec3& p : extent.samples) extent.box.add(p);
    const double aspect = 1.5;
    const ViewCamera cam = autoFrame(extent, 0, 30, aspect);
    double left = 1, right = -1, bottom = 1, top = -1;
    for (const Vec3& p : extent.samples) {
        const Vec4 c = project(cam, aspect, p);
        left = std::min(left, c.x);
        right = std::max(right, c.x);
        bottom = std::min(bottom, c.y);
        top = std::max(top, c.y);
        EXPECT_LT(std::abs(c.x), 0.9);
        EXPECT_LT(std::abs(c.y), 0.9);
    }
    // Centred: the projected extent is (nearly) symmetric about the image centre.
    EXPECT_NEAR(left + right, 0, 0.1);
}

TEST(AutoFrame, EmptyContentStillGivesAView) {
    const ViewCamera cam = autoFrame(SceneExtent{}, 2, 40, 1.0);
    EXPECT_GT(length(cam.position - cam.target), 1);
    EXPECT_NEAR(cam.target.y, 2.5, 1.0);
}

TEST(DepthRange, HoldsTheContentAndTheGround) {
    Bounds3 box;
    box.add(Vec3{-1, -1, -1});
    box.add(Vec3{1, 1, 1});
    const DepthRange r = depthRange({0, 0, 10}, box, 50);
    EXPECT_LT(r.zNear, 10 - std::sqrt(3.0));
    EXPECT_GT(r.zFar, 10 + 50);
    EXPECT_GT(r.zNear, 0);
}

}  // namespace
}  // namespace globular
