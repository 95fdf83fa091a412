// The render plan: what spans the animation is measured once and stored, so a render split
// into chunks draws exactly the pixels of one run.
#include "render_plan.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "box_mesh.h"
#include "errors.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "mesh.h"
#include "recording_reporter.h"
#include "render_stage.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 20;

/// Frame f of a small shot: a few globules falling and spreading, faster each frame, so
/// the automatic camera, the speed ramp and the bounds all grow over the animation.
Globules frameGlobules(int f) {
    Globules g;
    for (int i = 0; i < 6; ++i) {
        const double spread = 0.2 * f * (i - 2.5);
        g.add({spread, 8.0 - 0.3 * f + 0.5 * i, 0.1 * i * f}, {spread, -0.5 * f, 0}, 0.6f, 1,
              uint32_t(i));
    }
    return g;
}

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_render_plan_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (int f = 1; f <= kFrames; ++f) {
        writeGlobuleVdb(cacheVdbPath(dir, f), frameGlobules(f), {f, 0.04 * f});
    }
    return dir;
}

RenderJob splitJob() {
    RenderJob job;
    job.render.width = 48;
    job.render.height = 32;
    job.render.samples = 1;
    job.render.shadowMapSize = 256;
    job.render.colorBy = "speed";
    job.render.contactSheet = 4;
    job.render.contactTileWidth = 24;
    job.animationFrames = kFrames;
    return job;
}

void render(const RenderJob& job, const fs::path& dir, int first, int last,
            RecordingReporter& reporter) {
    runRenderStage(job, StageContext{dir, first, last, &reporter});
}

std::string bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

bool saidSomething(const RecordingReporter& r, const std::string& part) {
    for (const std::string& m : r.infos) {
        if (m.find(part) != std::string::npos) return true;
    }
    return false;
}

TEST(RenderPlan, SplitRenderIsByteIdenticalToOneRun) {
    const fs::path one = freshDir("one"), split = freshDir("split");
    RecordingReporter reporter("render");
    render(splitJob(), one, 1, kFrames, reporter);
    render(splitJob(), split, 1, 10, reporter);
    EXPECT_FALSE(fs::exists(split / "contact_sheet.png"));  // frames 11-20 not drawn yet
    render(splitJob(), split, 11, kFrames, reporter);
    for (int f = 1; f <= kFrames; ++f) {
        ASSERT_TRUE(fs::exists(framePngPath(split, f)));
        EXPECT_EQ(bytes(framePngPath(one, f)), bytes(framePngPath(split, f))) << "frame " << f;
    }
    ASSERT_TRUE(fs::exists(split / "contact_sheet.png"));
    EXPECT_EQ(bytes(one / "contact_sheet.png"), bytes(split / "contact_sheet.png"));
    const RenderPlan plan = readRenderPlan(renderPlanPath(split));
    EXPECT_EQ(plan.sheetFrames, (std::vector<int>{1, 7, 14, 20}));
    EXPECT_EQ(plan.firstFrame, 1);
    EXPECT_EQ(plan.lastFrame, kFrames);
    EXPECT_TRUE(plan.automaticCamera);
}

TEST(RenderPlan, SplitLiquidRenderIsByteIdenticalToOneRun) {
    // The surface drawn as a liquid under the shadowing key light: a chunk's first frame
    // is its renderer's first, when the liquid's passes create their textures (which once
    // unbound the shadow map, and the first frame of each chunk lost the key light).
    RenderJob job = splitJob();
    job.render.mode = "surface";
    job.render.colorBy = "constant";
    job.materialOptics = {LiquidOptics{}};
    // The camera fixed, and the key light mirrored about the slab's top at its centre:
    // its glint lies there, in the frame's middle (as in LiquidRender's test of it).
    const Vec3 eye{0, 5, 8}, top{0, 2, 0};
    job.camera.position = eye;
    job.camera.target = top;
    const Vec3 view = normalized(top - eye);
    LightSettings key;
    key.direction = -1.0 * Vec3{view.x, -view.y, view.z};
    job.lights = {key};
    const fs::path one = freshDir("liquid_one"), split = freshDir("liquid_split");
    for (const fs::path& dir : {one, split}) {
        for (int f = 1; f <= kFrames; ++f) {
            const double spread = 2 + 0.05 * f;  // a slab, its top at 2, spreading
            writeMeshPly(meshPath(dir, f, "ply"),
                         BoxMesh({-spread, 0, -spread}, {spread, 2, spread}).mesh());
        }
    }
    RecordingReporter reporter("render");
    render(job, one, 1, kFrames, reporter);
    render(job, split, 1, 10, reporter);
    render(job, split, 11, kFrames, reporter);
    for (int f = 1; f <= kFrames; ++f) {
        EXPECT_EQ(bytes(framePngPath(one, f)), bytes(framePngPath(split, f))) << "frame " << f;
    }
}

TEST(RenderPlan, ARangeMeasuredAloneFramesDifferently) {
    // What the plan prevents, so the test above can fail: the first chunk measured by
    // itself zooms in on frames 1-10 only.
    const fs::path one = freshDir("alone_one"), alone = freshDir("alone");
    RecordingReporter reporter("render");
    render(splitJob(), one, 1, kFrames, reporter);
    RenderJob job = splitJob();
    job.animationFrames = 0;  // the range is the whole animation
    render(job, alone, 1, 10, reporter);
    EXPECT_NE(bytes(framePngPath(one, 5)), bytes(framePngPath(alone, 5)));
    EXPECT_NE(readRenderPlan(renderPlanPath(one)).camera.position,
              readRenderPlan(renderPlanPath(alone)).camera.position);
}

TEST(RenderPlan, SpansTheCachedFramesWhenTheSimulationStoppedEarly) {
    // `run --frames 1-8` simulates to frame 8 only: the plan spans what is cached, and is
    // measured again once the simulation has run to the end.
    const fs::path dir = freshDir("early");
    for (int f = 9; f <= kFrames; ++f) fs::remove(cacheVdbPath(dir, f));
    RecordingReporter reporter("render");
    render(splitJob(), dir, 1, 8, reporter);
    EXPECT_EQ(readRenderPlan(renderPlanPath(dir)).lastFrame, 8);
    for (int f = 9; f <= kFrames; ++f) {
        writeGlobuleVdb(cacheVdbPath(dir, f), frameGlobules(f), {f, 0.04 * f});
    }
    render(splitJob(), dir, 9, 9, reporter);
    EXPECT_EQ(readRenderPlan(renderPlanPath(dir)).lastFrame, kFrames);
}

TEST(RenderPlan, TomlRoundTripsEveryDoubleExactly) {
    RenderPlan plan;
    plan.firstFrame = 1;
    plan.lastFrame = 240;
    plan.fingerprint = "0123456789abcdef";
    plan.mode = "spheres";
    plan.colorBy = "speed";
    plan.width = 1920;
    plan.height = 1080;
    plan.camera = {{0.1, 1.0 / 3.0, -2e-300}, {5e300, 2, 0}, 40};
    plan.automaticCamera = true;
    plan.content.add(Vec3{-1.0 / 7.0, 0, 3});
    plan.content.add(Vec3{1, 2.5, 4});
    plan.ramp.add(0.1, 17.0 / 3.0);
    plan.sheetFrames = {1, 120, 240};
    for (int f = 1; f <= 240; ++f) {
        plan.path.push_back({{f / 7.0, 1e-9 * f, -f * 1e10}, {3.0 / f, 0, 1}, 40});
    }
    const RenderPlan back = parseRenderPlan(renderPlanToml(plan), "test");
    ASSERT_EQ(back.path.size(), plan.path.size());
    for (std::size_t i = 0; i < plan.path.size(); ++i) {
        EXPECT_EQ(back.path[i].position, plan.path[i].position) << i;
        EXPECT_EQ(back.path[i].target, plan.path[i].target) << i;
    }
    EXPECT_EQ(back.cameraFor(7).target, plan.path[6].target);
    EXPECT_EQ(back.cameraFor(241).target, plan.camera.target);  // outside: the still camera
    EXPECT_EQ(back.camera.position, plan.camera.position);
    EXPECT_EQ(back.camera.target, plan.camera.target);
    EXPECT_EQ(back.camera.fov, 40.0);
    EXPECT_EQ(back.content.min, plan.content.min);
    EXPECT_EQ(back.content.max, plan.content.max);
    EXPECT_FALSE(back.content.empty);
    EXPECT_EQ(back.ramp.min, 0.1);
    EXPECT_EQ(back.ramp.max, 17.0 / 3.0);
    EXPECT_EQ(back.sheetFrames, plan.sheetFrames);
    EXPECT_EQ(back.fingerprint, plan.fingerprint);
    EXPECT_EQ(renderPlanToml(back), renderPlanToml(plan));
    // The keys the Blender add-on reads.
    const std::string text = renderPlanToml(plan);
    EXPECT_NE(text.find("[camera]\nposition = [0.1, 0.3333333333333333, -2e-300]"),
              std::string::npos)
        << text;
}

TEST(RenderPlan, DamagedPlanNamesFileAndKey) {
    try {
        parseRenderPlan("format = 2\nfingerprint = \"x\"\nfirst_frame = 1\n", "DIR/render_plan.toml");
        FAIL();
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("DIR/render_plan.toml"), std::string::npos) << message;
        EXPECT_NE(message.find("last_frame"), std::string::npos) << message;
    }
    EXPECT_THROW(parseRenderPlan("[camera\n", "p"), IoError);
    // A following camera's path must hold one point per frame, each finite.
    RenderPlan plan;
    plan.lastFrame = 3;
    plan.path.assign(3, ViewCamera{{1, 2, 3}, {4, 5, 6}, 40});
    const std::string text = renderPlanToml(plan);
    const std::string point = "  [4.0, 5.0, 6.0],\n";
    ASSERT_NE(text.find(point), std::string::npos) << text;
    std::string missing = text, infinite = text;
    missing.erase(missing.find(point), point.size());
    infinite.replace(infinite.find(point), point.size(), "  [4.0, inf, 6.0],\n");
    for (const std::string& damaged : {missing, infinite}) {
        try {
            parseRenderPlan(damaged, "DIR/render_plan.toml");
            ADD_FAILURE() << damaged;
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("camera.path_targets"), std::string::npos)
                << e.what();
        }
    }
}


TEST(RenderPlan, KeptWhileCurrentMeasuredAgainWhenStale) {
    const fs::path dir = freshDir("stale");
    RecordingReporter first("render");
    render(splitJob(), dir, 1, 2, first);
    EXPECT_TRUE(saidSomething(first, "measuring frames 1-20"));
    RecordingReporter again("render");
    render(splitJob(), dir, 3, 4, again);
    EXPECT_TRUE(saidSomething(again, "using"));
    EXPECT_FALSE(saidSomething(again, "measuring"));
    // A cache rewritten (a simulation run again): the plan is measured again.
    Globules moved = frameGlobules(20);
    moved.px[0] += 50;
    writeGlobuleVdb(cacheVdbPath(dir, 20), moved, {20, 0.8});
    RecordingReporter stale("render");
    render(splitJob(), dir, 3, 4, stale);
    EXPECT_TRUE(saidSomething(stale, "other settings or caches"));
    // Other settings: measured again too.
    RenderJob job = splitJob();
    job.render.colorBy = "height";
    RecordingReporter other("render");
    render(job, dir, 3, 3, other);
    EXPECT_TRUE(saidSomething(other, "other settings or caches"));
    EXPECT_EQ(readRenderPlan(renderPlanPath(dir)).colorBy, "height");
    // A damaged plan: a warning, and measured again.
    { std::ofstream(renderPlanPath(dir)) << "garbage ["; }
    RecordingReporter damaged("render");
    render(job, dir, 3, 3, damaged);
    ASSERT_EQ(damaged.warnings.size(), 1u);
    EXPECT_NE(damaged.warnings[0].find("render_plan.toml"), std::string::npos);
    EXPECT_NO_THROW(readRenderPlan(renderPlanPath(dir)));
}

TEST(RenderPlan, FinishNamesTheFramesNotYetDrawn) {
    const fs::path dir = freshDir("finish");
    RecordingReporter reporter("render");
    render(splitJob(), dir, 1, 10, reporter);
    try {
        finishRenderStage(splitJob(), StageContext{dir, 1, kFrames, &reporter});
        FAIL();
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("frame(s) 14, 20"), std::string::npos) << message;
    }
    render(splitJob(), dir, 11, kFrames, reporter);
    fs::remove(dir / "contact_sheet.png");
    finishRenderStage(splitJob(), StageContext{dir, 1, kFrames, &reporter});
    EXPECT_TRUE(fs::exists(dir / "contact_sheet.png"));
}

}  // namespace
}  // namespace globular
