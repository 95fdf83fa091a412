#include "renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "collider_mesh.h"
#include "color_ramp.h"
#include "errors.h"
#include "gl_context.h"
#include "scene_extent.h"

namespace globular {
namespace {

constexpr int kWidth = 320, kHeight = 240;

std::array<int, 3> rgb(const Image& image, int x, int y) {
    const uint8_t* p = image.pixel(x, y);
    return {p[0], p[1], p[2]};
}

int srgbByte(double linear) { return int(std::lround(255 * linearToSrgb(linear))); }

void expectColor(const Image& image, int x, int y, std::array<int, 3> expected, int tolerance) {
    const auto got = rgb(image, x, y);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(got[c], expected[c], tolerance)
            << "pixel (" << x << ", " << y << ") channel " << c;
    }
}

/// A camera on +z looking at the origin with a 90 degree vertical field of view, a white
/// light shining from the camera, no sky light, no highlight, no ground: a sphere's
/// centre pixel is then exactly its base colour.
FrameSetup flatSetup() {
    FrameSetup s;
    s.camera = {{0, 0, 10}, {0, 0, 0}, 90};
    LightSettings light;
    light.direction = {0, 0, -1};
    light.color = {1, 1, 1};
    light.intensity = 1;
    light.shadows = false;
    s.lights = {light};
    s.render.environmentIntensity = 0;  // no sky light
    s.render.ambientOcclusion = 0;
    s.render.specular = 0;
    s.render.ground = false;
    s.render.color = {0.8, 0.3, 0.2};  // sRGB bytes 204, 77, 51
    s.render.background = {1, 1, 1};
    return s;
}

constexpr std::array<int, 3> kBase{204, 77, 51}, kWhite{255, 255, 255};

Globules oneSphere(Vec3 center, float radius) {
    Globules g;
    g.add(center, {}, radius, 1, 0);
    return g;
}

/// Whether more than half of pixel (x, y) is covered by a sphere drawn over the white
/// background. Sphere pixels have green at most 77 (however they are lit); half covered,
/// the linear mean of white and such a colour is about 190 in sRGB.
bool covered(const Image& image, int x, int y) { return image.pixel(x, y)[1] < 190; }

int widthOnRow(const Image& image, int y) {
    int count = 0;
    for (int x = 0; x < image.width; ++x) count += covered(image, x, y);
    return count;
}

TEST(GlContext, IsAnOpenGlCoreProfile) {
    const std::string description = glContextDescription();
    EXPECT_NE(description.find("Core Profile"), std::string::npos) << description;
}

TEST(Renderer, ColorByMaterialGivesEachMaterialItsColour) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup setup = flatSetup();
    setup.render.colorBy = "material";
    setup.materialColors = {{0.8, 0.3, 0.2}, {0.2, 0.6, 0.8}};  // sRGB bytes 51, 153, 204
    Globules g;
    g.add({-3, 0, 0}, {}, 1, 1, 0);
    g.add({3, 0, 0}, {}, 1, 1, 1);
    g.material = {0, 1};
    const Image image = renderer.drawSpheres(g, setup);
    const int offset = int(std::lround(0.3 * kHeight / 2));  // x = +-3 at distance 10
    // Seen off-axis, the point under the projected centre is lit a little obliquely.
    expectColor(image, kWidth / 2 - offset, kHeight / 2, kBase, 8);
    expectColor(image, kWidth / 2 + offset, kHeight / 2, {51, 153, 204}, 8);
}

std::array<int, 3> srgbBytes(Vec3 c) {
    return {int(std::lround(255 * c.x)), int(std::lround(255 * c.y)), int(std::lround(255 * c.z))};
}

TEST(Renderer, ColorByTemperatureGivesHotAndColdTheirBlackbodyColours) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup setup = flatSetup();
    setup.render.colorBy = "temperature";
    setup.render.temperatureLow = 200;
    setup.render.temperatureHigh = 1200;
    Globules g;
    g.add({-3, 0, 0}, {}, 1, 1, 0);
    g.add({3, 0, 0}, {}, 1, 1, 1);
    g.temperature = {450, 1050};  // t = 0.25 (dark red) and 0.85 (yellow)
    const Image image = renderer.drawSpheres(g, setup);
    const int offset = int(std::lround(0.3 * kHeight / 2));
    const auto cold = rgb(image, kWidth / 2 - offset, kHeight / 2);
    const auto hot = rgb(image, kWidth / 2 + offset, kHeight / 2);
    expectColor(image, kWidth / 2 - offset, kHeight / 2, srgbBytes(blackbodyColor(0.25)), 8);
    expectColor(image, kWidth / 2 + offset, kHeight / 2, srgbBytes(blackbodyColor(0.85)), 8);
    EXPECT_GT(hot[1], cold[1] + 100);  // the hot one is far brighter

    // Globules without temperature cannot be coloured by it.
    g.temperature.clear();
    EXPECT_THROW(renderer.drawSpheres(g, setup), Error);
}

TEST(Renderer, MeshIsColouredByItsPerVertexTemperatureOrMaterial) {
    Renderer renderer(kWidth, kHeight, 1);
    const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const float hot[] = {90, 90, 90, 90};
    FrameSetup setup = flatSetup();
    setup.render.colorBy = "temperature";  // 0 to 100 by default
    MeshView mesh{positions, normals, 4, triangles, 2, true, hot};
    expectColor(renderer.drawMesh(mesh, setup), kWidth / 2, kHeight / 2,
                srgbBytes(blackbodyColor(0.9)), 2);
    mesh.values = nullptr;
    EXPECT_THROW(renderer.drawMesh(mesh, setup), Error);

    const float second[] = {1, 1, 1, 1};
    setup.render.colorBy = "material";
    setup.materialColors = {{0.8, 0.3, 0.2}, {0.2, 0.6, 0.8}};
    mesh.values = second;
    expectColor(renderer.drawMesh(mesh, setup), kWidth / 2, kHeight / 2, {51, 153, 204}, 2);
    mesh.values = nullptr;  // no attribute: material 0
    expectColor(renderer.drawMesh(mesh, setup), kWidth / 2, kHeight / 2, kBase, 2);
}

TEST(Renderer, OneSphereIsADiscOfItsColourAtItsProjectedPlace) {
    Renderer renderer(kWidth, kHeight, 4);
    const FrameSetup setup = flatSetup();
    const Image image = renderer.drawSpheres(oneSphere({0, 0, 0}, 1), setup);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    // The sphere's silhouette: tangent cone half-angle asin(r / d), so on screen a disc
    // of radius tan(asin(0.1)) / tan(45 degrees) * 120 pixels = 12.06 pixels.
    const double radius = std::tan(std::asin(0.1)) * kHeight / 2;
    expectColor(image, kWidth / 2, kHeight / 2, kBase, 1);
    EXPECT_NEAR(widthOnRow(image, kHeight / 2), 2 * radius, 1.0);
    int height = 0;
    for (int y = 0; y < kHeight; ++y) height += covered(image, kWidth / 2, y);
    EXPECT_NEAR(height, 2 * radius, 1.0);
    expectColor(image, kWidth / 2, kHeight / 2 - 14, kWhite, 0);
    expectColor(image, 5, 5, kWhite, 0);
}

TEST(Renderer, OffCentreSphereLandsWhereThePerspectiveSays) {
    Renderer renderer(kWidth, kHeight, 4);
    const Image image = renderer.drawSpheres(oneSphere({3, 1.5, 0}, 1), flatSetup());
    // Exact silhouette extent along x: the tangents from the eye to the circle of radius 1
    // at (3, depth 10) in the x-z plane.
    const double theta = std::atan2(3.0, 10.0), alpha = std::asin(1 / std::sqrt(109.0));
    const double focal = kHeight / 2.0;  // pixels per unit of x/depth (90 degrees)
    const double left = kWidth / 2.0 + std::tan(theta - alpha) * focal;
    const double right = kWidth / 2.0 + std::tan(theta + alpha) * focal;
    const int row = int(std::lround(kHeight / 2.0 - 1.5 / 10 * focal));
    int first = -1, last = -1;
    for (int x = 0; x < kWidth; ++x) {
        if (covered(image, x, row)) {
            if (first < 0) first = x;
            last = x;
        }
    }
    EXPECT_NEAR(first, left, 1.0);
    EXPECT_NEAR(last + 1, right, 1.0);
}

TEST(Renderer, SilhouettesAreAntiAliased) {
    auto partialPixels = [](const Image& image) {
        int partial = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const int g = image.pixel(x, y)[1];
                partial += g > 100 && g < 245;  // neither sphere (<= 77) nor background
            }
        }
        return partial;
    };
    Renderer smooth(kWidth, kHeight, 4);
    // The edge of a disc 24 pixels across crosses about 75 pixels.
    EXPECT_GT(partialPixels(smooth.drawSpheres(oneSphere({0, 0, 0}, 1), flatSetup())), 40);
    Renderer aliased(kWidth, kHeight, 1);
    EXPECT_EQ(partialPixels(aliased.drawSpheres(oneSphere({0, 0, 0}, 1), flatSetup())), 0);
}

TEST(Renderer, ColourByHeightFollowsTheRamp) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup setup = flatSetup();
    setup.render.colorBy = "height";
    setup.ramp.add(-1, 1);
    // Spheres whose centres project onto the centres of pixels (112, 108) and (208, 132):
    // that pixel's ray meets the point facing the eye, lit by the angle between its
    // normal and the light (along -z).
    auto centerAt = [](int x, int y) {
        return Vec3{(x + 0.5 - kWidth / 2.0) / (kHeight / 2.0) * 10,
                    (kHeight / 2.0 - y - 0.5) / (kHeight / 2.0) * 10, 0};
    };
    const Vec3 a = centerAt(112, 108), b = centerAt(208, 132);
    Globules g = oneSphere(a, 0.5f);
    g.add(b, {}, 0.5f, 1, 1);
    const Image image = renderer.drawSpheres(g, setup);
    auto expected = [](Vec3 center) {
        const double lit = normalized(Vec3{0, 0, 10} - center).z;
        const Vec3 c = srgbToLinear(rampColor((center.y + 1) / 2)) * lit;
        return std::array<int, 3>{srgbByte(c.x), srgbByte(c.y), srgbByte(c.z)};
    };
    expectColor(image, 112, 108, expected(a), 2);
    expectColor(image, 208, 132, expected(b), 2);
}

TEST(Renderer, ColourBySpeedFollowsTheRamp) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup setup = flatSetup();
    setup.render.colorBy = "speed";
    setup.ramp.add(0, 10);
    Globules g;
    g.add({0, 0, 0}, {3, 4, 0}, 1, 1, 0);  // speed 5: the middle of the ramp
    const Image image = renderer.drawSpheres(g, setup);
    const Vec3 c = rampColor(0.5);
    expectColor(
        image, kWidth / 2, kHeight / 2,
        {int(std::lround(255 * c.x)), int(std::lround(255 * c.y)), int(std::lround(255 * c.z))}, 2);
}

TEST(Renderer, NonFiniteGlobulesAreSkipped) {
    Renderer renderer(kWidth, kHeight, 4);
    Globules g = oneSphere({0, 0, 0}, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    g.add({0, 0, 0}, {}, 1, 1, 1);
    g.px.back() = nan;
    g.add({2, 0, 0}, {}, 1, 1, 2);
    g.radius.back() = std::numeric_limits<float>::infinity();
    g.add({-2, 0, 0}, {}, 0, 1, 3);  // no radius: nothing to draw
    const Image image = renderer.drawSpheres(g, flatSetup());
    const Image reference = renderer.drawSpheres(oneSphere({0, 0, 0}, 1), flatSetup());
    EXPECT_EQ(image.rgba, reference.rgba);
}

TEST(Renderer, EmptyFrameShowsTheGroundAlone) {
    Renderer renderer(kWidth, kHeight, 4);
    FrameSetup setup;
    setup.camera = {{0, 4, 12}, {0, 0, 0}, 40};
    setup.lights = {LightSettings{}};
    setup.render.environmentIntensity = 0;  // the key light alone, matte
    setup.render.specular = 0;
    const Image image = renderer.drawSpheres(Globules{}, setup);
    // Sky: the background exactly.
    const Vec3 bg = setup.render.background;
    expectColor(
        image, kWidth / 2, 2,
        {int(std::lround(255 * bg.x)), int(std::lround(255 * bg.y)), int(std::lround(255 * bg.z))},
        1);
    // Ground in front of the camera: lit ground colour, light or dark checker square.
    const Vec3 ground = srgbToLinear(setup.render.groundColor);
    const Vec3 toward = normalized(-1.0 * LightSettings{}.direction);
    const Vec3 light = srgbToLinear(LightSettings{}.color);
    const auto [r, g, b] = rgb(image, kWidth / 2, kHeight - 3);
    const double lit = light.x * toward.y;  // red channel
    EXPECT_LE(r, srgbByte(ground.x * lit) + 1);
    EXPECT_GE(r, srgbByte(ground.x * lit * (1 - 0.12)) - 1);
    EXPECT_GT(g, 0);
    EXPECT_GT(b, 0);
}

/// A sphere of radius 1 at (0, 3, 0) over a uniform ground lit by a white sun along
/// @p sunDirection alone (matte, no environment, no occlusion), seen from @p camera.
struct SunlitSphere {
    FrameSetup setup;
    Image image;
    SunlitSphere(ViewCamera camera, Vec3 sunDirection) {
        Renderer renderer(kWidth, kHeight, 4);
        setup.camera = camera;
        LightSettings sun;
        sun.direction = sunDirection;
        sun.color = {1, 1, 1};
        setup.lights = {sun};
        setup.render.checkerSize = 1000;  // one checker square: a uniform ground
        setup.render.environmentIntensity = 0;
        setup.render.specular = 0;
        setup.render.ambientOcclusion = 0;
        Bounds3 content;
        content.add(Vec3{-4, 0, -4});
        content.add(Vec3{4, 4, 4});
        setup.content = content;
        image = renderer.drawSpheres(oneSphere({0, 3, 0}, 1), setup);
    }
    /// The pixel (column, row from the top) where world point @p p appears.
    std::pair<int, int> pixelOf(Vec3 p) const {
        const Mat4 viewProj = perspective(40, double(kWidth) / kHeight, 0.1, 100) *
                              lookAt(setup.camera.position, setup.camera.target);
        const Vec4 c = transformPoint(viewProj, p);
        return {int((c.x / c.w + 1) / 2 * kWidth), int((1 - c.y / c.w) / 2 * kHeight)};
    }
};

TEST(Renderer, KeyLightCastsAShadowOnTheGround) {
    // Straight down: the shadow lies under the sphere.
    const SunlitSphere scene({{0, 12, 12}, {0, 0, 0}, 40}, {0, -1, 0});
    const Vec3 ground = srgbToLinear(scene.setup.render.groundColor);
    const auto [sx, sy] = scene.pixelOf({0, 0, 0.6});  // in the shadow, in front of the sphere
    const auto [lx, ly] = scene.pixelOf({3, 0, 0});    // in the sun
    // Light squares of the checker are the ground colour itself (checker 0 there).
    expectColor(scene.image, sx, sy, {0, 0, 0}, 1);
    EXPECT_NEAR(rgb(scene.image, lx, ly)[0], srgbByte(ground.x), 3);
}

TEST(Renderer, ALowLightsLongShadowReachesItsEnd) {
    // The ground is drawn with the shadow filter only where a caster's shadow can fall
    // (ground_shadow_region.h). A low sun throws the sphere's shadow far from it: all of
    // that must still be dark, and the ground beyond it lit. Low, from +x: the shadow
    // falls to -x, the sphere's centre 3 / 0.35 = 8.6 units away.
    const SunlitSphere scene({{-5, 14, 16}, {-5, 0, 0}, 40}, normalized(Vec3{-1, -0.35, 0}));
    const auto [sx, sy] = scene.pixelOf({-3.0 / 0.35, 0, 0});
    const auto [lx, ly] = scene.pixelOf({-3.0 / 0.35 - 5, 0, 0});  // past the shadow's end
    expectColor(scene.image, sx, sy, {0, 0, 0}, 1);
    EXPECT_GT(rgb(scene.image, lx, ly)[0], 40);
}

TEST(Renderer, MeshCoversItsProjection) {
    Renderer renderer(kWidth, kHeight, 4);
    // A square of side 2 facing the camera at z = 0: at distance 10 with 90 degrees it
    // spans 2 / 20 of the image height, centred.
    const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const MeshView mesh{positions, normals, 4, triangles, 2};
    const Image image = renderer.drawMesh(mesh, flatSetup());
    expectColor(image, kWidth / 2, kHeight / 2, kBase, 1);
    EXPECT_NEAR(widthOnRow(image, kHeight / 2), 0.1 * kHeight, 1.0);
    // Without normals the faces' own normal gives the same flat square.
    const MeshView faceted{positions, nullptr, 4, triangles, 2};
    expectColor(renderer.drawMesh(faceted, flatSetup()), kWidth / 2, kHeight / 2, kBase, 1);
}

TEST(Renderer, ClosedMeshesSkipBackFaces) {
    Renderer renderer(kWidth, kHeight, 1);
    // Wound clockwise as the camera sees it: a back face.
    const float positions[] = {-1, -1, 0, -1, 1, 0, 1, -1, 0};
    const uint32_t triangles[] = {0, 1, 2};
    MeshView mesh{positions, nullptr, 3, triangles, 1};
    expectColor(renderer.drawMesh(mesh, flatSetup()), kWidth / 2 - 3, kHeight / 2 + 3, kBase, 1);
    mesh.closed = true;
    expectColor(renderer.drawMesh(mesh, flatSetup()), kWidth / 2 - 3, kHeight / 2 + 3, kWhite, 0);
}

TEST(Renderer, MeshIndexOutOfRangeIsAnError) {
    Renderer renderer(64, 48, 1);
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t triangles[] = {0, 1, 3};
    EXPECT_THROW(renderer.drawMesh({positions, nullptr, 3, triangles, 1}, flatSetup()), Error);
}

TEST(Renderer, UnsupportedSampleCountIsAClearError) {
    try {
        Renderer renderer(64, 48, 64);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("samples"), std::string::npos) << e.what();
    }
}

TEST(Renderer, BigSpheresAreDrawnAsSquaresIdentically) {
    // Close to the camera a sphere outgrows a point sprite; the square path must give
    // the same disc as a far, small sphere scaled up.
    Renderer renderer(kWidth, kHeight, 4);
    FrameSetup setup = flatSetup();
    const Image image = renderer.drawSpheres(oneSphere({0, 0, 0}, 5), setup);
    const double radius = std::tan(std::asin(0.5)) * kHeight / 2;  // 69 pixels
    EXPECT_NEAR(widthOnRow(image, kHeight / 2), 2 * radius, 1.0);
    expectColor(image, kWidth / 2, kHeight / 2, kBase, 1);
}

/// A dense heap, radius 1 at spacing about 1: most globules are hidden behind others.
Globules denseHeap(std::size_t n) {
    Globules g;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const double side = std::cbrt(double(n));
    for (std::size_t i = 0; i < n; ++i) {
        const double x = side * u(rng), z = side * u(rng);
        const double y = 0.5 * side * (1 - (x * x + z * z) / (2 * side * side)) * (1 + u(rng));
        g.add({x, y, z}, {u(rng), u(rng), u(rng)}, float(0.8 + 0.2 * (1 + u(rng))), 1, int32_t(i));
    }
    return g;
}

TEST(Renderer, OcclusionCullingLeavesTheImageUnchanged) {
    // Culling only drops spheres that cannot change a sample: the frame, shadows,
    // anti-aliasing and all, is the same byte for byte.
    const Globules heap = denseHeap(20000);
    SceneExtent extent;
    extent.addFrame(heap);
    for (int samples : {1, 4}) {
        Renderer renderer(kWidth, kHeight, samples);
        FrameSetup setup;
        setup.lights = {LightSettings{}};
        setup.render.colorBy = "speed";
        setup.camera = autoFrame(extent, 0, 40, double(kWidth) / kHeight);
        const Image culled = renderer.drawSpheres(heap, setup);
        renderer.setOcclusionCulling(false);
        const Image all = renderer.drawSpheres(heap, setup);
        ASSERT_EQ(culled.width, all.width);
        std::size_t differing = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) differing += rgb(culled, x, y) != rgb(all, x, y);
        }
        EXPECT_EQ(differing, 0u) << samples << " samples";
    }
}

TEST(Renderer, OcclusionCullingAtTheFrameEdgeLeavesTheImageUnchanged) {
    // A big sphere whose centre is just off the left edge, in front of small ones inside
    // the frame: however the driver clips it, culling must not change what shows.
    Globules g;
    g.add({-10.8, 0, 2}, {}, 3, 1, 0);  // centre at x / depth = -1.35, the edge at -1.33
    int32_t id = 1;
    for (double y = -3; y <= 3; y += 0.5) {
        for (double x = -17; x <= -13.5; x += 0.5) g.add({x, y, -3}, {}, 0.3f, 1, id++);
    }
    for (int samples : {1, 4}) {
        Renderer renderer(kWidth, kHeight, samples);
        const FrameSetup setup = flatSetup();
        const Image culled = renderer.drawSpheres(g, setup);
        renderer.setOcclusionCulling(false);
        const Image all = renderer.drawSpheres(g, setup);
        std::size_t differing = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) differing += rgb(culled, x, y) != rgb(all, x, y);
        }
        EXPECT_EQ(differing, 0u) << samples << " samples";
    }
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

/// A box collider of edge 4 around the origin, as the render stage draws it.
Prop boxProp(bool seeThrough) {
    ColliderSettings box;
    box.shape = "box";
    box.size = {4, 4, 4};
    box.inside = seeThrough;
    return {colliderMesh(box, ColliderSolid(box, {}, 1), Pose{}), drawnSeeThrough(box)};
}

TEST(RendererProps, AnOpaqueColliderHidesWhatIsInsideIt) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup s = flatSetup();
    s.props = {boxProp(false)};
    const Image image = renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    // The box's face towards the camera, lit head-on: its neutral grey (sRGB 0.78).
    expectColor(image, kWidth / 2, kHeight / 2, {199, 199, 194}, 3);
}

TEST(RendererProps, AContainerIsACutawayThatShowsItsContent) {
    Renderer renderer(kWidth, kHeight, 1);
    FrameSetup s = flatSetup();
    s.props = {boxProp(true)};
    const Image image = renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    expectColor(image, kWidth / 2, kHeight / 2, kBase, 2);  // the sphere, through the cut
    // Beside the sphere: the tank's far wall, grey, not the white background.
    const auto wall = rgb(image, kWidth / 2 + 22, kHeight / 2);
    EXPECT_LT(wall[0], 230);
    EXPECT_NEAR(wall[0], wall[1], 3);
}

/// The frames @p draw(renderer, setup) makes with the ambient occlusion drawn only
/// around the occluders and over every pixel differ in no pixel.
template <typename Draw>
void expectOcclusionRegionsChangeNothing(const FrameSetup& setup, Draw&& draw) {
    for (int samples : {1, 4}) {
        Renderer renderer(kWidth, kHeight, samples);
        const Image around = draw(renderer, setup);
        renderer.setOcclusionRegions(false);
        const Image everywhere = draw(renderer, setup);
        FrameSetup none = setup;
        none.render.ambientOcclusion = 0;
        const Image unoccluded = draw(renderer, none);
        std::size_t differing = 0, darkened = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                differing += rgb(around, x, y) != rgb(everywhere, x, y);
                darkened += rgb(everywhere, x, y) != rgb(unoccluded, x, y);
            }
        }
        EXPECT_EQ(differing, 0u) << samples << " samples";
        EXPECT_GT(darkened, 500u) << "the occlusion must show for the test to mean anything";
    }
}

/// Looking down at the ground steeply (no horizon, where the pass over every pixel also
/// darkens a few ground pixels whose normals its depth steps bend: see
/// docs/performance.md, twenty-fourth pass), far enough that the content fills a part of
/// the frame; a strong occlusion reaching well beyond the content.
FrameSetup occludedSetup() {
    FrameSetup s;
    s.camera = {{-6, 16, 12}, {0, 1, 0}, 40};
    s.lights = {LightSettings{}};
    s.render.ambientOcclusion = 1;
    s.render.occlusionRadius = 2;
    return s;
}

TEST(RendererProps, OcclusionAroundTheOccludersOnlyLeavesTheImageUnchanged) {
    // The occlusion pass over the occluders' tiles only (render/occlusion_region.h): the
    // same frame, byte for byte, as over every pixel, for spheres, a mesh and a prop,
    // with the contact shadows on the ground around them and on each other.
    Globules heap;
    for (int i = 0; i < 40; ++i) {
        heap.add({-1.5 + 0.15 * (i % 7), 0.5 + 0.3 * (i / 7), 0.4 * (i % 3)}, {}, 0.5f, 1, i);
    }
    FrameSetup withProp = occludedSetup();
    Prop box = boxProp(false);
    for (std::size_t v = 0; v < box.mesh.positions.size(); v += 3) {
        box.mesh.positions[v] += 5;      // beside the heap, standing on the ground
        box.mesh.positions[v + 1] += 2;
    }
    withProp.props = {box};
    auto spheres = [&](Renderer& r, const FrameSetup& s) { return r.drawSpheres(heap, s); };
    expectOcclusionRegionsChangeNothing(occludedSetup(), spheres);
    expectOcclusionRegionsChangeNothing(withProp, spheres);
    // The box as the content, a mesh.
    Prop content = boxProp(false);
    for (std::size_t v = 1; v < content.mesh.positions.size(); v += 3) {
        content.mesh.positions[v] += 2;
    }
    const TriangleMesh& m = content.mesh;
    const MeshView view{m.positions.data(), m.normals.data(), m.vertexCount(), m.triangles.data(),
                        m.triangleCount(), true};
    expectOcclusionRegionsChangeNothing(
        occludedSetup(), [&](Renderer& r, const FrameSetup& s) { return r.drawMesh(view, s); });
}

}  // namespace
}  // namespace globular
