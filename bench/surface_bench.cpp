// Surfacing benchmarks: each step and the whole frame for 1e4, 1e5 and 1e6 globules
// (bench_puddle), and frames side by side against one frame at a time. Not part of ctest;
// the 1e6 cases take seconds each, so run them by hand:
//   build/bench/surface_bench --benchmark_filter=/1000000
// On a shared machine add --benchmark_repetitions=3 and read the "_min" rows.
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "collider_cut.h"
#include "frame_paths.h"
#include "surface_bench_scene.h"
#include "surface_frame.h"
#include "surface_grids.h"

namespace globular {
namespace {

/// The fastest repetition: on a shared machine, the run least slowed by other work.
double fastest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void sizes(benchmark::internal::Benchmark* b) {
    b->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
    b->ComputeStatistics("min", fastest);
}

const SurfaceSettings kSettings{};  // defaults: voxel = radius / 4 = 0.25

void BM_Splat(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const double h = resolveVoxelSize(kSettings, g);
    for (auto _ : state) {
        auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence, h,
                                    kSettings.isoValue);
        state.counters["leaves"] = double(field->tree().leafCount());
    }
}
BENCHMARK(BM_Splat)->Apply(sizes);

// The surface stage's own splat: the field and the velocity's three means beside it.
void BM_SplatWithVelocity(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const double h = resolveVoxelSize(kSettings, g);
    for (auto _ : state) {
        auto splat = splatMetaballsWithMean(g, {&g.vx, &g.vy, &g.vz}, kSettings.metaballKernel(),
                                            kSettings.influence, h, kSettings.isoValue);
        state.counters["leaves"] = double(splat.field->tree().leafCount());
    }
}
BENCHMARK(BM_SplatWithVelocity)->Apply(sizes);

void BM_LevelSet(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence,
                                      resolveVoxelSize(kSettings, g));
    for (auto _ : state) {
        benchmark::DoNotOptimize(fieldToLevelSet(*field, kSettings.isoValue, kSettings.bandWidth));
    }
}
BENCHMARK(BM_LevelSet)->Apply(sizes);

/// The levelSetRebuild path fieldToLevelSet replaced, for comparison.
void BM_LevelSetRebuild(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence,
                                      resolveVoxelSize(kSettings, g));
    for (auto _ : state) {
        benchmark::DoNotOptimize(rebuildLevelSet(*field, kSettings.isoValue, kSettings.bandWidth));
    }
}
BENCHMARK(BM_LevelSetRebuild)->Apply(sizes);

void meshAtAdaptivity(benchmark::State& state, double adaptivity) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence,
                                      resolveVoxelSize(kSettings, g));
    const auto levelSet = fieldToLevelSet(*field, kSettings.isoValue, kSettings.bandWidth);
    for (auto _ : state) {
        const TriangleMesh mesh = meshLevelSet(*levelSet, adaptivity);
        state.counters["triangles"] = double(mesh.triangleCount());
    }
}

void BM_Mesh(benchmark::State& state) { meshAtAdaptivity(state, kSettings.adaptivity); }
BENCHMARK(BM_Mesh)->Apply(sizes);

/// The mesh with the adaptivity of the end-to-end pour (scenes/bench/pour_1e5.toml),
/// where OpenVDB merges flat regions' voxels into larger polygons.
void BM_MeshAdaptive(benchmark::State& state) { meshAtAdaptivity(state, 0.01); }
BENCHMARK(BM_MeshAdaptive)->Apply(sizes);

void BM_Fog(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence,
                                      resolveVoxelSize(kSettings, g));
    const auto levelSet = fieldToLevelSet(*field, kSettings.isoValue, kSettings.bandWidth);
    for (auto _ : state) benchmark::DoNotOptimize(levelSetToFog(*levelSet));
}
BENCHMARK(BM_Fog)->Apply(sizes);

/// splat + level set + fog + mesh, what surfaceGlobules does per frame.
void BM_SurfaceFrame(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(surfaceGlobules(g, kSettings));
}
BENCHMARK(BM_SurfaceFrame)->Apply(sizes);

/// The same with a temperature per globule (rising with x) and two materials (by z):
/// the cost of the "temperature" grid and the mesh's per-vertex temperature and material.
void BM_SurfaceFrameThermal(benchmark::State& state) {
    Globules g = benchPuddle(std::size_t(state.range(0)));
    for (std::size_t i = 0; i < g.size(); ++i) {
        g.temperature.push_back(20.0f + 10.0f * g.px[i]);
        g.material.push_back(g.pz[i] < g.pz[g.size() / 2] ? 0 : 1);
    }
    for (auto _ : state) benchmark::DoNotOptimize(surfaceGlobules(g, kSettings));
}
BENCHMARK(BM_SurfaceFrameThermal)->Apply(sizes);

/// A wall one unit thick across the middle of the puddle (a knife through a tray of
/// liquid): a deep cut, through the interior as well as the narrow band.
ColliderSolid puddleKnife(const Globules& g) {
    double maxX = 0, maxY = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        maxX = std::max(maxX, double(g.px[i]));
        maxY = std::max(maxY, double(g.py[i]));
    }
    ColliderSettings knife;
    knife.shape = "box";
    knife.center = {0.5 * maxX, 0.5 * maxY, 0.5 * maxX};
    knife.size = {1.0, 2 * maxY + 8, 2 * maxX + 8};
    return ColliderSolid(knife, {}, 0);
}

/// subtractColliders alone: the knife cut out of the puddle's level set.
void BM_ColliderCut(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const auto field = splatMetaballs(g, kSettings.metaballKernel(), kSettings.influence,
                                      resolveVoxelSize(kSettings, g));
    const auto levelSet = fieldToLevelSet(*field, kSettings.isoValue, kSettings.bandWidth);
    const ColliderSolid knife = puddleKnife(g);
    const std::vector<PlacedSolid> colliders{{&knife, Pose{}}};
    for (auto _ : state) {
        state.PauseTiming();
        const auto copy = levelSet->deepCopy();
        state.ResumeTiming();
        subtractColliders(*copy, colliders);
        state.counters["leaves"] = double(copy->tree().leafCount());
    }
}
BENCHMARK(BM_ColliderCut)->Apply(sizes);

/// BM_SurfaceFrame with the knife cut out (compare the two for the cut's share of a frame).
void BM_SurfaceFrameWithCollider(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const ColliderSolid knife = puddleKnife(g);
    const std::vector<PlacedSolid> colliders{{&knife, Pose{}}};
    for (auto _ : state) benchmark::DoNotOptimize(surfaceGlobules(g, kSettings, colliders));
}
BENCHMARK(BM_SurfaceFrameWithCollider)->Apply(sizes);

/// Eight frames surfaced and written (VDB + PLY) the way runSurfaceStage does, either
/// one at a time with parallel steps (range(1) = 1) or two side by side (2).
void BM_Frames(benchmark::State& state) {
    const Globules g = benchPuddle(std::size_t(state.range(0)));
    const int inFlight = int(state.range(1));
    const auto dir = std::filesystem::temp_directory_path() / "globular_surface_bench";
    constexpr int kFrames = 8;
    for (auto _ : state) {
        auto one = [&](int f) {
            const SurfaceFrame frame = surfaceGlobules(g, kSettings);
            writeSurfaceVdb(surfaceVdbPath(dir, f), frame);
            writeSurfaceMesh(meshPath(dir, f, "ply"), frame.mesh, "ply");
        };
        if (inFlight == 1) {
            for (int f = 1; f <= kFrames; ++f) one(f);
        } else {
            // As runSurfaceStage: isolated, so a waiting thread does not start a third.
            tbb::parallel_for(1, kFrames + 1,
                              [&](int f) { tbb::this_task_arena::isolate([&] { one(f); }); });
        }
    }
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_Frames)
    ->ArgsProduct({{1000, 10000, 100000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ComputeStatistics("min", fastest);

}  // namespace
}  // namespace globular

BENCHMARK_MAIN();
