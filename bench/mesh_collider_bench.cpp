// Mesh colliders (sim/mesh_sdf.h): MeshSdf::sample per globule, as the simulation calls it
// once per globule per step per mesh collider, in a TBB loop; and the one-off build.
// The mesh is scenes/effectors/bowl.obj as a shell 0.1 thick, voxel 0.024 (1/100 of its
// width), reach 0.05 (globules of radius 0.05). Points (fixed seed, random order, as
// globules are not sorted in memory):
//   Bowl      globules in and around it: 75% filling the cavity (most beyond reach of
//             the wall), 15% within reach of the inner wall, 10% above and outside
//   NearWall  all within reach of the inner wall: every sample computes a normal
// Reported: per_sample, the wall-clock time per sample (all threads together).
// Run: build/bench/mesh_collider_bench.

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <random>
#include <vector>

#include "mesh.h"
#include "mesh_sdf.h"

using namespace globular;

namespace {

constexpr double kSphereRadius = 1.2;  // bowl.obj: a cap of this sphere...
const Vec3 kCenter{0, 1.2, 0};         // ...centred here, rim at y = 0.9
constexpr double kRimY = 0.9;
constexpr double kThickness = 0.1, kReach = 0.05, kVoxelSize = 0.024;
constexpr double kInner = kSphereRadius - kThickness / 2;  // the shell's inner face

const TriangleMesh& bowlMesh() {
    static const TriangleMesh mesh =
        readMeshFile(std::filesystem::path(GLOBULAR_SOURCE_DIR) / "scenes/effectors/bowl.obj");
    return mesh;
}

const MeshSdf& bowl() {
    static const MeshSdf sdf(bowlMesh(), kVoxelSize, kThickness, kReach, "bowl.obj");
    return sdf;
}

/// A point uniformly in the cavity below the rim (the liquid).
Vec3 inCavity(std::mt19937& rng) {
    std::uniform_real_distribution<double> xz(-kInner, kInner), y(0, kRimY);
    for (;;) {
        const Vec3 p{xz(rng), y(rng), xz(rng)};
        if (length(p - kCenter) < kInner) return p;
    }
}

/// A point below the rim up to @p fromWall inside the inner face of the shell.
Vec3 nearWall(std::mt19937& rng, double fromWall) {
    std::uniform_real_distribution<double> unit(-1, 1), u(0, 1);
    for (;;) {
        const Vec3 d{unit(rng), unit(rng), unit(rng)};
        if (dot(d, d) > 1 || dot(d, d) < 1e-6) continue;
        const Vec3 p = kCenter + (kInner - fromWall * u(rng)) * normalized(d);
        if (p.y < kRimY) return p;
    }
}

std::vector<Vec3> points(std::size_t n, bool nearWallOnly) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> out(n);
    for (Vec3& p : out) {
        const double kind = nearWallOnly ? 0.8 : u(rng);
        if (kind < 0.75) {
            p = inCavity(rng);
        } else if (kind < 0.9) {
            p = nearWall(rng, kReach);
        } else {
            p = {3 * u(rng) - 1.5, kRimY + 1.5 * u(rng) - 0.5, 3 * u(rng) - 1.5};  // around
        }
    }
    return out;
}

void runSamples(benchmark::State& state, bool nearWallOnly) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                std::size_t(state.range(1)));
    const MeshSdf& sdf = bowl();
    const std::vector<Vec3> at = points(std::size_t(state.range(0)), nearWallOnly);
    std::vector<SurfaceSample> out(at.size());
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, at.size(), 1024),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t i = r.begin(); i < r.end(); ++i) {
                                  out[i] = sdf.sample(at[i]);
                              }
                          });
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    // Seconds per sample (printed with its SI prefix: "31.7ns").
    state.counters["per_sample"] =
        benchmark::Counter(double(at.size()) * double(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_MeshSdfSampleBowl(benchmark::State& state) { runSamples(state, false); }
void BM_MeshSdfSampleNearWall(benchmark::State& state) { runSamples(state, true); }

/// The one-off build of the bowl's shell at voxel size 1 / range(0) of the bowl's radius.
void BM_MeshSdfBuildBowl(benchmark::State& state) {
    const double voxelSize = kSphereRadius / double(state.range(0));
    std::size_t bytes = 0;
    for (auto _ : state) {
        const MeshSdf sdf(bowlMesh(), voxelSize, 4 * voxelSize, kReach, "bowl.obj");
        bytes = sdf.memoryBytes();
    }
    state.counters["MB"] = double(bytes) / 1e6;
}

}  // namespace

BENCHMARK(BM_MeshSdfSampleBowl)
    ->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})
    ->ArgNames({"points", "threads"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_MeshSdfSampleNearWall)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"points", "threads"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(BM_MeshSdfBuildBowl)
    ->Arg(50)
    ->Arg(100)
    ->Arg(200)
    ->ArgName("voxels_per_radius")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
