#include "camera.h"

#include <gtest/gtest.h>

#include <array>
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

/// A box's corners projected by @p cam: the extent in NDC, [left, right, bottom, top].
std::array<double, 4> projectedBox(const ViewCamera& cam, double aspect, const Bounds3& b) {
    std::array<double, 4> e{1e300, -1e300, 1e300, -1e300};
    for (int k = 0; k < 8; ++k) {
        const Vec4 c = project(cam, aspect, {k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y,
                                             k & 4 ? b.max.z : b.min.z});
        e = {std::min(e[0], c.x), std::max(e[1], c.x), std::min(e[2], c.y), std::max(e[3], c.y)};
    }
    return e;
}

Bounds3 boxOf(Vec3 lo, Vec3 hi) {
    Bounds3 b;
    b.add(lo);
    b.add(hi);
    return b;
}

TEST(AutoFrame, FramesWhereTheContentIsForMostOfTheShotNotItsTallestMoment) {
    // The paper's pour: a column 2 wide that falls from 80 units for 40 frames into a
    // puddle 12 wide and 2 high, which stays for 110 frames.
    SceneExtent extent;
    for (int f = 0; f < 150; ++f) {
        const double top = f < 40 ? 80.0 - 78.0 * f / 40 : 2.0;
        const double half = f < 40 ? 1.0 + 5.0 * f / 40 : 6.0;
        extent.currentFrame = boxOf({-half, 0, -half}, {half, top, half});
        extent.box.add(extent.currentFrame);
        extent.endFrame();
    }
    ASSERT_EQ(extent.frames.size(), 150u);
    const double aspect = 16.0 / 9.0;
    const ViewCamera cam = autoFrame(extent, 0, 40, aspect);
    const auto puddle = projectedBox(cam, aspect, boxOf({-6, 0, -6}, {6, 2, 6}));
    // The puddle, the subject of three quarters of the shot, spans most of the width
    // (it was about a tenth of it when the whole column was framed) and is fully in view.
    EXPECT_GT(puddle[1] - puddle[0], 2 * 0.5) << "puddle width, NDC";
    for (double edge : puddle) EXPECT_LE(std::abs(edge), 0.9 + 1e-6);
    // Every edge holds the content of at least three quarters of the frames.
    int held = 0;
    for (const Bounds3& b : extent.frames) {
        const auto e = projectedBox(cam, aspect, b);
        held += e[0] >= -0.9 - 1e-6 && e[1] <= 0.9 + 1e-6 && e[2] >= -0.9 - 1e-6 &&
                e[3] <= 0.9 + 1e-6;
    }
    EXPECT_GE(held, 0.75 * 150 - 1);
    // And the frame is filled: an edge of the kept content touches the 90% margin.
    EXPECT_NEAR(std::max(puddle[1], -puddle[0]), 0.9, 0.35);
}

TEST(AutoFrame, ASplashOnAFewFramesDoesNotShrinkTheSubject) {
    SceneExtent still, splash;
    for (int f = 0; f < 100; ++f) {
        for (SceneExtent* e : {&still, &splash}) {
            e->currentFrame = boxOf({-3, 0, -3}, {3, 4, 3});
            if (e == &splash && f >= 50 && f < 60) e->currentFrame.add(Vec3{40, 25, -30});
            e->endFrame();
        }
    }
    const ViewCamera a = autoFrame(still, 0, 40, 1.5), b = autoFrame(splash, 0, 40, 1.5);
    EXPECT_NEAR(length(a.position - b.position), 0, 1e-6 * length(a.position - a.target));
    EXPECT_NEAR(length(a.target - b.target), 0, 1e-6 * length(a.position - a.target));
    // A box alone fills 90% of the image in its tighter direction, its foot on the ground.
    const auto e = projectedBox(a, 1.5, boxOf({-3, 0, -3}, {3, 4, 3}));
    EXPECT_NEAR(std::max(e[1] - e[0], e[3] - e[2]), 1.8, 0.01);
    EXPECT_NEAR(e[0] + e[1], 0, 0.01);  // centred
    EXPECT_NEAR(e[2] + e[3], 0, 0.01);
}

TEST(AutoFrame, FramesReachDownToTheirFootOnTheGround) {
    SceneExtent extent;
    for (int f = 0; f < 10; ++f) {
        extent.currentFrame = boxOf({-1, 10, -1}, {1, 12, 1});  // floating 10 units up
        extent.endFrame();
    }
    const ViewCamera cam = autoFrame(extent, 0, 40, 1.0);
    const auto ground = projectedBox(cam, 1.0, boxOf({-1, 0, -1}, {1, 0, 1}));
    EXPECT_GE(ground[2], -0.9 - 1e-6);
    EXPECT_LE(ground[2], -0.8);  // the foot is at the bottom edge
}

// The paper's pour again with a following camera: the column is framed while it stands
// and the puddle fills the picture at the end; the camera glides (no cut between frames).
TEST(FollowTheAction, FramesTheColumnThenThePuddleAndGlides) {
    SceneExtent extent;
    for (int f = 0; f < 150; ++f) {
        const double top = f < 100 ? 80.0 : 2.0;
        const double half = f < 100 ? 1.0 : 6.0;
        extent.currentFrame = boxOf({-half, 0, -half}, {half, top, half});
        extent.box.add(extent.currentFrame);
        extent.endFrame();
    }
    const double aspect = 16.0 / 9.0;
    const std::vector<ViewCamera> path = followTheAction(extent, 0, 40, aspect, 25);
    ASSERT_EQ(path.size(), 150u);
    const Bounds3 puddle = boxOf({-6, 0, -6}, {6, 2, 6});
    const auto still = projectedBox(autoFrame(extent, 0, 40, aspect), aspect, puddle);
    const auto last = projectedBox(path.back(), aspect, puddle);
    // One still camera holds the column two thirds of the shot and the puddle is small;
    // following, it fills the frame's height at the end (90% margin, 2 = full height).
    EXPECT_LT(still[1] - still[0], 0.5) << "puddle width, NDC, still camera";
    EXPECT_NEAR(std::max(last[1] - last[0], last[3] - last[2]), 1.8, 0.05);
    const auto column = projectedBox(path[40], aspect, boxOf({-1, 0, -1}, {1, 80, 1}));
    EXPECT_NEAR(column[3] - column[2], 1.8, 0.05) << "the column fills the height";
    // The subject changes at once (frame 100); the camera takes the move over about two
    // windows: no step between two frames is more than 5% of the whole move.
    const double move = length(path.back().target - path.front().target);
    for (std::size_t f = 1; f < path.size(); ++f) {
        const double d0 = length(path[f - 1].position - path[f - 1].target);
        const double d1 = length(path[f].position - path[f].target);
        EXPECT_LT(std::abs(std::log(d1 / d0)), 0.1) << "frame " << f;
        EXPECT_LT(length(path[f].target - path[f - 1].target), 0.05 * move) << "frame " << f;
    }
}

// A shot that does not change is framed as autoFrame frames it, on every frame; frames
// with nothing in them (before anything is emitted) take their neighbours' framing.
TEST(FollowTheAction, AStillShotGetsTheStillCamera) {
    SceneExtent extent;
    for (int f = 0; f < 40; ++f) {
        if (f >= 5) extent.currentFrame = boxOf({-3, 0, -3}, {3, 4, 3});
        extent.endFrame();
    }
    ASSERT_EQ(extent.frames.size(), 40u);  // empty frames keep their place
    const ViewCamera still = autoFrame(extent, 0, 40, 1.5);
    for (const ViewCamera& c : followTheAction(extent, 0, 40, 1.5, 10)) {
        EXPECT_NEAR(length(c.position - still.position), 0, 1e-9 * length(still.position));
        EXPECT_NEAR(length(c.target - still.target), 0, 1e-9 * length(still.position));
    }
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
