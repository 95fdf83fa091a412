#include "forces.h"

#include <gtest/gtest.h>

#include <cmath>

#include "emitter.h"
#include "integrator.h"
#include "material.h"

using namespace globular;

namespace {

Globules randomCloud(std::size_t n, double extent, uint64_t seed) {
    Jitter rng(seed);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        g.add({extent * rng.next(), extent * rng.next(), extent * rng.next()},
              {rng.next(), rng.next(), rng.next()}, float(0.8 + 0.2 * rng.next()), 1.0f,
              int32_t(i));
    }
    return g;
}

}  // namespace

TEST(Forces, PairForcesConserveMomentum) {
    const Globules g = randomCloud(600, 6.0, 7);
    const PairForce pair = PairForce::fromMaterial(MaterialSettings{});
    Accelerations f;
    NeighborWorkspace workspace;
    pairForcesGrid(g, pair, workspace, f);
    double sum[3] = {0, 0, 0}, magnitude = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        sum[0] += f.x[i];
        sum[1] += f.y[i];
        sum[2] += f.z[i];
        magnitude += std::abs(f.x[i]) + std::abs(f.y[i]) + std::abs(f.z[i]);
    }
    ASSERT_GT(magnitude, 100.0);  // the cloud is dense enough to interact
    for (double s : sum) EXPECT_LT(std::abs(s), 1e-5 * magnitude);
}

TEST(Forces, CellListEqualsAllPairsOnRandomClouds) {
    for (uint64_t seed : {1u, 2u, 3u}) {
        MaterialSettings m;
        m.preset = seed == 3 ? "solid" : "liquid";
        const Globules g = randomCloud(800, 8.0 + double(seed), seed);
        const PairForce pair = PairForce::fromMaterial(m);
        Accelerations grid, reference;
        NeighborWorkspace workspace;
        pairForcesGrid(g, pair, workspace, grid);
        pairForcesAllPairs(g, pair, reference);
        for (std::size_t i = 0; i < g.size(); ++i) {
            const float scale = 1e-4f * (1 + std::abs(reference.x[i]) + std::abs(reference.y[i]) +
                                         std::abs(reference.z[i]));
            ASSERT_NEAR(grid.x[i], reference.x[i], scale) << "globule " << i;
            ASSERT_NEAR(grid.y[i], reference.y[i], scale) << "globule " << i;
            ASSERT_NEAR(grid.z[i], reference.z[i], scale) << "globule " << i;
        }
    }
}

TEST(Forces, NeighborGridVisitsEveryCloseGlobuleOnce) {
    const Globules g = randomCloud(500, 50.0, 11);  // sparse: many empty cells, collisions
    NeighborGrid grid;
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), 4.0f);
    for (std::size_t i = 0; i < g.size(); i += 7) {
        std::vector<int> seen(g.size(), 0);
        grid.forEachCandidate(g.px[i], g.py[i], g.pz[i], [&](uint32_t j) { ++seen[j]; });
        for (std::size_t j = 0; j < g.size(); ++j) {
            const float dx = g.px[i] - g.px[j], dy = g.py[i] - g.py[j], dz = g.pz[i] - g.pz[j];
            ASSERT_LE(seen[j], 1);
            if (dx * dx + dy * dy + dz * dz < 16.0f) {
                ASSERT_EQ(seen[j], 1);
            }
        }
    }
}

TEST(Forces, RunCursorGivesTheRunsOfAFreshQuery) {
    for (const double extent : {6.0, 40.0}) {  // dense, and sparse with hash collisions
        const Globules g = randomCloud(3000, extent, 5);
        NeighborGrid grid;
        grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), 3.0f);
        NeighborGrid::RunCursor cursor;
        std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> fresh, advanced;
        for (const uint32_t i : grid.sortedOrder()) {  // the force loop's order
            const int n = grid.neighborRuns(g.px[i], g.py[i], g.pz[i], fresh);
            ASSERT_EQ(grid.neighborRuns(g.px[i], g.py[i], g.pz[i], cursor, advanced), n);
            for (int r = 0; r < n; ++r) ASSERT_EQ(advanced[r], fresh[r]) << "globule " << i;
        }
    }
}

TEST(Forces, GroundHoldsARestingGlobuleAtTheExpectedDepth) {
    for (const char* contact : {"center", "surface"}) {
        GroundSettings ground;
        ground.contact = contact;
        ForceField field(PairForce::fromMaterial(MaterialSettings{}),
                         ExternalForces{{0, -9.8, 0}, ground, {}, {}});
        Globules g;
        g.add({0, 1.5, 0}, {0, 0, 0}, 0.5f, 1.0f, 0);
        SemiImplicitEuler integrator;
        for (int s = 0; s < 4000; ++s) {
            integrator.step(g, 0.001f, [&](Globules& gg, Accelerations& a) {
                field.compute(gg, a);
            });
        }
        // Equilibrium of eq. (9): k_s depth = m g.
        const double depth = 9.8 / 5000.0;
        const double expected = std::string(contact) == "center" ? -depth : 0.5 - depth;
        EXPECT_NEAR(g.py[0], expected, 2e-5) << contact;
        EXPECT_NEAR(g.vy[0], 0.0, 1e-3) << contact;
    }
}

TEST(Forces, GroundPushesOnlyInContact) {
    GroundSettings ground;
    EXPECT_EQ(groundForce(ground, 0.1f, -5.0f, 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(groundForce(ground, -0.01f, 0.0f, 1.0f), 50.0f);
    EXPECT_FLOAT_EQ(groundForce(ground, -0.01f, -1.0f, 1.0f), 350.0f);
}
