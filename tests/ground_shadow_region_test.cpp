// The ground's shadow region (render/ground_shadow_region.h), checked by projecting ground
// points forwards into the light's map, independently of the region's inverse mapping.
#include "ground_shadow_region.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "transform.h"

namespace globular::detail {
namespace {

constexpr int kMapSize = 512;
constexpr double kGround = 0.5;

/// A frame lit along @p toward (unit, towards the light), its map around a sphere of
/// radius 6 at the origin, as the renderer fits it.
FrameUniforms frameLitFrom(Vec3 toward) {
    FrameUniforms f;
    const double radius = 6;
    const Vec3 center{0, 2, 0};
    const Mat4 view = lookAt(center + toward * (2.0 * radius), center);
    const double reach = 3.0 * radius + 2.0 * radius / std::max(std::abs(toward.y), 0.05);
    f.lightViewProj = orthographic(-radius, radius, -radius, radius, 0.5 * radius, reach) * view;
    f.shadowed = true;
    f.shadowMapSize = kMapSize;
    f.shadowTexel = float(2.0 * radius / kMapSize);
    f.shadowSoftness = 1.5f;
    f.eye = {0, 6, 14};
    f.pixelAngle = 0.002f;
    return f;
}

/// The texel (continuous) where the shadow filter looks up ground point (x, z).
std::pair<double, double> lookupTexel(const FrameUniforms& f, double x, double z) {
    const double lift = (1.5 + 0.5 * f.shadowSoftness) * f.shadowTexel;
    const Vec4 c = transformPoint(f.lightViewProj, Vec3{x, kGround + lift, z});
    return {(c.x / c.w * 0.5 + 0.5) * kMapSize, (c.y / c.w * 0.5 + 0.5) * kMapSize};
}

bool inside(const GroundRect& r, double x, double z) {
    return x >= r.x0 && x <= r.x1 && z >= r.z0 && z <= r.z1;
}

void expectHoldsEveryReachingPoint(Vec3 toward) {
    const FrameUniforms f = frameLitFrom(normalized(toward));
    const TexelRect drawn{200, 230, 260, 300};
    const std::optional<GroundRect> region = groundShadowRegion(f, drawn, kGround);
    ASSERT_TRUE(region.has_value());
    // The filter's taps lie within its disc (1.5 texels) of the lookup, each reading the
    // 2x2 texels around it: a point reads a drawn texel only if its lookup lies within
    // 2.5 texels of the drawn ones (texel i spans [i, i + 1)).
    const double reads = 1.5 + 1.0;
    int reaching = 0;
    for (double x = -30; x <= 30; x += 0.05) {
        for (double z = -30; z <= 30; z += 0.05) {
            const auto [u, v] = lookupTexel(f, x, z);
            const double du = std::max({drawn.x0 - u, u - (drawn.x1 + 1), 0.0});
            const double dv = std::max({drawn.y0 - v, v - (drawn.y1 + 1), 0.0});
            if (std::max(du, dv) >= reads) continue;
            ++reaching;
            ASSERT_TRUE(inside(*region, x, z)) << "(" << x << ", " << z << ") reads a drawn texel";
        }
    }
    EXPECT_GT(reaching, 1000);
    // And it is not much bigger: a rectangle around that parallelogram of ground, plus a
    // pixel's footprint (a few hundredths of a unit here).
    const double reachingArea = reaching * 0.05 * 0.05;
    EXPECT_LT((region->x1 - region->x0) * (region->z1 - region->z0), 4 * reachingArea);
}

TEST(GroundShadowRegion, HoldsEveryPointWhoseFilterReadsADrawnTexel) {
    expectHoldsEveryReachingPoint({0, 1, 0});        // a light overhead
    expectHoldsEveryReachingPoint({-1, 1.5, 0.6});   // oblique: shadows fall to one side
    expectHoldsEveryReachingPoint({1, 0.3, 0.2});    // low: long shadows, far from casters
}

TEST(GroundShadowRegion, ReachesAPixelsFootprintPastThat) {
    // A pixel is shaded at its centre, up to a pixel from the samples it covers: every
    // ground point a pixel's width (seen from the eye) from one the filter reaches must
    // lie in the region too. Far from the eye and seen at a grazing angle, that is wide.
    FrameUniforms f = frameLitFrom(normalized(Vec3{-1, 1.5, 0.6}));
    f.pixelAngle = 0.01f;
    f.eye = {0, 2, 30};
    const TexelRect drawn{200, 230, 260, 300};
    const std::optional<GroundRect> region = groundShadowRegion(f, drawn, kGround);
    FrameUniforms exact = f;
    exact.pixelAngle = 0;
    const std::optional<GroundRect> reached = groundShadowRegion(exact, drawn, kGround);
    ASSERT_TRUE(region && reached);
    for (double x : {reached->x0, reached->x1}) {
        for (double z : {reached->z0, reached->z1}) {
            // Tilt the eye ray through the corner by a pixel's angle, up and sideways.
            const Vec3 p{x, kGround, z};
            const Vec3 ray = normalized(p - f.eye);
            const Vec3 side = normalized(cross(ray, Vec3{0, 1, 0}));
            const Vec3 up = cross(side, ray);
            for (const Vec3 tilt : {up, up * -1.0, side, side * -1.0}) {
                const Vec3 d = normalized(ray + tilt * double(f.pixelAngle));
                if (d.y >= 0) continue;
                const double t = (kGround - f.eye.y) / d.y;
                const Vec3 q = f.eye + d * t;
                EXPECT_TRUE(inside(*region, q.x, q.z)) << "(" << q.x << ", " << q.z << ")";
            }
        }
    }
}

TEST(GroundShadowRegion, EmptyWithoutCastersUnboundedWhenLevelWithTheGround) {
    const FrameUniforms f = frameLitFrom(normalized(Vec3{-1, 1.5, 0.6}));
    const std::optional<GroundRect> none = groundShadowRegion(f, TexelRect{}, kGround);
    ASSERT_TRUE(none.has_value());
    EXPECT_TRUE(none->empty());
    // A light along the ground: its shadows have no end.
    EXPECT_FALSE(groundShadowRegion(frameLitFrom({1, 0, 0}), TexelRect{0, 0, 10, 10}, kGround));
    // An eye level with the ground: a pixel's footprint has no end either.
    FrameUniforms level = f;
    level.eye.y = kGround;
    EXPECT_FALSE(groundShadowRegion(level, TexelRect{0, 0, 10, 10}, kGround));
}

}  // namespace
}  // namespace globular::detail
