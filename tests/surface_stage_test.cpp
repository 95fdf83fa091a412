// The surface stage end to end: caches in, VDB and mesh files out, refusals up front.
#include "surface_stage.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>
#include <vector>

#include "errors.h"
#include "frame_paths.h"
#include "globule_cache.h"
#include "mesh.h"
#include "mesh_topology.h"
#include "surface_estimate.h"
#include "surface_frame.h"
#include "recording_reporter.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// Frame f holds two globules f - 1 units apart along x.
Globules frameGlobules(int f) {
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 1.0f, 1, 0);
    g.add({double(f) - 1.0, 0, 0}, {0, 0, 0}, 1.0f, 1, 1);
    return g;
}

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_surface_stage_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeCaches(const fs::path& dir, int first, int last) {
    for (int f = first; f <= last; ++f) {
        writeGlobuleVdb(cacheVdbPath(dir, f), frameGlobules(f), {f, 0.1 * f});
    }
}

TEST(SurfaceStage, WritesVdbAndMeshForTheRequestedFramesOnly) {
    const fs::path dir = freshDir("frames");
    writeCaches(dir, 1, 6);
    SurfaceSettings s;
    s.voxelSize = 0.125;
    RecordingReporter reporter("surface");
    runSurfaceStage(s, {dir, 2, 5, &reporter});

    for (int f = 1; f <= 6; ++f) {
        const bool wanted = f >= 2 && f <= 5;
        EXPECT_EQ(fs::exists(surfaceVdbPath(dir, f)), wanted) << f;
        EXPECT_EQ(fs::exists(meshPath(dir, f, "ply")), wanted) << f;
    }
    // Frame 5 (globules 4 apart) is two spheres; frame 2 (1 apart) one blob. The files hold
    // exactly what surfacing the frame in memory gives.
    EXPECT_EQ(analyzeMesh(readMeshPly(meshPath(dir, 5, "ply"))).components, 2u);
    const TriangleMesh two = readMeshPly(meshPath(dir, 2, "ply"));
    EXPECT_EQ(analyzeMesh(two).components, 1u);
    const SurfaceFrame expected = surfaceGlobules(frameGlobules(2), s);
    EXPECT_EQ(two.positions, expected.mesh.positions);
    EXPECT_EQ(two.triangles, expected.mesh.triangles);

    ASSERT_EQ(reporter.steps.size(), 5u);
    EXPECT_EQ(reporter.steps.front(), std::make_pair(0L, 4L));
    EXPECT_EQ(reporter.steps.back(), std::make_pair(4L, 4L));
    for (std::size_t i = 1; i < reporter.steps.size(); ++i) {
        EXPECT_EQ(reporter.steps[i].first, long(i));
    }
    // No temporaries left behind.
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().find("globular-tmp"), std::string::npos) << entry.path();
    }
}

TEST(SurfaceStage, ObjFormatAndSerialFramesGiveTheSameMesh) {
    const fs::path dir = freshDir("obj");
    writeCaches(dir, 3, 3);
    SurfaceSettings s;
    s.voxelSize = 0.125;
    s.meshFormat = "obj";
    s.framesInFlight = 1;
    NullReporter quiet;
    runSurfaceStage(s, {dir, 3, 3, &quiet});
    EXPECT_TRUE(fs::exists(meshPath(dir, 3, "obj")));
    EXPECT_FALSE(fs::exists(meshPath(dir, 3, "ply")));
    EXPECT_GT(fs::file_size(meshPath(dir, 3, "obj")), 1000u);
}

TEST(SurfaceStage, MissingCacheNamesTheFileAndTheSimStage) {
    const fs::path dir = freshDir("missing");
    writeCaches(dir, 1, 2);
    NullReporter quiet;
    try {
        runSurfaceStage(SurfaceSettings{}, {dir, 1, 3, &quiet});
        FAIL() << "expected IoError";
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(cacheVdbPath(dir, 3).string()), std::string::npos) << message;
        EXPECT_NE(message.find("sim stage"), std::string::npos) << message;
    }
    // Refused before anything was written, even for the frames that exist.
    EXPECT_FALSE(fs::exists(surfaceVdbPath(dir, 1)));
}

TEST(SurfaceStage, RefusesUpFrontWhenTheEstimateExceedsMemory) {
    const fs::path dir = freshDir("memory");
    writeCaches(dir, 1, 2);
    SurfaceSettings s;
    s.voxelSize = 0.01;  // 200 voxels per globule radius
    // A limit between the two frames' estimates: frame 1 fits, frame 2 does not.
    const double gib = 1024.0 * 1024.0 * 1024.0;
    const double fits = double(estimateSurface(frameGlobules(1), s).bytes) / gib;
    const double needed = double(estimateSurface(frameGlobules(2), s).bytes) / gib;
    ASSERT_LT(fits, needed);
    s.memoryLimitGiB = 0.5 * (fits + needed);
    NullReporter quiet;
    try {
        runSurfaceStage(s, {dir, 1, 2, &quiet});
        FAIL() << "expected ResourceError";
    } catch (const ResourceError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("voxels"), std::string::npos) << message;
        EXPECT_NE(message.find("iB)"), std::string::npos) << message;  // the estimate
        EXPECT_NE(message.find("voxel_size"), std::string::npos) << message;
        EXPECT_NE(message.find("frame 2"), std::string::npos) << message;  // the larger one
    }
    EXPECT_FALSE(fs::exists(surfaceVdbPath(dir, 1)));
}

TEST(SurfaceStage, RejectsAnEmptyFrameRange) {
    NullReporter quiet;
    EXPECT_THROW(runSurfaceStage(SurfaceSettings{}, {freshDir("range"), 3, 2, &quiet}), SceneError);
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

TEST(SurfaceStage, WritesTheCollidersAtEachFramesPose) {
    const fs::path dir = freshDir("colliders");
    writeCaches(dir, 1, 3);
    ColliderSettings sphere;
    sphere.shape = "sphere";
    sphere.radius = 0.5;
    ColliderKey start, end;
    end.time = 0.08;  // frame 3 at 25 fps
    end.position = {4, 0, 0};
    sphere.keys = {start, end};
    NullReporter quiet;
    runSurfaceStage(SurfaceSettings{}, {dir, 1, 3, &quiet}, ColliderScene{{sphere}, {}, 2}, 25);
    for (int f = 1; f <= 3; ++f) {
        const TriangleMesh mesh = readMeshPly(collidersMeshPath(dir, f));
        ASSERT_GT(mesh.vertexCount(), 100u);
        float low = 1e9f, high = -1e9f;
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            low = std::min(low, mesh.positions[3 * v]);
            high = std::max(high, mesh.positions[3 * v]);
        }
        // The sphere (radius 0.5) moves its centre from x = 0 (frame 1) to x = 4 (frame 3).
        const double expected = poseAt(sphere.keys, double(f - 1) / 25).translation.x;
        EXPECT_NEAR(0.5 * (low + high), expected, 1e-5) << f;
        EXPECT_NEAR(high - low, 1.0, 1e-5) << f;
    }
    EXPECT_NEAR(poseAt(sphere.keys, 0.08).translation.x, 4, 1e-12);
}

}  // namespace
}  // namespace globular
