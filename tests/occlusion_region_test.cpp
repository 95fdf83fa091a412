// Where the ambient occlusion can darken (render/occlusion_region.h), checked against
// the pass's own geometry: a tap behind an occluder, seen from any pixel it can belong to.
#include "occlusion_region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "transform.h"

namespace globular::detail {
namespace {

constexpr int kWidth = 320, kHeight = 240;

/// A camera at @p eye looking at @p target, 40 degrees of vertical field, as the renderer
/// sets it up.
FrameUniforms frameFrom(Vec3 eye, Vec3 target) {
    FrameUniforms f;
    f.width = kWidth;
    f.height = kHeight;
    const double aspect = double(kWidth) / kHeight, tanHalf = std::tan(20.0 * M_PI / 180.0);
    f.view = lookAt(eye, target);
    f.zNear = 0.1f;
    f.zFar = 200.0f;
    f.viewProj = perspective(40, aspect, f.zNear, f.zFar) * f.view;
    const Mat4& v = f.view;
    f.camRight = Vec3{v(0, 0), v(0, 1), v(0, 2)} * (tanHalf * aspect);
    f.camUp = Vec3{v(1, 0), v(1, 1), v(1, 2)} * tanHalf;
    f.camForward = Vec3{-v(2, 0), -v(2, 1), -v(2, 2)};
    f.eye = eye;
    return f;
}

bool holds(const std::vector<PixelRect>& rects, int x, int y) {
    for (const PixelRect& r : rects) {
        if (x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1) return true;
    }
    return false;
}

/// The pixel (window coordinates) whose area holds @p point's image; false off the frame.
bool pixelOf(const FrameUniforms& f, Vec3 point, int& x, int& y) {
    const Vec4 c = transformPoint(f.viewProj, point);
    if (!(c.w > f.zNear)) return false;
    x = int(std::floor((c.x / c.w * 0.5 + 0.5) * f.width));
    y = int(std::floor((c.y / c.w * 0.5 + 0.5) * f.height));
    return x >= 0 && x < f.width && y >= 0 && y < f.height;
}

std::size_t area(const std::vector<PixelRect>& rects) {
    std::size_t pixels = 0;
    for (const PixelRect& r : rects) pixels += std::size_t(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1);
    return pixels;
}

// A triangle standing on the ground, and the occlusion radius.
const float kTriangle[9] = {-1, 0, 0, 1, 0, 0.5f, 0, 2, 0};
const uint32_t kCorners[3] = {0, 1, 2};
constexpr double kRadius = 1.5;

TEST(OcclusionRegion, HoldsEveryPixelWhoseTapCanLandOnAnOccluder) {
    // Pixel p's tap q lies within the radius of p's point and is occluded where the depth
    // buffer, at q's image, shows an occluder point o in front of q: q on o's ray beyond
    // it. Every such p, from every side, must lie in the region.
    for (const Vec3 eye : {Vec3{0, 3, 12}, Vec3{-7, 9, 5}, Vec3{4, 1, 3}, Vec3{0, 14, 1}}) {
        const FrameUniforms f = frameFrom(eye, Vec3{0, 0.5, 0});
        OcclusionRegion region(f, kRadius);
        region.addTriangles(kTriangle, 3, kCorners, 1);
        ASSERT_FALSE(region.whole());
        const std::vector<PixelRect> rects = region.rects();
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
        int checked = 0;
        for (int k = 0; k < 200000; ++k) {
            double a = u(rng), b = u(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const Vec3 o{kTriangle[0] + a * (kTriangle[3] - kTriangle[0]) +
                             b * (kTriangle[6] - kTriangle[0]),
                         kTriangle[1] + a * (kTriangle[4] - kTriangle[1]) +
                             b * (kTriangle[7] - kTriangle[1]),
                         kTriangle[2] + a * (kTriangle[5] - kTriangle[2]) +
                             b * (kTriangle[8] - kTriangle[2])};
            const Vec3 q = o + (o - eye) * (2 * kRadius * u(rng) / length(o - eye));
            Vec3 step{s(rng), s(rng), s(rng)};
            if (dot(step, step) > 1) continue;
            const Vec3 p = q + step * kRadius;
            int x, y;
            if (!pixelOf(f, p, x, y)) continue;
            ++checked;
            ASSERT_TRUE(holds(rects, x, y)) << "pixel " << x << ", " << y << " from eye " << eye.x
                                            << ", " << eye.y << ", " << eye.z;
        }
        EXPECT_GT(checked, 10000);
    }
}

TEST(OcclusionRegion, IsAPartOfTheFrameAroundASmallOccluder) {
    // From afar the triangle and its reach cover a small part of the frame: the pass
    // then shades a small part.
    const FrameUniforms f = frameFrom(Vec3{0, 6, 30}, Vec3{0, 0.5, 0});
    OcclusionRegion region(f, 0.3);
    region.addTriangles(kTriangle, 3, kCorners, 1);
    ASSERT_FALSE(region.whole());
    const std::size_t pixels = area(region.rects());
    EXPECT_GT(pixels, 0u);
    EXPECT_LT(pixels, std::size_t(kWidth * kHeight) / 8);
}

TEST(OcclusionRegion, IsEmptyWithoutOccludersAndWholeWhenItCannotBeBounded) {
    const FrameUniforms f = frameFrom(Vec3{0, 3, 12}, Vec3{0, 0.5, 0});
    OcclusionRegion none(f, kRadius);
    EXPECT_FALSE(none.whole());
    EXPECT_TRUE(none.rects().empty());
    // Off the frame: nothing to darken.
    const float aside[9] = {-90, 0, 0, -89, 0, 0, -90, 1, 0};
    OcclusionRegion offFrame(f, kRadius);
    offFrame.addTriangles(aside, 3, kCorners, 1);
    EXPECT_FALSE(offFrame.whole());
    EXPECT_TRUE(offFrame.rects().empty());
    // Behind the near plane, not finite, an index past the vertices: every pixel.
    const float behind[9] = {-1, 0, 20, 1, 0, 20, 0, 2, 20};
    OcclusionRegion back(f, kRadius);
    back.addTriangles(behind, 3, kCorners, 1);
    EXPECT_TRUE(back.whole());
    float broken[9];
    std::copy(kTriangle, kTriangle + 9, broken);
    broken[4] = std::numeric_limits<float>::quiet_NaN();
    OcclusionRegion notFinite(f, kRadius);
    notFinite.addTriangles(broken, 3, kCorners, 1);
    EXPECT_TRUE(notFinite.whole());
    const uint32_t past[3] = {0, 1, 3};
    OcclusionRegion badIndex(f, kRadius);
    badIndex.addTriangles(kTriangle, 3, past, 1);
    EXPECT_TRUE(badIndex.whole());
    Globules nearEye;
    nearEye.add({0, 3, 11.95}, {}, 0.2f, 1, 0);
    OcclusionRegion sphere(f, kRadius);
    sphere.addSpheres(nearEye);
    EXPECT_TRUE(sphere.whole());
}

TEST(OcclusionRegion, HoldsASphereAndItsReach) {
    // Points on a sphere as occluders: every pixel a tap behind one can belong to, with a
    // reach beyond the sphere and one well within it.
    const FrameUniforms f = frameFrom(Vec3{-3, 3, 5}, Vec3{0, 0.5, 0});
    const Vec3 centre{1.5, 0.6, -0.5};
    Globules g;
    g.add(centre, {}, 1.0f, 1, 0);
    for (const double radius : {1.5, 0.05}) {
        OcclusionRegion region(f, radius);
        region.addSpheres(g);
        const std::vector<PixelRect> rects = region.rects();
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
        for (int k = 0; k < 100000; ++k) {
            Vec3 d{s(rng), s(rng), s(rng)}, step{s(rng), s(rng), s(rng)};
            if (dot(d, d) > 1 || dot(d, d) < 1e-6 || dot(step, step) > 1) continue;
            const Vec3 o = centre + d * (1.0 / length(d));
            const Vec3 q = o + (o - f.eye) * (2 * radius * u(rng) / length(o - f.eye));
            int x, y;
            if (!pixelOf(f, q + step * radius, x, y)) continue;
            ASSERT_TRUE(holds(rects, x, y)) << "pixel " << x << ", " << y << ", radius " << radius;
        }
    }
}

}  // namespace
}  // namespace globular::detail
