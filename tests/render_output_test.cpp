// What the renderer hands a compositor: the linear frame with its passes (distance from
// the eye, world normal), EXR files with those channels, a transparent background, and
// the render stage's 16-bit PNG and EXR frames. Draws through OSMesa.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>

#include "color_ramp.h"
#include "errors.h"
#include "exr_image.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "recording_reporter.h"
#include "render_stage.h"
#include "renderer.h"
#include "tone_map.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

// Odd sizes: the middle pixel's centre lies on the camera's axis.
constexpr int kWidth = 161, kHeight = 121;

/// A camera on +z, 10 units from the origin, looking at it; a light from the camera; no
/// ground. One sphere of radius 2 at the origin: its front is 8 units from the eye.
FrameSetup sphereSetup() {
    FrameSetup s;
    s.camera = {{0, 0, 10}, {0, 0, 0}, 60};
    LightSettings light;
    light.direction = {0, 0, -1};
    light.color = {1, 1, 1};
    light.shadows = false;
    s.lights = {light};
    s.render.ground = false;
    s.render.specular = 0;
    s.render.environmentIntensity = 0;  // no sky light
    s.render.ambientOcclusion = 0;
    s.render.color = {0.8, 0.3, 0.2};
    return s;
}

Globules sphereAtOrigin() {
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 2.0f, 1, 0);
    return g;
}

std::size_t at(int x, int y) { return std::size_t(y) * kWidth + x; }

TEST(RenderPasses, CentreOfASphereFacesTheCameraAtTheDistanceOfItsFront) {
    Renderer renderer(kWidth, kHeight, 4, 1024, /*passes=*/true);
    renderer.drawSpheres(sphereAtOrigin(), sphereSetup());
    const LinearFrame& f = renderer.lastFrame();
    ASSERT_TRUE(f.hasPasses());
    ASSERT_EQ(f.width, kWidth);
    ASSERT_EQ(f.height, kHeight);
    const std::size_t c = at(kWidth / 2, kHeight / 2);
    EXPECT_NEAR(f.depth[c], 8.0f, 1e-3f);
    EXPECT_NEAR(f.normal[3 * c + 0], 0.0f, 1e-2f);
    EXPECT_NEAR(f.normal[3 * c + 1], 0.0f, 1e-2f);
    EXPECT_NEAR(f.normal[3 * c + 2], 1.0f, 1e-3f);  // towards the camera on +z
    // Towards the right edge the normal turns right and the surface recedes.
    const std::size_t right = at(kWidth / 2 + 12, kHeight / 2);
    EXPECT_GT(f.normal[3 * right], 0.2f);
    EXPECT_GT(f.depth[right], 8.0f);
    // The sky: nothing there.
    EXPECT_EQ(f.depth[at(0, 0)], LinearFrame::kNothing);
    EXPECT_EQ(f.normal[3 * at(0, 0) + 2], 0.0f);
    // Colour is linear: the lit centre is the base colour in linear light.
    EXPECT_NEAR(f.pixel(kWidth / 2, kHeight / 2)[1], srgbToLinear(0.3), 2e-3);
    EXPECT_EQ(f.pixel(0, 0)[3], 1.0f);  // opaque background by default
}

TEST(RenderPasses, MeshAndGroundWriteThePassesToo) {
    Renderer renderer(kWidth, kHeight, 1, 1024, true);
    FrameSetup s = sphereSetup();
    s.render.ground = true;
    s.groundHeight = -1;
    s.camera = {{0, 2, 10}, {0, -1, 0}, 60};
    // A mesh square facing +z at z = 1, across the middle of the view.
    const float positions[] = {-1, -1, 1, 1, -1, 1, 1, 1.5f, 1, -1, 1.5f, 1};
    const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    renderer.drawMesh({positions, normals, 4, triangles, 2, false, nullptr}, s);
    const LinearFrame& f = renderer.lastFrame();
    const std::size_t c = at(kWidth / 2, kHeight / 2);
    // The view axis from (0, 2, 10) to (0, -1, 0) meets z = 1 at y = -0.7.
    EXPECT_NEAR(f.normal[3 * c + 2], 1.0f, 1e-3f);
    EXPECT_NEAR(f.depth[c], std::sqrt(9.0f * 9.0f + 2.7f * 2.7f), 1e-2f);
    const std::size_t ground = at(kWidth / 2, kHeight - 2);  // bottom middle: the ground
    EXPECT_NEAR(f.normal[3 * ground + 1], 1.0f, 1e-3f);
    EXPECT_LT(f.depth[ground], 20.0f);
    // A mesh has no velocities: no motion pass, whatever the interval.
    s.frameSeconds = 0.04;
    renderer.drawMesh({positions, normals, 4, triangles, 2, false, nullptr}, s);
    EXPECT_TRUE(f.motion.empty());
    EXPECT_TRUE(f.hasPasses());
}

TEST(RenderPasses, TransparentBackgroundHasAlphaZeroAroundTheSubject) {
    Renderer renderer(kWidth, kHeight, 4, 1024);
    FrameSetup s = sphereSetup();
    s.render.transparent = true;
    const Image image = renderer.drawSpheres(sphereAtOrigin(), s);
    for (auto [x, y] : {std::pair{0, 0}, {kWidth - 1, 0}, {0, kHeight - 1}, {kWidth - 1, kHeight - 1}}) {
        EXPECT_EQ(image.pixel(x, y)[3], 0) << x << ", " << y;
        EXPECT_EQ(renderer.lastFrame().pixel(x, y)[3], 0.0f);
    }
    EXPECT_EQ(image.pixel(kWidth / 2, kHeight / 2)[3], 255);
    // Straight alpha in the image: the subject keeps its colour (sRGB 0.3 green = 77).
    EXPECT_NEAR(image.pixel(kWidth / 2, kHeight / 2)[1], 77, 1);
    // The silhouette is partly covered.
    int partial = 0;
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) {
        partial += image.rgba[i] > 0 && image.rgba[i] < 255;
    }
    EXPECT_GT(partial, 20);
    // Opaque, the same corners are the background.
    s.render.transparent = false;
    const Image opaque = renderer.drawSpheres(sphereAtOrigin(), s);
    EXPECT_EQ(opaque.pixel(0, 0)[3], 255);
}

TEST(RenderPasses, TransparentGroundFadesIntoAlpha) {
    Renderer renderer(kWidth, kHeight, 1, 1024);
    FrameSetup s = sphereSetup();
    s.render.transparent = true;
    s.render.ground = true;
    s.groundHeight = -2;
    s.camera = {{0, 3, 10}, {0, 0, 0}, 60};
    const Image image = renderer.drawSpheres(sphereAtOrigin(), s);
    EXPECT_EQ(image.pixel(0, 0)[3], 0);                       // sky
    EXPECT_EQ(image.pixel(kWidth / 2, kHeight - 1)[3], 255);  // near ground, opaque
}

TEST(RenderPasses, ExposureOfOneStopDoublesTheLinearColour) {
    Renderer renderer(kWidth, kHeight, 1, 1024);
    FrameSetup s = sphereSetup();
    s.render.exposure = 1;
    const Image image = renderer.drawSpheres(sphereAtOrigin(), s);
    const uint8_t* p = image.pixel(kWidth / 2, kHeight / 2);
    EXPECT_EQ(p[0], 255);  // 0.8 sRGB is 0.60 linear: doubled, clipped
    EXPECT_NEAR(p[1], std::lround(255 * linearToSrgb(2 * srgbToLinear(0.3))), 1);
    EXPECT_NEAR(p[2], std::lround(255 * linearToSrgb(2 * srgbToLinear(0.2))), 1);
    s.render.exposure = 0;
    s.render.toneMapping = "aces";
    const Image filmic = renderer.drawSpheres(sphereAtOrigin(), s);
    EXPECT_NEAR(filmic.pixel(kWidth / 2, kHeight / 2)[1],
                std::lround(255 * linearToSrgb(acesFilmic(float(srgbToLinear(0.3))))), 1);
}

TEST(RenderPasses, MotionIsTheScreenShiftOverOneFrameInPixels) {
    Renderer renderer(kWidth, kHeight, 4, 1024, true);
    FrameSetup s = sphereSetup();
    s.frameSeconds = 0.04;
    Globules g;
    g.add({0, 0, 0}, {25, 0, 0}, 2.0f, 1, 0);  // one unit to the right per frame
    renderer.drawSpheres(g, s);
    const LinearFrame& f = renderer.lastFrame();
    ASSERT_EQ(f.motion.size(), std::size_t(2) * kWidth * kHeight);
    // The front point, 8 units away, moves 1 unit: focal length (pixels) / 8.
    const double focal = 0.5 * kHeight / std::tan(30 * std::numbers::pi / 180);
    const std::size_t c = at(kWidth / 2, kHeight / 2);
    EXPECT_NEAR(f.motion[2 * c], focal / 8, 0.05);
    EXPECT_NEAR(f.motion[2 * c + 1], 0.0, 0.01);
    EXPECT_EQ(f.motion[2 * at(0, 0)], 0.0f);  // nothing there
    // Up and towards the camera: up on the screen, and spreading out from the centre.
    g.vx[0] = 0;
    g.vy[0] = 25;
    renderer.drawSpheres(g, s);
    EXPECT_NEAR(f.motion[2 * c + 1], focal / 8, 0.05);
    // Without an interval, or in mesh mode, there is no motion pass.
    s.frameSeconds = 0;
    renderer.drawSpheres(g, s);
    EXPECT_TRUE(f.motion.empty());
    EXPECT_TRUE(f.hasPasses());
}

/// Reads channel @p name of @p path as floats, rows top first.
std::vector<float> readChannel(const fs::path& path, const char* name) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<float> values(std::size_t(w) * h);
    Imf::FrameBuffer buffer;
    buffer.insert(name, Imf::Slice(Imf::FLOAT, (char*)values.data(), sizeof(float),
                                   sizeof(float) * w));
    file.setFrameBuffer(buffer);
    file.readPixels(window.min.y, window.max.y);
    return values;
}

std::map<std::string, Imf::PixelType> channelsOf(const fs::path& path) {
    Imf::InputFile file(path.c_str());
    std::map<std::string, Imf::PixelType> channels;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
        channels[it.name()] = it.channel().type;
    }
    return channels;
}

TEST(Exr, HoldsLinearRgbaDepthAndNormalWithTheirTypes) {
    Renderer renderer(kWidth, kHeight, 4, 1024, true);
    FrameSetup s = sphereSetup();
    s.render.transparent = true;
    s.render.exposure = 3;  // not in the EXR: it stays scene-linear
    renderer.drawSpheres(sphereAtOrigin(), s);
    const fs::path path = fs::temp_directory_path() / "globular_render_output_test.exr";
    writeExr(path, renderer.lastFrame());
    const std::map<std::string, Imf::PixelType> expected{
        {"R", Imf::HALF},   {"G", Imf::HALF},   {"B", Imf::HALF},   {"A", Imf::HALF},
        {"Z", Imf::FLOAT},  {"N.x", Imf::HALF}, {"N.y", Imf::HALF}, {"N.z", Imf::HALF}};
    EXPECT_EQ(channelsOf(path), expected);
    const std::size_t c = at(kWidth / 2, kHeight / 2), corner = at(0, 0);
    EXPECT_NEAR(readChannel(path, "Z")[c], 8.0f, 1e-3f);
    EXPECT_EQ(readChannel(path, "Z")[corner], LinearFrame::kNothing);
    EXPECT_NEAR(readChannel(path, "N.z")[c], 1.0f, 1e-3f);
    EXPECT_NEAR(readChannel(path, "G")[c], srgbToLinear(0.3), 2e-3);
    EXPECT_EQ(readChannel(path, "A")[c], 1.0f);
    EXPECT_EQ(readChannel(path, "A")[corner], 0.0f);
    EXPECT_EQ(readChannel(path, "R")[corner], 0.0f);
    // With motion: forward.u and forward.v, half.
    Globules moving = sphereAtOrigin();
    moving.vx[0] = 25;
    s.frameSeconds = 0.04;
    renderer.drawSpheres(moving, s);
    writeExr(path, renderer.lastFrame());
    const auto withMotion = channelsOf(path);
    EXPECT_EQ(withMotion.size(), 10u);
    EXPECT_EQ(withMotion.at("forward.u"), Imf::HALF);
    EXPECT_EQ(withMotion.at("forward.v"), Imf::HALF);
    EXPECT_GT(readChannel(path, "forward.u")[c], 10.0f);
    // Without passes: colour and alpha only.
    Renderer plain(kWidth, kHeight, 1, 1024);
    plain.drawSpheres(sphereAtOrigin(), sphereSetup());
    writeExr(path, plain.lastFrame());
    EXPECT_EQ(channelsOf(path).size(), 4u);
    fs::remove(path);
}

TEST(Exr, UnwritablePathIsAnIoErrorNamingIt) {
    LinearFrame f;
    f.width = f.height = 2;
    f.rgba.assign(16, 0.5f);
    EXPECT_THROW(writeExr("/proc/globular/x.exr", f), IoError);
    f.rgba.resize(3);
    EXPECT_THROW(writeExr(fs::temp_directory_path() / "bad.exr", f), IoError);
}

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_render_output_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

StageContext context(const fs::path& dir, Reporter& reporter) {
    StageContext ctx;
    ctx.outDir = dir;
    ctx.firstFrame = 1;
    ctx.lastFrame = 1;
    ctx.reporter = &reporter;
    return ctx;
}

TEST(RenderStageOutput, SixteenBitPngMatchesTheEightBitFrameAndExrSitsBesideIt) {
    const fs::path dir = freshDir("deep");
    Globules g;
    g.add({0, 1, 0}, {1, 0, 0}, 1.0f, 1, 0);
    g.add({1.5, 1, 0}, {0, 2, 0}, 0.7f, 1, 1);
    writeGlobuleVdb(cacheVdbPath(dir, 1), g, {1, 0.04});
    RenderJob job;
    job.render.width = 96;
    job.render.height = 64;
    RecordingReporter reporter("render");
    runRenderStage(job, context(dir, reporter));
    const Image eight = readPng(framePngPath(dir, 1));
    EXPECT_FALSE(fs::exists(dir / "frames" / "frame.0001.exr"));

    job.render.pngBits = 16;
    job.render.exr = true;
    runRenderStage(job, context(dir, reporter));
    int bits = 0;
    const Image16 deep = readPng16(framePngPath(dir, 1), &bits);
    EXPECT_EQ(bits, 16);
    ASSERT_EQ(deep.rgba.size(), eight.rgba.size());
    int worst = 0;
    for (std::size_t i = 0; i < deep.rgba.size(); ++i) {
        worst = std::max(worst, int(std::lround(std::abs(deep.rgba[i] / 257.0 - eight.rgba[i]))));
    }
    EXPECT_LE(worst, 1);
    const fs::path exr = dir / "frames" / "frame.0001.exr";
    ASSERT_TRUE(fs::exists(exr));
    // Spheres at the scene's fps (25): with the motion pass.
    EXPECT_EQ(channelsOf(exr).size(), 10u);
    EXPECT_EQ(channelsOf(exr).count("forward.u"), 1u);

    job.render.pngBits = 8;
    job.render.transparent = true;
    job.render.ground = false;
    runRenderStage(job, context(dir, reporter));
    const Image clear = readPng(framePngPath(dir, 1));
    EXPECT_EQ(clear.pixel(0, 0)[3], 0);
    EXPECT_EQ(readChannel(exr, "A")[0], 0.0f);
}

}  // namespace
}  // namespace globular
