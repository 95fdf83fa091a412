// The liquid look against analytic optics: Snell's law (a clear slab over the checker
// shifts its edges where the refracted rays say), Beer-Lambert (an absorbing slab keeps
// exp(-sigma d) of the light along the refracted path), and the screen-space fluid (a
// block of globules becomes one surface with a flat top).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "box_mesh.h"
#include "renderer.h"

namespace globular {
namespace {

constexpr double kIor = 1.33;

/// A frame with no lights (the sky alone lights the ground evenly), a checker of 1 unit.
FrameSetup liquidSetup(Vec3 eye, Vec3 target, Vec3 sigma) {
    FrameSetup s;
    s.camera = {eye, target, 40};
    s.lights = {};
    s.render.checkerSize = 1;
    s.content.add(Vec3{-4, 0, -4});
    s.content.add(Vec3{4, 2, 4});
    s.materialOptics = {LiquidOptics{true, sigma, kIor}};
    s.liquidSurface = true;
    return s;
}

/// The eye ray through window row @p windowY (pixels from the bottom, continuous) of the
/// image's centre column, as the renderer's camera casts it.
Vec3 centreColumnRay(const ViewCamera& c, int width, int height, double windowY) {
    const Vec3 forward = normalized(c.target - c.position);
    const Vec3 side = normalized(cross(forward, Vec3{0, 1, 0}));
    const Vec3 up = cross(side, forward);
    const double tanHalf = std::tan(c.fov * std::numbers::pi / 360.0);
    (void)width;
    return normalized(forward + up * ((windowY / height * 2 - 1) * tanHalf));
}

/// Snell's law at a horizontal surface seen along @p d (unit, going down).
Vec3 refractDown(Vec3 d, double ior) {
    const Vec3 n{0, 1, 0};
    const double cosi = -dot(d, n), eta = 1 / ior;
    const double k = 1 - eta * eta * (1 - cosi * cosi);
    return normalized(d * eta + n * (eta * cosi - std::sqrt(k)));
}

/// z where the ray from the eye through window row @p windowY meets the ground, through a
/// clear slab of height @p h on it (h = 0: no slab).
double groundZ(const ViewCamera& c, int w, int hgt, double windowY, double h) {
    const Vec3 d = centreColumnRay(c, w, hgt, windowY);
    const Vec3 p = c.position + d * ((h - c.position.y) / d.y);
    if (h <= 0) return p.z;
    const Vec3 r = refractDown(d, kIor);
    return (p + r * (-p.y / r.y)).z;
}

/// The window row where the ground's z is @p z (bisection; z grows down the image).
double rowOf(double z, const ViewCamera& c, int w, int h, double slab) {
    double lo = 0, hi = h;  // the bottom row sees the nearest ground (largest z)
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (groundZ(c, w, h, mid, slab) > z ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double luminance(const LinearFrame& f, int x, int y) {
    const float* p = &f.rgba[(std::size_t(y) * f.width + x) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/// Where, in window rows, the centre column crosses the mid level between the darkest and
/// lightest of the rows within @p reach of @p near (one checker edge in that span).
double measuredEdge(const LinearFrame& f, double near, int reach) {
    const int x = f.width / 2;
    std::vector<double> rows, values;
    for (int y = int(near) - reach; y <= int(near) + reach; ++y) {
        const int top = f.height - 1 - y;  // the frame's rows run top first
        rows.push_back(y + 0.5);
        values.push_back(luminance(f, x, top));
    }
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    const double mid = 0.5 * (*lo + *hi);
    for (std::size_t i = 0; i + 1 < values.size(); ++i) {
        if ((values[i] - mid) * (values[i + 1] - mid) <= 0 && values[i] != values[i + 1]) {
            return rows[i] + (mid - values[i]) / (values[i + 1] - values[i]);
        }
    }
    return -1;
}

TEST(LiquidRender, ClearSlabShiftsTheCheckerAsSnellsLawPredicts) {
    constexpr int kW = 161, kH = 121;  // odd: the centre column's pixel centres lie on x = 0.5
    const double height = 1.5;
    const BoxMesh slab({-60, 0, -60}, {60, height, 60});
    // x = 0.5: the middle of a checker column, so only the edges across z show.
    FrameSetup s = liquidSetup({0.5, 6, 10}, {0.5, 0, 0}, {0, 0, 0});
    Renderer renderer(kW, kH, 4);
    renderer.drawMesh(slab.view(), s);
    const LinearFrame& f = renderer.lastFrame();
    for (double edge : {1.0, 3.0}) {
        SCOPED_TRACE(edge);
        const double expected = rowOf(edge, s.camera, kW, kH, height);
        const double bare = rowOf(edge, s.camera, kW, kH, 0);
        ASSERT_GT(std::abs(expected - bare), 6.0) << "the slab must shift the edge visibly";
        const double measured = measuredEdge(f, expected, 5);
        EXPECT_NEAR(measured, expected, 1.0) << "without refraction it would be at " << bare;
    }
}

/// A 6x6 slab of liquid, 1 high, seen from above and in front, with the key light mirrored
/// about the slab's top at its centre: its glint lies there, in the image's centre.
struct GlintScene {
    static constexpr int kW = 161, kH = 121;
    BoxMesh slab{{-3, 0, -3}, {3, 1, 3}};
    Vec3 top{0, 1, 0};
    FrameSetup setup;
    GlintScene() {
        const Vec3 eye{0, 5, 8};
        const Vec3 view = normalized(top - eye);
        setup = liquidSetup(eye, top, {0.2, 0.1, 0.05});
        LightSettings key;
        key.direction = -1.0 * Vec3{view.x, -view.y, view.z};  // down to the top, mirrored
        setup.lights = {key};
    }
    /// Luminance at the glint and 8 pixels beside it.
    static double glint(const LinearFrame& f) { return luminance(f, kW / 2, kH / 2); }
    static double beside(const LinearFrame& f) { return luminance(f, kW / 2 + 8, kH / 2); }
};

TEST(LiquidRender, RenderersFirstFrameHasTheKeyLightsGlint) {
    // The glint shows where the key light's visibility (the shadow map) lets it through.
    // The passes create their textures on a renderer's first frame; that once unbound the
    // shadow map, and the first frame of every range came out without glints.
    const GlintScene scene;
    Renderer renderer(GlintScene::kW, GlintScene::kH, 4);
    renderer.drawMesh(scene.slab.view(), scene.setup);
    const LinearFrame first = renderer.lastFrame();
    renderer.drawMesh(scene.slab.view(), scene.setup);
    const LinearFrame& second = renderer.lastFrame();
    const double glint = GlintScene::glint(second);
    ASSERT_GT(glint, GlintScene::beside(second) + 0.2) << "the glint must stand out";
    EXPECT_NEAR(GlintScene::glint(first), glint, 1e-6);
    EXPECT_TRUE(first.rgba == second.rgba) << "the same frame drawn twice must match";
}

TEST(LiquidRender, GlintInAPropsShadowIsDark) {
    // A box between the glint and the key light: the shadow map must reach the glint (the
    // liquid's shading looks its visibility up once per pixel).
    GlintScene scene;
    Renderer renderer(GlintScene::kW, GlintScene::kH, 4);
    renderer.drawMesh(scene.slab.view(), scene.setup);
    const double lit = GlintScene::glint(renderer.lastFrame());
    const double beside = GlintScene::beside(renderer.lastFrame());
    ASSERT_GT(lit, beside + 0.2) << "the glint must stand out";
    // Towards the light from the top, behind it as the camera sees it.
    const Vec3 blocker = scene.top - 3.0 * scene.setup.lights.front().direction;
    const BoxMesh box(blocker - Vec3{0.6, 0.6, 0.6}, blocker + Vec3{0.6, 0.6, 0.6});
    scene.setup.props = {{box.mesh(), false}};
    renderer.drawMesh(scene.slab.view(), scene.setup);
    const double shadowed = GlintScene::glint(renderer.lastFrame());
    EXPECT_LT(shadowed, beside + 0.05 * (lit - beside)) << "lit " << lit << ", beside " << beside;
}

TEST(LiquidRender, AbsorbingSlabTransmitsExpMinusSigmaD) {
    constexpr int kW = 81, kH = 61;  // odd: the centre pixel's ray goes to the target
    const double height = 2;
    const BoxMesh slab({-40, 0, -40}, {40, height, 40});
    const Vec3 eye{0.5, 8, 2.5}, target{0.5, 0, 0.5};
    // The centre ray's path inside the slab: along the refracted ray to the ground.
    const Vec3 d = normalized(target - eye);
    const double path = height / -refractDown(d, kIor).y;
    auto centre = [&](Vec3 sigma) {
        Renderer renderer(kW, kH, 1);
        renderer.drawMesh(slab.view(), liquidSetup(eye, target, sigma));
        const LinearFrame& f = renderer.lastFrame();
        const float* p = &f.rgba[(std::size_t(kH / 2) * kW + kW / 2) * 4];
        return Vec3{p[0], p[1], p[2]};
    };
    // clear, absorbing, and opaque (only the reflection is left)
    const Vec3 sigma{0.45, 0.2, 0.06};
    const Vec3 clear = centre({0, 0, 0}), tinted = centre(sigma), opaque = centre({80, 80, 80});
    const double s[3] = {sigma.x, sigma.y, sigma.z};
    const double c[3] = {clear.x, clear.y, clear.z}, t[3] = {tinted.x, tinted.y, tinted.z},
                 o[3] = {opaque.x, opaque.y, opaque.z};
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        ASSERT_GT(c[k] - o[k], 0.05) << "the ground must show through the clear slab";
        const double expected = std::exp(-s[k] * path);
        EXPECT_NEAR((t[k] - o[k]) / (c[k] - o[k]), expected, 0.03 * expected);
    }
}

// The mesh is shaded deferred: each pixel from the triangle its id buffer names,
// interpolated where the pixel's eye ray meets that triangle's plane. The passes then
// hold that exact point: its distance from the eye and the face's normal, with the
// mesh's normals and (faceted) without them.
TEST(LiquidRender, MeshPassesHoldTheExactPointWherePixelRaysMeetTheSurface) {
    constexpr int kW = 81, kH = 61;  // odd: the centre column's rays lie in the plane x = 0.5
    const double height = 1.5;
    const BoxMesh slab({-60, 0, -60}, {60, height, 60});
    FrameSetup s = liquidSetup({0.5, 6, 10}, {0.5, 0, 0}, {0.1, 0.1, 0.1});
    MeshView faceted = slab.view();
    faceted.normals = nullptr;
    std::vector<float> colours[2];
    for (const MeshView& mesh : {slab.view(), faceted}) {
        SCOPED_TRACE(mesh.normals ? "with normals" : "faceted");
        Renderer renderer(kW, kH, 4, 1024, true);
        renderer.drawMesh(mesh, s);
        const LinearFrame& f = renderer.lastFrame();
        ASSERT_TRUE(f.hasPasses());
        int checked = 0;
        for (int y = 0; y < kH; ++y) {
            const Vec3 d = centreColumnRay(s.camera, kW, kH, y + 0.5);
            if (d.y >= 0) continue;  // the sky
            const double expected = (height - s.camera.position.y) / d.y;
            const std::size_t i = std::size_t(kH - 1 - y) * kW + kW / 2;
            ASSERT_NE(f.depth[i], LinearFrame::kNothing) << "row " << y;
            EXPECT_NEAR(f.depth[i], expected, 1e-4 * expected) << "row " << y;
            EXPECT_NEAR(f.normal[3 * i + 1], 1.0, 1e-5) << "row " << y;
            ++checked;
        }
        EXPECT_GT(checked, kH / 3);
        colours[mesh.normals ? 0 : 1] = f.rgba;
    }
    // Flat faces: the face normal is the vertices' normal, so the frames agree.
    double largest = 0;
    for (std::size_t k = 0; k < colours[0].size(); ++k) {
        largest = std::max(largest, double(std::abs(colours[0][k] - colours[1][k])));
    }
    EXPECT_LT(largest, 1e-3);
}

/// A block of globules: 24 x 3 x 24 of radius 1 on a grid of 0.8, its top at y = 3.1.
Globules block() {
    Globules g;
    int id = 0;
    for (int i = 0; i < 24; ++i) {
        for (int j = 0; j < 3; ++j) {
            for (int k = 0; k < 24; ++k) {
                g.add({0.8 * (i - 11.5), 0.5 + 0.8 * j, 0.8 * (k - 11.5)}, {0, 0, 0}, 1.0f, 1.0f,
                      id++);
            }
        }
    }
    return g;
}

/// Fraction of the pixels in the middle fifth of the frame that hold liquid whose normal
/// is within @p degrees of straight up; @p covered: the fraction that hold liquid.
double flatFraction(const LinearFrame& f, double degrees, double& covered) {
    int flat = 0, hit = 0, all = 0;
    for (int y = 2 * f.height / 5; y < 3 * f.height / 5; ++y) {
        for (int x = 2 * f.width / 5; x < 3 * f.width / 5; ++x) {
            ++all;
            const std::size_t i = std::size_t(y) * f.width + x;
            if (f.depth[i] == LinearFrame::kNothing) continue;
            ++hit;
            flat += f.normal[3 * i + 1] > std::cos(degrees * std::numbers::pi / 180);
        }
    }
    covered = double(hit) / all;
    return double(flat) / all;
}

TEST(LiquidRender, FluidBlockOfGlobulesHasAFlatTop) {
    const Globules g = block();
    FrameSetup s;
    s.camera = {{0, 28, 12}, {0, 3, 0}, 40};
    s.lights = {LightSettings{}};
    Renderer renderer(160, 120, 1, 1024, true);
    renderer.drawFluid(g, s);
    double covered = 0;
    const double smooth = flatFraction(renderer.lastFrame(), 2, covered);
    EXPECT_EQ(covered, 1.0) << "the top must be one surface, without holes";
    EXPECT_GT(smooth, 0.97);
    // The bare spheres (no smoothing) are bumpy: the test can tell.
    s.render.fluidSmoothing = 0;
    renderer.drawFluid(g, s);
    EXPECT_LT(flatFraction(renderer.lastFrame(), 2, covered), 0.6);
}

TEST(LiquidRender, FluidMotionPassIsTheScreenShiftOfItsGlobulesOverOneFrame) {
    // A globule of radius 1 at 10 units/s across the view, 9 units in front of the eye:
    // over 1/25 s its front moves 0.4 units, 0.4 x focal / 9 pixels to the right.
    Globules g;
    g.add({0, 1, 0}, {10, 0, 0}, 1.0f, 1.0f, 0);
    FrameSetup s;
    s.camera = {{0, 1, 10}, {0, 1, 0}, 40};
    s.lights = {};
    s.frameSeconds = 0.04;
    s.render.fluidSmoothing = 0;  // the bare sphere: its front is 9 units away, exactly
    constexpr int kW = 97, kH = 65;  // odd: the centre pixel looks at the globule's front
    Renderer renderer(kW, kH, 1, 1024, true);
    renderer.drawFluid(g, s);
    const LinearFrame& f = renderer.lastFrame();
    ASSERT_EQ(f.motion.size(), std::size_t(kW) * kH * 2);
    const std::size_t centre = std::size_t(kH / 2) * kW + kW / 2;
    const double focal = 0.5 * kH / std::tan(20 * std::numbers::pi / 180);  // pixels
    EXPECT_NEAR(f.motion[2 * centre], 0.4 * focal / 9, 0.05);
    EXPECT_NEAR(f.motion[2 * centre + 1], 0, 0.05);
}

TEST(LiquidRender, FluidLeavesOpaqueMaterialsAsSpheres) {
    // Material 1 looks opaque: its globule is drawn as a shaded sphere, not as liquid.
    Globules g;
    g.add({-3, 1, 0}, {0, 0, 0}, 1.0f, 1.0f, 0);
    g.add({3, 1, 0}, {0, 0, 0}, 1.0f, 1.0f, 1);
    g.material = {0, 1};
    FrameSetup s;
    s.camera = {{0, 4, 14}, {0, 1, 0}, 40};
    s.lights = {LightSettings{}};
    s.render.color = {1, 0, 0};
    s.materialOptics = {LiquidOptics{}, LiquidOptics{false, {0, 0, 0}, 1.33}};
    Renderer renderer(96, 64, 1);
    renderer.drawFluid(g, s);
    const LinearFrame& f = renderer.lastFrame();
    auto at = [&](Vec3 world) {
        // the globule's centre projects near these pixels: left and right thirds, middle row
        const int x = world.x < 0 ? 96 * 5 / 16 : 96 * 11 / 16;
        const float* p = &f.rgba[(std::size_t(64 / 2) * 96 + x) * 4];
        return Vec3{p[0], p[1], p[2]};
    };
    const Vec3 liquid = at({-3, 1, 0}), sphere = at({3, 1, 0});
    EXPECT_GT(sphere.x, 2 * sphere.z) << "the opaque globule is the red of render.color";
    EXPECT_GT(liquid.z, liquid.x) << "the liquid one is clear, tinted blue by absorption";
    // color_by = material colours the opaque spheres by their material.
    s.render.colorBy = "material";
    s.materialColors = {{0, 0, 1}, {0, 1, 0}};
    renderer.drawFluid(g, s);
    const Vec3 green = at({3, 1, 0});
    EXPECT_GT(green.y, 2 * green.x);
    EXPECT_GT(green.y, 2 * green.z);
}

}  // namespace
}  // namespace globular
