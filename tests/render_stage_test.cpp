// The render stage end to end: caches or meshes in, frames, contact sheet and movie out.
#include "render_stage.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "errors.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "mesh.h"
#include "png_image.h"
#include "renderer.h"
#include "render_plan.h"
#include "transform.h"
#include "recording_reporter.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// Frame f: a globule falling onto a resting one; frame 3 is empty.
Globules frameGlobules(int f) {
    Globules g;
    if (f == 3) return g;
    g.add({0, 0, 0}, {0, 0, 0}, 1.0f, 1, 0);
    g.add({0.5, 6.0 - f, 0}, {0, -2.0 * f, 0}, 1.0f, 1, 1);
    return g;
}

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_render_stage_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeCaches(const fs::path& dir, int first, int last) {
    for (int f = first; f <= last; ++f) {
        writeGlobuleVdb(cacheVdbPath(dir, f), frameGlobules(f), {f, 0.04 * f});
    }
}

RenderJob smallJob() {
    RenderJob job;
    job.render.width = 64;
    job.render.height = 48;
    return job;
}

StageContext context(const fs::path& dir, int first, int last, Reporter& reporter) {
    StageContext ctx;
    ctx.outDir = dir;
    ctx.firstFrame = first;
    ctx.lastFrame = last;
    ctx.reporter = &reporter;
    return ctx;
}

TEST(RenderStage, AutomaticCameraFramesWhereTheContentIsForMostOfTheShot) {
    // A column 15 units tall for 5 frames, then a puddle 7 units wide for 15: the plan's
    // camera frames the puddle (the subject of three quarters of the shot) large, the
    // column's top leaving the picture, instead of the whole column over a speck.
    const fs::path dir = freshDir("framing");
    for (int f = 1; f <= 20; ++f) {
        Globules g;
        if (f <= 5) {
            for (int k = 0; k < 30; ++k) g.add({0, 0.5 + 0.5 * k, 0}, {0, -5, 0}, 0.5f, 1, k);
        } else {
            for (int i = 0; i < 7; ++i) {
                for (int j = 0; j < 7; ++j) g.add({i - 3.0, 0.5, j - 3.0}, {}, 0.5f, 1, 7 * i + j);
            }
        }
        writeGlobuleVdb(cacheVdbPath(dir, f), g, {f, 0.04 * f});
    }
    RecordingReporter reporter;
    RenderJob job = smallJob();
    job.render.width = 160;
    job.render.height = 90;
    const RenderPlan plan = ensureRenderPlan(job, context(dir, 1, 20, reporter));
    const double aspect = 160.0 / 90.0;
    const Mat4 m = perspective(plan.camera.fov, aspect, 0.1, 1000) *
                   lookAt(plan.camera.position, plan.camera.target);
    double left = 1e300, right = -1e300;
    for (const Vec3 p : {Vec3{-3.5, 0, -3.5}, Vec3{3.5, 0, -3.5}, Vec3{-3.5, 1, 3.5},
                         Vec3{3.5, 1, 3.5}, Vec3{-3.5, 0, 3.5}, Vec3{3.5, 1, -3.5}}) {
        const Vec4 c = transformPoint(m, p);
        left = std::min(left, c.x / c.w);
        right = std::max(right, c.x / c.w);
    }
    EXPECT_GT(right - left, 2 * 0.6) << "the puddle's width, NDC (2 = the image)";
    EXPECT_GE(left, -0.91);
    EXPECT_LE(right, 0.91);
}

TEST(RenderStage, WritesAPngForEachRequestedFrameOnly) {
    const fs::path dir = freshDir("frames");
    writeCaches(dir, 1, 5);
    RecordingReporter reporter("render");
    runRenderStage(smallJob(), context(dir, 2, 4, reporter));
    EXPECT_FALSE(fs::exists(framePngPath(dir, 1)));
    for (int f = 2; f <= 4; ++f) {
        const Image image = readPng(framePngPath(dir, f));
        EXPECT_EQ(image.width, 64);
        EXPECT_EQ(image.height, 48);
    }
    EXPECT_FALSE(fs::exists(framePngPath(dir, 5)));
    EXPECT_EQ(reporter.steps, (std::vector<std::pair<long, long>>{{0, 3}, {1, 3}, {2, 3}, {3, 3}}));
    EXPECT_FALSE(fs::exists(dir / "contact_sheet.png"));
    EXPECT_FALSE(fs::exists(dir / "movie.mp4"));
}

TEST(RenderStage, AFrameThatCannotBeWrittenStopsTheStageNamingItAndKeepsTheOthers) {
    // Frames are written on a worker while the next one draws: the failure must still
    // surface, name its file, and leave the frames before it whole.
    const fs::path dir = freshDir("unwritable");
    writeCaches(dir, 1, 5);
    const fs::path blocked = framePngPath(dir, 3);
    fs::create_directories(blocked / "occupied");  // a non-empty folder where the PNG goes
    RecordingReporter reporter("render");
    try {
        runRenderStage(smallJob(), context(dir, 2, 5, reporter));
        FAIL() << "frame 3 cannot be written";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("frame.0003.png"), std::string::npos) << e.what();
    }
    EXPECT_EQ(readPng(framePngPath(dir, 2)).width, 64);
    EXPECT_TRUE(fs::is_directory(blocked));
    EXPECT_FALSE(fs::exists(framePngPath(dir, 5)));
}

TEST(RenderStage, FramesAreTheRenderersWithTheGivenCamera) {
    const fs::path dir = freshDir("camera");
    writeCaches(dir, 1, 2);
    RenderJob job = smallJob();
    job.camera.position = {0, 3, 14};
    job.camera.target = {0, 2, 0};
    RecordingReporter reporter("render");
    runRenderStage(job, context(dir, 1, 2, reporter));
    // The same frame drawn directly, with the stage's whole-animation extent.
    SceneExtent extent;
    extent.addFrame(frameGlobules(1));
    extent.addFrame(frameGlobules(2));
    FrameSetup setup;
    setup.render = job.render;
    setup.camera = {job.camera.position, job.camera.target, job.camera.fov};
    setup.lights = {LightSettings{}};
    setup.content = extent.box;
    setup.ramp = extent.height;
    Renderer renderer(64, 48, 4);
    EXPECT_EQ(readPng(framePngPath(dir, 2)).rgba,
              renderer.drawSpheres(frameGlobules(2), setup).rgba);
}

TEST(RenderStage, EmptyFrameRendersTheGround) {
    const fs::path dir = freshDir("empty");
    writeCaches(dir, 3, 3);
    RecordingReporter reporter("render");
    runRenderStage(smallJob(), context(dir, 3, 3, reporter));
    const Image image = readPng(framePngPath(dir, 3));
    // Ground below, background above: the image is not uniform.
    EXPECT_NE(image.pixel(32, 2)[0], image.pixel(32, 45)[0]);
}

TEST(RenderStage, MissingCacheNamesTheFileAndTheSimStage) {
    const fs::path dir = freshDir("missing");
    writeCaches(dir, 1, 2);
    RecordingReporter reporter("render");
    try {
        runRenderStage(smallJob(), context(dir, 1, 3, reporter));
        FAIL();
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("globules.0003.vdb"), std::string::npos) << message;
        EXPECT_NE(message.find("sim stage"), std::string::npos) << message;
    }
    EXPECT_FALSE(fs::exists(framePngPath(dir, 1)));  // checked before drawing anything
}

TEST(RenderStage, InvalidSettingsAreSceneErrors) {
    const fs::path dir = freshDir("invalid");
    writeCaches(dir, 1, 1);
    RecordingReporter reporter("render");
    RenderJob job = smallJob();
    job.render.samples = 3;
    EXPECT_THROW(runRenderStage(job, context(dir, 1, 1, reporter)), SceneError);
    job = smallJob();
    job.lights.resize(9);
    EXPECT_THROW(runRenderStage(job, context(dir, 1, 1, reporter)), SceneError);
    EXPECT_THROW(runRenderStage(smallJob(), context(dir, 2, 1, reporter)), SceneError);
}

TEST(RenderStage, ContactSheetTilesEvenlySpacedFrames) {
    const fs::path dir = freshDir("sheet");
    writeCaches(dir, 1, 5);
    RenderJob job = smallJob();
    job.render.contactSheet = 3;
    job.render.contactTileWidth = 32;
    RecordingReporter reporter("render");
    runRenderStage(job, context(dir, 1, 5, reporter));
    const Image sheet = readPng(dir / "contact_sheet.png");
    EXPECT_EQ(sheet.width, 8 + 3 * (32 + 8));
    EXPECT_EQ(sheet.height, 8 + 24 + 8);
}

TEST(RenderStage, SurfaceModeReadsTheMeshes) {
    const fs::path dir = freshDir("surface");
    TriangleMesh mesh;
    mesh.positions = {-2, 0.5, -2, 2, 0.5, -2, 0, 3, 0};
    mesh.triangles = {0, 2, 1};
    computeAreaWeightedNormals(mesh);
    writeMeshPly(meshPath(dir, 1, "ply"), mesh);
    writeMeshObj(meshPath(dir, 2, "obj"), mesh);
    RenderJob job = smallJob();
    job.render.mode = "surface";
    RecordingReporter reporter("render");
    runRenderStage(job, context(dir, 1, 1, reporter));
    EXPECT_TRUE(fs::exists(framePngPath(dir, 1)));
    job.meshFormat = "obj";
    runRenderStage(job, context(dir, 2, 2, reporter));
    EXPECT_TRUE(fs::exists(framePngPath(dir, 2)));
    try {
        runRenderStage(job, context(dir, 3, 3, reporter));
        FAIL();
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("surface.0003.obj"), std::string::npos) << message;
        EXPECT_NE(message.find("surface stage"), std::string::npos) << message;
    }
}

TEST(RenderStage, FluidModeDrawsTheCachesAsALiquid) {
    // mode = "fluid" reads the caches as spheres mode does, and draws them otherwise.
    const fs::path fluid = freshDir("fluid"), spheres = freshDir("fluid_spheres");
    writeCaches(fluid, 1, 1);
    writeCaches(spheres, 1, 1);
    RenderJob job = smallJob();
    RecordingReporter reporter("render");
    runRenderStage(job, context(spheres, 1, 1, reporter));
    job.render.mode = "fluid";
    runRenderStage(job, context(fluid, 1, 1, reporter));
    const Image a = readPng(framePngPath(fluid, 1)), b = readPng(framePngPath(spheres, 1));
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    int differ = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) differ += std::abs(a.rgba[i] - b.rgba[i]) > 12;
    EXPECT_GT(differ, 40) << "the liquid is not the opaque spheres";
}

TEST(RenderStage, SurfaceIsALiquidWhenItsMaterialsAreAndNoColourCodesAValue) {
    TriangleMesh mesh;
    mesh.positions = {-2, 0.5, -2, 2, 0.5, -2, 0, 3, 0};
    mesh.triangles = {0, 2, 1, 0, 1, 2};  // both sides: one faces the camera
    auto draw = [&](const std::string& name, const std::string& colorBy, bool liquid) {
        const fs::path dir = freshDir(name);
        writeMeshPly(meshPath(dir, 1, "ply"), mesh);
        RenderJob job = smallJob();
        job.render.mode = "surface";
        job.render.colorBy = colorBy;
        job.materialOptics = {LiquidOptics{liquid, {0.3, 0.09, 0.035}, 1.33}};
        RecordingReporter reporter("render");
        runRenderStage(job, context(dir, 1, 1, reporter));
        return readPng(framePngPath(dir, 1));
    };
    auto differing = [](const Image& a, const Image& b) {
        int n = 0;
        for (std::size_t i = 0; i < a.rgba.size(); ++i) n += std::abs(a.rgba[i] - b.rgba[i]) > 12;
        return n;
    };
    EXPECT_GT(differing(draw("liquid", "constant", true), draw("opaque", "constant", false)), 40);
    EXPECT_EQ(differing(draw("coded", "height", true), draw("coded_opaque", "height", false)), 0);
}

TEST(RenderStage, MovieNeedsFfmpegOnPath) {
    const fs::path dir = freshDir("movie");
    writeCaches(dir, 1, 3);
    RenderJob job = smallJob();
    job.render.movie = true;
    RecordingReporter reporter("render");
    const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
    ::setenv("PATH", dir.c_str(), 1);  // a PATH without ffmpeg
    runRenderStage(job, context(dir, 1, 3, reporter));
    ::setenv("PATH", path.c_str(), 1);
    EXPECT_FALSE(fs::exists(dir / "movie.mp4"));
    ASSERT_EQ(reporter.warnings.size(), 1u);
    EXPECT_NE(reporter.warnings[0].find("ffmpeg"), std::string::npos);
}

TEST(RenderStage, MovieIsAssembledWithFfmpeg) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "no ffmpeg";
    const fs::path dir = freshDir("movie_ffmpeg");
    writeCaches(dir, 1, 3);
    RenderJob job = smallJob();
    job.render.movie = true;
    RecordingReporter reporter("render");
    runRenderStage(job, context(dir, 1, 3, reporter));
    ASSERT_TRUE(fs::exists(dir / "movie.mp4"));
    EXPECT_GT(fs::file_size(dir / "movie.mp4"), 500u);
    EXPECT_TRUE(reporter.warnings.empty());
}

}  // namespace
}  // namespace globular
