// The builds of the force loops (simd_path.h) against each other: the same forces to
// single-precision rounding, the same simulation to the tolerance the grid keeps against
// all pairs, momentum conserved and thread counts bit-identical on each. A path this CPU
// lacks is skipped with a message. (The physics and thermal suites also run whole on
// each path: tests/sim_tests.cmake.)

#include "simd_path.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <iostream>

#include "emitter.h"
#include "errors.h"
#include "forces.h"
#include "material.h"
#include "reporter.h"
#include "simulation.h"
#include "simulation_runs.h"

using namespace globular;

namespace {

const SimdPath kAllPaths[] = {SimdPath::Scalar, SimdPath::Avx2, SimdPath::Avx512};

/// Whether to test @p path here; says so when the CPU lacks it.
bool runs(SimdPath path) {
    if (simdPathSupported(path)) return true;
    std::cout << "[  SKIPPED ] the " << simdPathName(path) << " path: this CPU lacks it\n";
    return false;
}

/// @p n globules in a cube of edge @p extent; radii 0.8-1 or, with @p uniformRadius, all 1
/// (the AVX-512 loop then sums straight over the candidates: pair_kernel.h).
Globules randomCloud(std::size_t n, double extent, uint64_t seed, bool twoMaterials,
                     bool uniformRadius = false) {
    Jitter rng(seed);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = 0.8 + 0.2 * rng.next();
        g.add({extent * rng.next(), extent * rng.next(), extent * rng.next()},
              {rng.next(), rng.next(), rng.next()}, uniformRadius ? 1.0f : float(r), 1.0f,
              int32_t(i));
    }
    if (twoMaterials) {
        for (std::size_t i = 0; i < n; ++i) g.material.push_back(uint8_t(i % 3 == 0));
    }
    return g;
}

/// |a - b| within 1e-4 of the force's size (the grid's tolerance against all pairs).
void expectClose(const Accelerations& a, const Accelerations& b) {
    ASSERT_EQ(a.x.size(), b.x.size());
    for (std::size_t i = 0; i < a.x.size(); ++i) {
        const float scale = 1e-4f * (1 + std::abs(b.x[i]) + std::abs(b.y[i]) + std::abs(b.z[i]));
        ASSERT_NEAR(a.x[i], b.x[i], scale) << "globule " << i;
        ASSERT_NEAR(a.y[i], b.y[i], scale) << "globule " << i;
        ASSERT_NEAR(a.z[i], b.z[i], scale) << "globule " << i;
    }
}

SimulationSetup helix(int count) {
    SimulationSetup setup;
    EmitterSettings e;
    e.count = count;
    setup.emitters = {e};
    return setup;
}

/// Two blobs thrown at each other, without gravity or ground: momentum is conserved.
SimulationSetup collision() {
    SimulationSetup setup;
    setup.ground.enabled = false;
    setup.simulation.gravity = {0, 0, 0};
    EmitterSettings left, right;
    for (EmitterSettings* e : {&left, &right}) {
        e->type = "box";
        e->count = 0;
        e->spacing = 1.0;
        e->min = {-4, 0, -2};
        e->max = {0, 4, 2};
        e->velocity = {2, 0, 0};
    }
    right.min = {0.5, 1, -2};
    right.max = {4.5, 5, 2};
    right.velocity = {-3, 0.5, 0};
    setup.emitters = {left, right};
    return setup;
}

Globules runOn(SimdPath path, const SimulationSetup& setup, int frames, int threads = 2) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    Simulation sim(setup);
    sim.setSimdPath(path);
    NullReporter quiet;
    for (int f = 2; f <= frames; ++f) sim.advanceFrame(f, quiet);
    return sim.globules();
}

}  // namespace

TEST(SimdPath, NamesAndTheEnvironmentVariable) {
    for (SimdPath p : kAllPaths) EXPECT_EQ(parseSimdPath(simdPathName(p)), p);
    EXPECT_FALSE(parseSimdPath("AVX2").has_value());
    EXPECT_TRUE(simdPathSupported(SimdPath::Scalar));
    const SimdPath best = supportedSimdPaths().back();
    EXPECT_EQ(chooseSimdPath(nullptr), best);
    EXPECT_EQ(chooseSimdPath(""), best);
    EXPECT_EQ(chooseSimdPath("auto"), best);
    EXPECT_EQ(chooseSimdPath("scalar"), SimdPath::Scalar);
    try {
        chooseSimdPath("sse9");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "GLOBULAR_SIMD=sse9: expected auto, scalar, avx2 or avx512");
    }
    for (SimdPath p : kAllPaths) {
        if (simdPathSupported(p)) {
            EXPECT_EQ(chooseSimdPath(simdPathName(p)), p);
        } else {
            EXPECT_THROW(chooseSimdPath(simdPathName(p)), Error) << simdPathName(p);
        }
    }
}

namespace {

/// A liquid and a solid: the table the force tests use (the liquid with itself for one
/// material).
PairTable liquidAndSolid() {
    MaterialSettings liquid, solid;
    solid.preset = "solid";
    return PairTable({liquid, solid}, {});
}

/// The all-pairs forces on @p cloud, in its order.
Accelerations allPairsForces(const Globules& cloud, const PairTable& table, bool twoMaterials) {
    Accelerations reference;
    twoMaterials ? pairForcesAllPairs(cloud, table, reference)
                 : pairForcesAllPairs(cloud, table(0, 0), reference);
    return reference;
}

/// The grid loop's forces on @p cloud on @p path, back in the cloud's order; @p grain:
/// globules per task at least (NeighborWorkspace).
Accelerations gridForces(const Globules& cloud, const PairTable& table, bool twoMaterials,
                         SimdPath path, std::size_t grain = NeighborWorkspace{}.grain) {
    Globules sorted = cloud;
    NeighborWorkspace workspace;
    workspace.grain = grain;
    Accelerations grid;
    twoMaterials ? pairForcesSorting(sorted, table, workspace, grid, path)
                 : pairForcesSorting(sorted, table(0, 0), workspace, grid, path);
    Accelerations inOrder;
    inOrder.resize(cloud.size());
    for (std::size_t k = 0; k < sorted.size(); ++k) {
        const std::size_t i = std::size_t(sorted.id[k]);
        inOrder.x[i] = grid.x[k];
        inOrder.y[i] = grid.y[k];
        inOrder.z[i] = grid.z[k];
    }
    return inOrder;
}

}  // namespace

TEST(SimdPath, EveryPathGivesTheAllPairsForces) {
    const PairTable table = liquidAndSolid();
    for (bool twoMaterials : {false, true}) {
        const Globules cloud = randomCloud(800, 9.0, 5, twoMaterials);
        const Accelerations reference = allPairsForces(cloud, table, twoMaterials);
        for (SimdPath p : kAllPaths) {
            if (!runs(p)) continue;
            SCOPED_TRACE(std::string(simdPathName(p)) + (twoMaterials ? ", two materials" : ""));
            expectClose(gridForces(cloud, table, twoMaterials, p), reference);
        }
    }
}

// Crowded cells (about 160 globules a group) are split into parts with their own
// candidates (force_kernels.cpp, GroupParts): still every pair within reach, once, and the
// same bits on one thread as on two, where the ranges may cut groups at other places, and
// with a grain of a few globules, where they do. With a uniform radius the AVX-512 sum's
// lanes follow the candidate lists, which follow the groups: the tasks keep cells whole.
TEST(SimdPath, CrowdedCellsGiveTheAllPairsForcesOnAnyThreadCount) {
    const PairTable table = liquidAndSolid();
    for (int variant = 0; variant < 4; ++variant) {
        const bool twoMaterials = variant % 2 == 1, uniformRadius = variant >= 2;
        const Globules cloud = randomCloud(1500, 5.0, 11, twoMaterials, uniformRadius);
        const Accelerations reference = allPairsForces(cloud, table, twoMaterials);
        for (SimdPath p : kAllPaths) {
            if (!runs(p)) continue;
            SCOPED_TRACE(std::string(simdPathName(p)) + (twoMaterials ? ", two materials" : "") +
                         (uniformRadius ? ", uniform radius" : ""));
            Accelerations byThreads[3];
            for (std::size_t threads : {1u, 2u}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
                byThreads[threads - 1] = gridForces(cloud, table, twoMaterials, p);
            }
            {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
                byThreads[2] = gridForces(cloud, table, twoMaterials, p, 5);
            }
            expectClose(byThreads[0], reference);
            for (int run : {1, 2}) {
                SCOPED_TRACE(run == 1 ? "2 threads" : "2 threads, grain 5");
                EXPECT_EQ(byThreads[0].x, byThreads[run].x);
                EXPECT_EQ(byThreads[0].y, byThreads[run].y);
                EXPECT_EQ(byThreads[0].z, byThreads[run].z);
            }
        }
    }
}

TEST(SimdPath, SimulationsAgreeAcrossPaths) {
    const SimulationSetup setup = helix(300);
    const Globules scalar = runOn(SimdPath::Scalar, setup, 4);
    ASSERT_EQ(scalar.size(), 300u);
    std::vector<std::size_t> indexOfId(scalar.size());
    for (std::size_t i = 0; i < scalar.size(); ++i) indexOfId[std::size_t(scalar.id[i])] = i;
    for (SimdPath p : {SimdPath::Avx2, SimdPath::Avx512}) {
        if (!runs(p)) continue;
        SCOPED_TRACE(simdPathName(p));
        const Globules g = runOn(p, setup, 4);
        ASSERT_EQ(g.size(), scalar.size());
        for (std::size_t i = 0; i < g.size(); ++i) {
            const std::size_t j = indexOfId[std::size_t(g.id[i])];
            ASSERT_NEAR(g.px[i], scalar.px[j], 1e-3) << "id " << g.id[i];
            ASSERT_NEAR(g.py[i], scalar.py[j], 1e-3) << "id " << g.id[i];
            ASSERT_NEAR(g.pz[i], scalar.pz[j], 1e-3) << "id " << g.id[i];
        }
    }
}

TEST(SimdPath, EachPathConservesMomentumAndIgnoresTheThreadCount) {
    const SimulationSetup setup = collision();
    const auto [before, scale] = momentumOf(Simulation(setup).globules());
    ASSERT_GT(scale, 100.0);
    for (SimdPath p : kAllPaths) {
        if (!runs(p)) continue;
        SCOPED_TRACE(simdPathName(p));
        const Globules one = runOn(p, setup, 12, 1), two = runOn(p, setup, 12, 2);
        EXPECT_LT(length(momentumOf(two).first - before), 1e-4 * scale);
        EXPECT_EQ(one.px, two.px);
        EXPECT_EQ(one.vy, two.vy);
        EXPECT_EQ(one.id, two.id);
    }
}
