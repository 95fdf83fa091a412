// Physically based shading and light (render/shaders.cpp, environment.h): the white
// furnace (energy is conserved), roughness and metallic per material, soft shadows, the
// environment file's errors, ambient occlusion at contacts (and none on the bare ground).

#include <gtest/gtest.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>

#include "box_mesh.h"
#include "collider_mesh.h"
#include "errors.h"
#include "renderer.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 64;

/// A lat-long OpenEXR of one radiance everywhere.
fs::path uniformEnvironment(float radiance) {
    // One folder per process: ctest runs these tests in parallel processes, and one
    // rewriting the file while another reads it made WhiteFurnace fail now and then.
    const fs::path dir =
        fs::temp_directory_path() / ("globular_lighting_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path path = dir / ("uniform_" + std::to_string(radiance) + ".exr");
    const int width = 16, height = 8;
    std::vector<float> rgb(std::size_t(3) * width * height, radiance);
    Imf::Header header(width, height);
    Imf::FrameBuffer buffer;
    for (int c = 0; c < 3; ++c) {
        const char* name = c == 0 ? "R" : c == 1 ? "G" : "B";
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        buffer.insert(name, Imf::Slice(Imf::FLOAT, (char*)(rgb.data() + c), 3 * sizeof(float),
                                       3 * sizeof(float) * width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(buffer);
    file.writePixels(height);
    return path;
}

Globules oneSphere(Vec3 center, float radius, uint8_t material = 0) {
    Globules g;
    g.add(center, {}, radius, 1, 0);
    if (material != 0) g.material = {material};
    return g;
}

/// A camera on +z at distance 6 looking at a unit sphere at the origin (about 15 pixels
/// of radius), nothing else: no ground, no lights, no occlusion.
FrameSetup bareSetup() {
    FrameSetup s;
    s.camera = {{0, 0, 6}, {0, 0, 0}, 40};
    s.lights = {};
    s.render.ground = false;
    s.render.ambientOcclusion = 0;
    s.render.background = {0, 0, 0};
    s.render.color = {1, 1, 1};
    return s;
}

/// Linear red of the pixel at (dx, dy) pixels from the image's centre.
float redAt(const LinearFrame& f, int dx, int dy) {
    return f.pixel(kSize / 2 + dx, kSize / 2 + dy)[0];
}

// A white diffuse sphere under a uniform white environment reflects exactly what arrives
// at every point: diffuse and specular share the light without creating or losing any.
TEST(Lighting, WhiteFurnace) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = bareSetup();
    s.render.environment = uniformEnvironment(1.0f).string();
    for (double roughness : {1.0, 0.5, 0.1}) {
        s.materialLooks = {{roughness, 0.0}};
        renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
        const LinearFrame& f = renderer.lastFrame();
        int checked = 0;
        for (int dy = -12; dy <= 12; ++dy) {
            for (int dx = -12; dx <= 12; ++dx) {
                if (dx * dx + dy * dy > 12 * 12) continue;
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(f.pixel(kSize / 2 + dx, kSize / 2 + dy)[c], 1.0, 0.03)
                        << "roughness " << roughness << " at (" << dx << ", " << dy << ")";
                }
                ++checked;
            }
        }
        EXPECT_GT(checked, 400);
    }
}

// Twice the environment, twice the light; none, black.
TEST(Lighting, EnvironmentIntensityScalesTheLight) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = bareSetup();
    s.render.environment = uniformEnvironment(1.0f).string();
    s.render.environmentIntensity = 2;
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    EXPECT_NEAR(redAt(renderer.lastFrame(), 0, 0), 2.0, 0.06);
    s.render.environmentIntensity = 0;
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    EXPECT_EQ(redAt(renderer.lastFrame(), 0, 0), 0.0f);
}

FrameSetup keyLitSetup() {
    FrameSetup s = bareSetup();
    s.render.environmentIntensity = 0;
    LightSettings light;
    light.direction = {-0.3, -0.3, -1};  // from behind the camera, up and to the right
    light.color = {1, 1, 1};
    light.shadows = false;
    s.lights = {light};
    return s;
}

float brightest(const LinearFrame& f) {
    float most = 0;
    for (std::size_t i = 0; i < f.rgba.size(); i += 4) most = std::max(most, f.rgba[i]);
    return most;
}

// A smooth surface concentrates the light's reflection into a small bright highlight; a
// rough one spreads it thin (the same energy).
TEST(Lighting, RoughnessSpreadsTheHighlight) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = keyLitSetup();
    s.render.color = {0, 0, 0};  // black: the highlight alone
    s.materialLooks = {{0.15, 0.0}};
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    const float smooth = brightest(renderer.lastFrame());
    s.materialLooks = {{0.8, 0.0}};
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
    const float rough = brightest(renderer.lastFrame());
    EXPECT_GT(smooth, 4 * rough);
    EXPECT_GT(rough, 0.005f);
}

// A metal diffuses nothing: away from its highlight it is dark; a dielectric of the same
// colour shows its colour there. Each globule takes its own material's values.
TEST(Lighting, MetalsReflectTheirColourAndDiffuseNothing) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = keyLitSetup();
    s.render.color = {0.9, 0.2, 0.1};
    s.materialLooks = {{0.3, 0.0}, {0.3, 1.0}};
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1, 0), s);
    const float dielectric = redAt(renderer.lastFrame(), -8, 8);  // lower left: off the highlight
    renderer.drawSpheres(oneSphere({0, 0, 0}, 1, 1), s);
    const float metal = redAt(renderer.lastFrame(), -8, 8);
    EXPECT_GT(dielectric, 0.3f);
    EXPECT_LT(metal, 0.1f * dielectric);
    EXPECT_GT(brightest(renderer.lastFrame()), 0.5f);  // its highlight is there
}

// Subsurface wrap (Fd_Wrap): a white matte sphere, no specular, no environment. Lit from
// the camera, the point facing the light dims to 1 / (1 + w) of Lambert's; lit from the
// side, the centre of the disc lies on the shadow line, dark for Lambert and lit to
// w / (1 + w)^2 with the wrap, and light reaches past it.
TEST(Lighting, SubsurfaceWrapsTheDiffuseLightPastTheShadowLine) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = keyLitSetup();
    s.render.specular = 0;
    const auto centreAndLeft = [&](double w, Vec3 direction) {
        s.lights.front().direction = direction;
        s.materialLooks = {{1.0, 0.0, w}};
        renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
        return std::make_pair(redAt(renderer.lastFrame(), 0, 0),
                              redAt(renderer.lastFrame(), -5, 0));
    };
    const float lambertFacing = centreAndLeft(0, {0, 0, -1}).first;
    const float wrappedFacing = centreAndLeft(0.5, {0, 0, -1}).first;
    EXPECT_NEAR(lambertFacing, 1.0, 0.02);
    EXPECT_NEAR(wrappedFacing / lambertFacing, 1 / 1.5, 0.02);

    const auto [lambertLine, lambertPast] = centreAndLeft(0, {-1, 0, 0});
    const auto [wrappedLine, wrappedPast] = centreAndLeft(0.5, {-1, 0, 0});
    EXPECT_LT(lambertLine, 0.05f);  // the pixel's centre is half a pixel off the line
    EXPECT_EQ(lambertPast, 0.0f);
    EXPECT_NEAR(wrappedLine, 0.5 / (1.5 * 1.5), 0.02);
    EXPECT_GT(wrappedPast, 0.03f);
    EXPECT_LT(wrappedPast, wrappedLine);
}

// A mesh takes each vertex's material (its "material" attribute) for roughness and
// metallic: a square of material 1 (metal) is dark off its highlight where one of
// material 0 (dielectric) shows its colour.
TEST(Lighting, MeshVerticesTakeTheirMaterialsLook) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = keyLitSetup();
    s.lights.front().direction = {1, 0, -1};  // the mirror direction misses the camera
    s.render.color = {0.9, 0.2, 0.1};
    s.materialLooks = {{0.15, 0.0}, {0.15, 1.0}};
    const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    float redOf[2];
    for (int material = 0; material < 2; ++material) {
        const float materials[] = {float(material), float(material), float(material),
                                   float(material)};
        MeshView mesh{positions, normals, 4, triangles, 2, false, nullptr, materials};
        renderer.drawMesh(mesh, s);
        redOf[material] = redAt(renderer.lastFrame(), 0, 0);
    }
    EXPECT_GT(redOf[0], 0.3f);
    EXPECT_LT(redOf[1], 0.1f * redOf[0]);
}

// The shadow's edge on the ground: hard without softness, a penumbra several texels wide
// with it.
int penumbraPixels(double softness) {
    Renderer renderer(kSize, kSize, 1, 256);
    FrameSetup s = bareSetup();
    s.render.ground = true;
    s.render.checkerSize = 1000;
    s.render.environmentIntensity = 0;
    s.render.specular = 0;
    s.render.shadowSoftness = softness;
    s.camera = {{0, 14, 0.01}, {0, 0, 0}, 40};  // looking straight down
    LightSettings sun;
    sun.direction = {1, -1, 0};  // the shadow falls beside the sphere
    sun.color = {1, 1, 1};
    s.lights = {sun};
    Bounds3 content;
    content.add(Vec3{-4, 0, -4});
    content.add(Vec3{4, 4, 4});
    s.content = content;
    renderer.drawSpheres(oneSphere({-1.5, 2, 0}, 1.5), s);
    const LinearFrame& f = renderer.lastFrame();
    const float lit = f.pixel(1, 1)[0];  // a corner of the ground in the sun
    int between = 0;
    for (std::size_t i = 0; i < f.rgba.size(); i += 4) {
        if (f.rgba[i] > 0.1f * lit && f.rgba[i] < 0.8f * lit) ++between;  // checker: 0.88
    }
    return between;
}

// (The sphere's own limb counts the same in both.)
TEST(Lighting, ShadowSoftnessWidensThePenumbra) {
    const int hard = penumbraPixels(0), soft = penumbraPixels(8);
    EXPECT_GT(soft, 2 * hard) << "hard " << hard << ", soft " << soft;
}

/// The occlusion tests' setup: a lit ground seen at an angle,
/// occlusion of radius 1 and strength 1.
FrameSetup occlusionSetup() {
    FrameSetup s = bareSetup();
    s.render.ground = true;
    s.render.checkerSize = 1000;
    s.render.environment = uniformEnvironment(1.0f).string();
    s.camera = {{0, 3, 8}, {0, 0.5, 0}, 40};
    s.content.add(Vec3{-3, 0, -3});
    s.content.add(Vec3{3, 3, 3});
    s.render.occlusionRadius = 1;
    s.render.ambientOcclusion = 1;
    return s;
}

// Ambient occlusion darkens the floor where a sphere rests on it, and leaves the open
// floor and the sphere's top as they were.
TEST(Lighting, AmbientOcclusionDarkensTheContactOnly) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = occlusionSetup();
    s.render.ambientOcclusion = 0;
    const Globules g = oneSphere({0, 1, 0}, 1);  // touching the ground at the origin
    renderer.drawSpheres(g, s);
    const LinearFrame plain = renderer.lastFrame();
    s.render.ambientOcclusion = 1;
    renderer.drawSpheres(g, s);
    const LinearFrame& occluded = renderer.lastFrame();
    // The floor just in front of the contact (found below the sphere's disc).
    int contactY = 0;
    for (int y = kSize - 1; y > 0 && contactY == 0; --y) {
        if (std::abs(plain.pixel(kSize / 2, y)[2] - plain.pixel(kSize / 2, y - 1)[2]) > 0.05f) {
            contactY = y;
        }
    }
    ASSERT_GT(contactY, kSize / 2);
    float darkest = 1;
    for (int y = contactY + 1; y < std::min(contactY + 5, kSize); ++y) {
        darkest = std::min(darkest, occluded.pixel(kSize / 2, y)[1] / plain.pixel(kSize / 2, y)[1]);
    }
    EXPECT_LT(darkest, 0.85f);
    for (auto [x, y] : {std::pair{2, kSize - 2}, std::pair{kSize - 3, kSize - 2},
                        std::pair{kSize / 2, kSize / 2 - 8}}) {
        EXPECT_NEAR(occluded.pixel(x, y)[1], plain.pixel(x, y)[1], 0.01f * plain.pixel(x, y)[1])
            << "(" << x << ", " << y << ")";
    }
}

// Why a liquid frame without props skips the pass (renderer.cpp): the ground is a plane,
// every tap lies above it, so the pass leaves the bare ground as it was, to the bit. Not
// at its far rim, where it fades into the background: there the old pass darkened a row
// or two (a 64-pixel frame's occlusion radius spans pixels out there; at 1920x1080 the
// pour's frames were byte-identical with and without it), so the rows nearer than the
// view's centre are compared.
TEST(Lighting, AmbientOcclusionLeavesTheBareGroundAsItIs) {
    for (int samples : {1, 4}) {
        SCOPED_TRACE(samples);
        Renderer renderer(kSize, kSize, samples);
        FrameSetup s = occlusionSetup();
        renderer.drawSpheres(Globules{}, s);  // opaque content: the pass runs, on the ground
        const LinearFrame occluded = renderer.lastFrame();
        s.render.ambientOcclusion = 0;
        renderer.drawSpheres(Globules{}, s);
        const LinearFrame& plain = renderer.lastFrame();
        std::size_t differing = 0;
        for (int y = kSize / 2; y < kSize; ++y) {  // rows top first: the nearer half
            for (int x = 0; x < kSize; ++x) {
                for (int c = 0; c < 3; ++c) {
                    ASSERT_GT(plain.pixel(x, y)[c], 0.05f) << "the ground must be lit here";
                    differing += occluded.pixel(x, y)[c] != plain.pixel(x, y)[c];
                }
            }
        }
        EXPECT_EQ(differing, 0u);
    }
}

// The skip does not reach a liquid frame with props: a box on the ground still darkens
// the ground at its foot.
TEST(Lighting, ALiquidFrameKeepsItsPropsOcclusion) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = occlusionSetup();
    s.liquidSurface = true;
    ColliderSettings box;
    box.shape = "box";
    box.size = {2, 2, 2};
    box.center = {0, 1, 0};
    s.props = {{colliderMesh(box, ColliderSolid(box, {}, 1), Pose{}), false}};
    const BoxMesh pool({-3, 0, -3}, {-2, 0.2, -2});  // a little liquid, off to one side
    renderer.drawMesh(pool.view(), s);
    const LinearFrame occluded = renderer.lastFrame();
    s.render.ambientOcclusion = 0;
    renderer.drawMesh(pool.view(), s);
    const LinearFrame& plain = renderer.lastFrame();
    // The ground just below the box's front face: the first row under its foot.
    float darkest = 1;
    for (int y = kSize / 2; y < kSize; ++y) {
        const float p = plain.pixel(kSize / 2, y)[1];
        if (p > 0) darkest = std::min(darkest, occluded.pixel(kSize / 2, y)[1] / p);
    }
    EXPECT_LT(darkest, 0.9f);
}

TEST(Lighting, MissingEnvironmentFileIsAnErrorNamingIt) {
    Renderer renderer(kSize, kSize, 1);
    FrameSetup s = bareSetup();
    s.render.environment = "/nonexistent/sky_for_test.exr";
    try {
        renderer.drawSpheres(oneSphere({0, 0, 0}, 1), s);
        FAIL() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("sky_for_test.exr"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace globular
