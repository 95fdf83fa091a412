// Helper of bench/surface_vs_vdb_tool.sh: writes the benchmark particles for vdb_tool and
// times globular's pipeline on the same particles.
//   globular_surface_compare points COUNT FILE.ply   x y z of bench_puddle(COUNT)
//   globular_surface_compare time COUNT VOXEL OUT.ply [THREADS [rebuild]]
//       splat + level set + mesh + PLY write, the steps vdb_tool's
//       -points2ls -ls2mesh -write do; prints one line per step (wall seconds), the
//       process CPU seconds ("cpu") and "total SECONDS" (wall). With "rebuild", the level
//       set comes from levelSetRebuild (the old path) instead of fieldToLevelSet.
//   globular_surface_compare estimate COUNT VOXEL
//       surfaces the whole frame and prints the stage's memory estimate beside it.
//   globular_surface_compare frame COUNT VOXEL DIR [THREADS]
//       the surface stage's whole frame (surfaceGlobules: with the velocity, the fog, the
//       mesh's vertex attributes), then its VDB and PLY files written into DIR: wall
//       seconds of each and the files' bytes ("total" = frame + both writes).
//   globular_surface_compare steps COUNT VOXEL [THREADS]
//       the frame's steps one after the other (surfaceGlobules runs some side by side):
//       wall seconds of each, to see where a frame's time goes.
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "surface_bench_scene.h"
#include "surface_estimate.h"
#include "surface_frame.h"
#include "surface_grids.h"
#include "vertex_attributes.h"

using namespace globular;

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

int writePoints(std::size_t count, const std::string& path) {
    const Globules g = benchPuddle(count);
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << g.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    for (std::size_t i = 0; i < g.size(); ++i) {
        const float p[3] = {g.px[i], g.py[i], g.pz[i]};
        out.write(reinterpret_cast<const char*>(p), sizeof p);
    }
    return out ? 0 : 1;
}

int timePipeline(std::size_t count, double voxelSize, const std::string& meshPath, bool rebuild) {
    const std::clock_t cpuStart = std::clock();
    const Globules g = benchPuddle(count);
    SurfaceSettings s;
    s.voxelSize = voxelSize;
    openvdb::initialize();

    const auto start = std::chrono::steady_clock::now();
    auto t = start;
    const auto field = splatMetaballs(g, s.metaballKernel(), s.influence, voxelSize, s.isoValue);
    const double splat = seconds(t);
    t = std::chrono::steady_clock::now();
    const auto levelSet = rebuild ? rebuildLevelSet(*field, s.isoValue, s.bandWidth)
                                  : fieldToLevelSet(*field, s.isoValue, s.bandWidth);
    const double levelSetTime = seconds(t);
    t = std::chrono::steady_clock::now();
    const TriangleMesh mesh = meshLevelSet(*levelSet, s.adaptivity);
    const double meshing = seconds(t);
    t = std::chrono::steady_clock::now();
    writeMeshPly(meshPath, mesh);
    const double write = seconds(t);
    const double total = seconds(start);
    const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
    std::printf(
        "splat %.3f\nlevelset %.3f\nmesh %.3f\nwrite %.3f\ntriangles %zu\ncpu %.3f\n"
        "total %.3f\n",
        splat, levelSetTime, meshing, write, mesh.triangleCount(), cpu, total);
    return 0;
}

/// The whole frame (with fog) and the stage's memory estimate for it, to check the
/// estimate against the peak memory (run under /usr/bin/time -f %M).
int estimateFrame(std::size_t count, double voxelSize) {
    const Globules g = benchPuddle(count);
    SurfaceSettings s;
    s.voxelSize = voxelSize;
    const SurfaceEstimate e = estimateSurface(g, s);
    const auto start = std::chrono::steady_clock::now();
    const SurfaceFrame frame = surfaceGlobules(g, s);
    std::printf("estimate_bytes %llu\nestimate_leaves %zu\nfield_leaves %zu\nframe %.3f\n",
                static_cast<unsigned long long>(e.bytes), e.fieldLeaves, frame.fieldLeaves,
                seconds(start));
    return 0;
}

/// surfaceGlobules, writeSurfaceVdb and writeSurfaceMesh as the stage calls them.
int timeFrame(std::size_t count, double voxelSize, const std::filesystem::path& dir) {
    const Globules g = benchPuddle(count);
    SurfaceSettings s;
    s.voxelSize = voxelSize;
    openvdb::initialize();
    std::filesystem::create_directories(dir);
    const auto start = std::chrono::steady_clock::now();
    const SurfaceFrame frame = surfaceGlobules(g, s);
    const double surfacing = seconds(start);
    auto t = std::chrono::steady_clock::now();
    writeSurfaceVdb(dir / "surface.vdb", frame);
    const double vdb = seconds(t);
    t = std::chrono::steady_clock::now();
    writeSurfaceMesh(dir / "surface.ply", frame.mesh, "ply");
    const double ply = seconds(t);
    const double total = seconds(start);
    std::printf(
        "frame %.3f\nvdb_write %.3f\nply_write %.3f\nvdb_bytes %ju\nply_bytes %ju\n"
        "vel_voxels %ju\ntriangles %zu\ntotal %.3f\n",
        surfacing, vdb, ply, std::uintmax_t(std::filesystem::file_size(dir / "surface.vdb")),
        std::uintmax_t(std::filesystem::file_size(dir / "surface.ply")),
        std::uintmax_t(frame.grids->vel ? frame.grids->vel->activeVoxelCount() : 0),
        frame.mesh.triangleCount(), total);
    return 0;
}

/// The steps of surfaceGlobules (no filters, droplets or colliders) one at a time.
int timeSteps(std::size_t count, double voxelSize) {
    const Globules g = benchPuddle(count);
    SurfaceSettings s;
    s.voxelSize = voxelSize;
    openvdb::initialize();
    const MetaballKernel kernel = s.metaballKernel();
    const auto start = std::chrono::steady_clock::now();
    auto t = start;
    const auto lap = [&](const char* name) {
        std::printf("%s %.3f\n", name, seconds(t));
        t = std::chrono::steady_clock::now();
    };
    const GlobuleBins bins(g, voxelSize, s.influence);
    lap("bins");
    MeanSplat splat = splatMetaballsWithMean(g, bins, {&g.vx, &g.vy, &g.vz}, kernel, voxelSize,
                                             s.isoValue);
    lap("splat_with_means");
    const auto levelSet = fieldToLevelSet(*splat.field, s.isoValue, s.bandWidth);
    lap("levelset");
    const auto fog = levelSetToFog(*levelSet);
    lap("fog");
    const auto vel = velocityInBand(*splat.means[0], *splat.means[1], *splat.means[2], *levelSet,
                                    2.0 * voxelSize);
    lap("vel");
    TriangleMesh mesh = meshLevelSet(*levelSet, s.adaptivity);
    lap("mesh");
    carryGlobuleAttributes(mesh, g, bins, kernel, voxelSize, attributesOf(g));
    lap("attributes");
    std::printf("field_leaves %zu\nband_leaves %zu\nvel_voxels %ju\ntotal %.3f\n",
                std::size_t(splat.field->tree().leafCount()),
                std::size_t(levelSet->tree().leafCount()),
                std::uintmax_t(vel->activeVoxelCount()), seconds(start));
    return 0;
}

int inArena(int argc, char** argv, int threadArg, const std::function<int()>& body) {
    const int threads = argc > threadArg && std::stoi(argv[threadArg]) > 0
                            ? std::stoi(argv[threadArg])
                            : tbb::info::default_concurrency();
    int rc = 0;
    tbb::task_arena(threads).execute([&] { rc = body(); });
    return rc;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "points" && argc == 4) return writePoints(std::stoul(argv[2]), argv[3]);
    if (mode == "estimate" && argc == 4)
        return estimateFrame(std::stoul(argv[2]), std::stod(argv[3]));
    if (mode == "frame" && (argc == 5 || argc == 6)) {
        return inArena(argc, argv, 5, [&] {
            return timeFrame(std::stoul(argv[2]), std::stod(argv[3]), argv[4]);
        });
    }
    if (mode == "steps" && (argc == 4 || argc == 5)) {
        return inArena(argc, argv, 4,
                       [&] { return timeSteps(std::stoul(argv[2]), std::stod(argv[3])); });
    }
    if (mode == "time" && argc >= 5 && argc <= 7 && (argc < 7 || std::string(argv[6]) == "rebuild")) {
        // An optional thread count (0 = all), to compare with vdb_tool on equal terms.
        const int threads = argc >= 6 && std::stoi(argv[5]) > 0 ? std::stoi(argv[5])
                                                                : tbb::info::default_concurrency();
        const bool rebuild = argc == 7;
        int rc = 0;
        tbb::task_arena(threads).execute([&] {
            rc = timePipeline(std::stoul(argv[2]), std::stod(argv[3]), argv[4], rebuild);
        });
        return rc;
    }
    std::fprintf(stderr,
                 "usage: %s points COUNT FILE.ply\n       %s time COUNT VOXEL OUT.ply [THREADS [rebuild]]\n"
                 "       %s frame COUNT VOXEL DIR [THREADS]\n       %s steps COUNT VOXEL [THREADS]\n",
                 argv[0], argv[0], argv[0], argv[0]);
    return 2;
}
