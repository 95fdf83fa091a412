// End-to-end tests of the `globular` executable: exit codes, messages on stderr and the
// files a sim run writes. Each test runs the built binary in its own temporary folder.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "errors.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "render_plan.h"
#include "transform.h"
#include "surface_frame.h"
#include "surface_grids.h"
#include "reporter.h"
#include "scene.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

// 30 globules in a helix, 5 frames: a run takes a fraction of a second.
const char* kSmallScene = R"([simulation]
frames = 5

[[emitter]]
type = "helix"
count = 30
)";

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

using Cli = CliTest;

TEST_F(Cli, VersionExitsZero) {
    const RunResult r = run("--version");
    EXPECT_EQ(r.status, 0) << r.err;
    const auto version = lines(r.out);
    ASSERT_EQ(version.size(), 2u) << r.out;
    EXPECT_EQ(version[0], "globular " GLOBULAR_TEST_VERSION);
    if (GLOBULAR_TEST_JEMALLOC) {
        // The build's own configuration: jemalloc on transparent huge pages.
        EXPECT_TRUE(version[1].starts_with("memory: jemalloc ")) << version[1];
        EXPECT_TRUE(version[1].ends_with(" (huge pages: always)")) << version[1];
    } else {
        EXPECT_EQ(version[1], "memory: the C library's malloc");
    }
}

// jemalloc is configured by the executable itself (core/memory_allocator.cpp), and the
// MALLOC_CONF variable still overrides it, as jemalloc documents.
TEST_F(Cli, MallocConfOverridesTheBuiltInAllocatorSettings) {
    if (!GLOBULAR_TEST_JEMALLOC) GTEST_SKIP() << "built without jemalloc (GLOBULAR_JEMALLOC=OFF)";
    const RunResult r = run("--version", "MALLOC_CONF=thp:never");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("(huge pages: never)"), std::string::npos) << r.out;
}

TEST_F(Cli, HelpExitsZero) {
    const RunResult r = run("--help");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("run"), std::string::npos) << r.out;
    const RunResult runHelp = run("run --help");
    EXPECT_EQ(runHelp.status, 0) << runHelp.err;
    for (const char* option :
         {"--out", "--stages", "--frames", "--threads", "--set", "--resume", "--quiet"}) {
        EXPECT_NE(runHelp.out.find(option), std::string::npos) << option;
    }
}

TEST_F(Cli, NoCommandIsBadUsage) {
    const RunResult r = run("");
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(r.err.empty());
}

TEST_F(Cli, SimStageWritesCachesStatsSceneAndState) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r =
        run("run " + quote(scene.string()) + " --stages sim --out " + quote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
    // Not a terminal: plain progress lines, the last one for frame 5.
    EXPECT_NE(r.err.find("sim: frame 5/5"), std::string::npos) << r.err;

    for (int frame = 1; frame <= 5; ++frame) {
        const fs::path cache = out / "cache" / ("globules.000" + std::to_string(frame) + ".vdb");
        EXPECT_TRUE(fs::is_regular_file(cache)) << cache;
        EXPECT_GT(fs::file_size(cache), 0u) << cache;
    }
    EXPECT_FALSE(fs::exists(out / "cache" / "globules.0006.vdb"));
    EXPECT_FALSE(fs::exists(out / "cache" / "globules.0000.vdb"));
    EXPECT_FALSE(fs::exists(out / "cache" / "globules.0001.ply")) << "ply = false by default";
    EXPECT_TRUE(fs::is_regular_file(out / "state.bin"));

    const std::vector<std::string> stats = lines(readFile(out / "stats.csv"));
    ASSERT_EQ(stats.size(), 6u) << "a header and 5 rows";
    EXPECT_TRUE(stats[0].starts_with("frame,time,count,")) << stats[0];
    const auto columns = std::count(stats[0].begin(), stats[0].end(), ',');
    for (int frame = 1; frame <= 5; ++frame) {
        const std::string& row = stats[std::size_t(frame)];
        EXPECT_TRUE(row.starts_with(std::to_string(frame) + ",")) << row;
        EXPECT_EQ(std::count(row.begin(), row.end(), ','), columns) << row;
    }
    EXPECT_TRUE(stats[1].starts_with("1,0,30,")) << stats[1];
    EXPECT_TRUE(stats[5].starts_with("5,0.16,30,")) << stats[5];

    // DIR/scene.toml is the resolved scene: exactly what the library writes for this
    // scene, and a valid scene itself that resolves to the same values.
    NullReporter quiet;
    const std::string written = readFile(out / "scene.toml");
    EXPECT_EQ(written, resolvedSceneToml(loadScene(scene, {}, quiet)));
    const Scene reread = parseScene(written, (out / "scene.toml").string(), {}, quiet);
    EXPECT_EQ(reread.simulation.frames, 5);
    ASSERT_EQ(reread.emitters.size(), 1u);
    EXPECT_EQ(reread.emitters[0].type, "helix");
    EXPECT_EQ(reread.emitters[0].count, 30);
    EXPECT_EQ(reread.material.preset, "liquid");
}

TEST_F(Cli, SetOverridesTheFrameCount) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r = run("run " + quote(scene.string()) + " --stages sim --quiet --out " +
                            quote(out.string()) + " --set simulation.frames=3");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "cache" / "globules.0003.vdb"));
    EXPECT_FALSE(fs::exists(out / "cache" / "globules.0004.vdb"));
    EXPECT_EQ(lines(readFile(out / "stats.csv")).size(), 4u);
    NullReporter quiet;
    EXPECT_EQ(loadScene(out / "scene.toml", {}, quiet).simulation.frames, 3);
}

TEST_F(Cli, AdaptiveRunSummarisesItsSteps) {
    const fs::path scene = writeScene("small.toml", kSmallScene);
    const std::string common = "run " + quote(scene.string()) + " --stages sim --set "
                               "simulation.integrator=semi_implicit_euler --set simulation.dt=0.01";
    const RunResult fixed = run(common + " --out " + quote((mDir / "fixed").string()));
    ASSERT_EQ(fixed.status, 0) << fixed.err;
    EXPECT_EQ(fixed.err.find("adaptive time steps"), std::string::npos) << fixed.err;

    const RunResult r = run(common + " --set simulation.adaptive=true --out " +
                            quote((mDir / "adaptive").string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string key = "sim: adaptive time steps: ";
    const std::size_t at = r.err.find(key);
    ASSERT_NE(at, std::string::npos) << r.err;
    long steps = 0;
    double mean = 0, shortest = 0, fixedSteps = 0;
    ASSERT_EQ(std::sscanf(r.err.c_str() + at + key.size(),
                          "%ld steps (mean %lf s, shortest %lf s); a fixed step as short as the "
                          "shortest would take %lf",
                          &steps, &mean, &shortest, &fixedSteps),
              4)
        << r.err;
    // Four frames of 1/25 s, each ending on its instant: at least one step each, none
    // longer than the dt cap, and the mean is the time over the steps.
    EXPECT_GE(steps, 4 * 4);  // 0.04 s frames in steps of at most 0.01 s
    EXPECT_LE(shortest, 0.01 + 1e-9);
    EXPECT_NEAR(mean, 0.16 / double(steps), 0.01 * mean);
    EXPECT_GE(fixedSteps, double(steps));
}

TEST_F(Cli, BadSceneExitsTwoAndWritesNothing) {
    const fs::path scene = writeScene("bad.toml", "[simulation]\ndt = -1\n"), out = mDir / "out";
    const RunResult r =
        run("run " + quote(scene.string()) + " --stages sim --out " + quote(out.string()));
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("error: " + scene.string() + ":2:6: [simulation] key 'dt' = -1"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out / "cache"));
    EXPECT_FALSE(fs::exists(out / "stats.csv"));
}

TEST_F(Cli, BadOverrideExitsTwo) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r = run("run " + quote(scene.string()) + " --stages sim --out " +
                            quote(out.string()) + " --set material.b1");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("error: --set material.b1: expected KEY=VALUE"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out / "cache"));
}

TEST_F(Cli, UnknownStageExitsTwo) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r =
        run("run " + quote(scene.string()) + " --stages sim,paint --out " + quote(out.string()));
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("error: --stages: unknown stage 'paint'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "cache"));
}

TEST_F(Cli, ReversedFrameRangeExitsTwo) {
    const fs::path scene = writeScene("ten.toml", "[simulation]\nframes = 10\n");
    const fs::path out = mDir / "out";
    const RunResult r = run("run " + quote(scene.string()) + " --stages sim --frames 9-3 --out " +
                            quote(out.string()));
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("error: --frames 9-3: must lie within 1-10"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "cache"));
}

TEST_F(Cli, MissingSceneFileIsBadUsageNamingThePath) {
    const fs::path missing = mDir / "no_such_scene.toml";
    const RunResult r = run("run " + quote(missing.string()) + " --stages sim --out " +
                            quote((mDir / "out").string()));
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
}

TEST_F(Cli, StatsIdenticalForAnyThreadCount) {
    // Enough globules that the neighbour search and forces split across threads.
    const fs::path scene = writeScene(
        "threads.toml", "[simulation]\nframes = 4\n\n[[emitter]]\ntype = \"helix\"\ncount = 600\n");
    std::string stats[2];
    for (int threads : {1, 2}) {
        const fs::path out = mDir / ("out" + std::to_string(threads));
        const RunResult r =
            run("run " + quote(scene.string()) + " --stages sim --quiet --threads " +
                std::to_string(threads) + " --out " + quote(out.string()));
        ASSERT_EQ(r.status, 0) << r.err;
        stats[threads - 1] = readFile(out / "stats.csv");
    }
    EXPECT_EQ(lines(stats[0]).size(), 5u);
    EXPECT_EQ(stats[0], stats[1]);
}

TEST_F(Cli, QuietPrintsNothingOnSuccess) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r =
        run("run " + quote(scene.string()) + " --stages sim --quiet --out " + quote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(fs::exists(out / "cache" / "globules.0005.vdb"));
}

TEST_F(Cli, QuietStillPrintsWarnings) {
    const fs::path scene = writeScene("small.toml", kSmallScene), out = mDir / "out";
    const RunResult r = run("run " + quote(scene.string()) + " --stages sim --quiet --out " +
                            quote(out.string()) + " --set material.b1=3.5");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err,
              "warning: --set material.b1=3.5: [material] key 'b1': b1 = 3.500000 is outside "
              "the paper's stable range [1, 3]\n");
}

TEST_F(CliTest, TemperatureTravelsThroughEveryStage) {
    // A warm blob dropped on a hot plate: the caches carry temperatures, the surface file
    // a temperature grid, the mesh per-vertex temperature and material, and the frames
    // are coloured by temperature.
    writeScene("hot.toml",
               "[simulation]\nframes = 4\n[thermal]\nenabled = true\n"
               "ground_temperature = 200\nground_transfer = 20\n"
               "[[material]]\nname = \"wax\"\nt_solid = 40\nt_liquid = 60\n"
               "[material.solid]\npreset = \"solid\"\n[[material]]\nname = \"oil\"\n"
               "[[emitter]]\ncount = 40\ntemperature = 30\ncenter = [0.0, 0.0, 0.0]\n"
               "[[emitter]]\ncount = 40\nmaterial = \"oil\"\ncenter = [1.5, 0.0, 0.0]\n"
               "[render]\nwidth = 160\nheight = 90\ncolor_by = \"temperature\"\n");
    const RunResult all = run("run hot.toml --out out");
    ASSERT_EQ(all.status, 0) << all.err;
    const Globules last = readGlobuleVdb(mDir / "out/cache/globules.0004.vdb");
    ASSERT_EQ(last.temperature.size(), 80u);
    EXPECT_GT(*std::max_element(last.temperature.begin(), last.temperature.end()), 40.0f);
    EXPECT_TRUE(readSurfaceVdb(mDir / "out/surface/surface.0004.vdb").temperature);
    const TriangleMesh mesh = readMeshPly(mDir / "out/mesh/surface.0004.ply");
    EXPECT_TRUE(mesh.attribute("temperature") && mesh.attribute("material"));
    EXPECT_TRUE(std::filesystem::exists(mDir / "out/frames/frame.0004.png"));
    // The resolved scene runs again as it is.
    const RunResult again = run("run out/scene.toml --out again --stages sim");
    EXPECT_EQ(again.status, 0) << again.err;
}

/// How much of a 16:9 image the globule centres of frame @p f span, seen by the camera
/// the run planned: the larger of the fractions of its width and of its height.
double subjectShare(const fs::path& out, int f) {
    const RenderPlan plan = readRenderPlan(renderPlanPath(out));
    const Globules g = readGlobuleVdb(cacheVdbPath(out, f));
    const Mat4 m = perspective(plan.camera.fov, 16.0 / 9.0, 0.01, 1e4) *
                   lookAt(plan.camera.position, plan.camera.target);
    double left = 1e300, right = -1e300, bottom = 1e300, top = -1e300;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const Vec4 c = transformPoint(m, g.position(i));
        left = std::min(left, c.x / c.w);
        right = std::max(right, c.x / c.w);
        bottom = std::min(bottom, c.y / c.w);
        top = std::max(top, c.y / c.w);
    }
    return std::max(right - left, top - bottom) / 2;
}

TEST_F(CliTest, AutomaticCameraKeepsTheShippedScenesSubjectLarge) {
    // The default scene's pour into the glass and the paper's helix, the first frames of
    // each: the automatic camera (the render plan's) shows them large, never a speck.
    const std::string paper = std::string(GLOBULAR_SOURCE_DIR) + "/scenes/paper/";
    const std::string few = " --stages sim,plan --set simulation.frames=12 --set render.mode=spheres";
    // The pour reaches the glass's floor by frame 40 (1.6 s).
    ASSERT_EQ(run("run --out default --stages sim,plan --set simulation.frames=40 "
                  "--set render.mode=spheres").status, 0);
    EXPECT_GT(subjectShare(mDir / "default", 40), 0.4);
    ASSERT_EQ(run("run " + quote(paper + "liquid.toml") + " --out helix" + few).status, 0);
    EXPECT_GT(subjectShare(mDir / "helix", 12), 0.7);
    ASSERT_EQ(run("run " + quote(paper + "powder.toml") + " --out powder" + few).status, 0);
    EXPECT_GT(subjectShare(mDir / "powder", 12), 0.5);
}

TEST_F(CliTest, GlBackendIsChosenAtRunTimeAndAMissingEglIsNamed) {
    writeScene("drop.toml",
               "[simulation]\nframes = 2\n[[emitter]]\ncount = 20\n"
               "[render]\nwidth = 96\nheight = 54\n");
    ASSERT_EQ(run("run drop.toml --out osmesa --stages sim,render").status, 0);
    // EGL surfaceless draws the same frame as OSMesa (both llvmpipe here).
    const RunResult egl = run("run drop.toml --out egl --stages sim,render --set render.gl=egl");
    ASSERT_EQ(egl.status, 0) << egl.err;
    EXPECT_EQ(readFile(mDir / "egl/frames/frame.0002.png"),
              readFile(mDir / "osmesa/frames/frame.0002.png"));
    // Without libEGL the run fails, naming the back end and the library.
    const RunResult missing = run("run drop.toml --out osmesa --stages render",
                                  "GLOBULAR_GL=egl GLOBULAR_EGL_LIBRARY=libglobular_no_egl.so.1");
    EXPECT_NE(missing.status, 0);
    EXPECT_NE(missing.err.find("OpenGL back end \"egl\""), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("libglobular_no_egl.so.1 cannot be loaded"), std::string::npos)
        << missing.err;
    // A value GLOBULAR_GL does not know is an error naming it.
    const RunResult bad = run("run drop.toml --out osmesa --stages render", "GLOBULAR_GL=vulkan");
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.err.find("GLOBULAR_GL"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

TEST_F(CliTest, ADynamicColliderTravelsThroughEveryStage) {
    // A ball fired into globules of two materials; the sim stage writes the ball's poses,
    // the surface stage places its mesh from them, the render stage draws it; then the
    // surface stage alone, without the poses, is an error naming the file.
    writeScene("shot.toml",
               "[simulation]\nframes = 4\n"
               "[[material]]\nname = \"a\"\n[[material]]\nname = \"b\"\npreset = \"powder\"\n"
               "[[emitter]]\ncount = 30\n[[emitter]]\ncount = 30\nmaterial = \"b\"\n"
               "center = [3.0, 5.0, 0.0]\n"
               "[[collider]]\nname = \"ball\"\nshape = \"sphere\"\nradius = 0.8\n"
               "center = [-4.0, 6.0, 0.0]\ndynamic = true\nmass = 20.0\n"
               "velocity = [30.0, 0.0, 0.0]\n"
               "[render]\nwidth = 160\nheight = 90\ncolor_by = \"material\"\n");
    const RunResult all = run("run shot.toml --out out");
    ASSERT_EQ(all.status, 0) << all.err;
    for (const char* file : {"out/cache/colliders.0004.toml", "out/mesh/colliders.0004.ply",
                             "out/frames/frame.0004.png"}) {
        EXPECT_TRUE(std::filesystem::exists(mDir / file)) << file;
    }
    // The mesh of frame 4 is where the poses file put the ball: moved on in x.
    const TriangleMesh ball = readMeshPly(mDir / "out/mesh/colliders.0004.ply");
    float low = 1e9f;
    for (std::size_t v = 0; v < ball.vertexCount(); ++v) low = std::min(low, ball.positions[3 * v]);
    EXPECT_GT(low, -4.0f - 0.8f + 1.0f);
    std::filesystem::remove(mDir / "out/cache/colliders.0002.toml");
    const RunResult surface = run("run shot.toml --out out --stages surface");
    EXPECT_EQ(surface.status, 1);
    EXPECT_NE(surface.err.find("colliders.0002.toml"), std::string::npos) << surface.err;
    EXPECT_NE(surface.err.find("'ball' is dynamic"), std::string::npos) << surface.err;
}

}  // namespace
}  // namespace globular
