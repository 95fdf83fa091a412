// Several materials in one shot (issue 14): the mixing rule and [[material_pair]]
// overrides, a symmetric table, the split-by-material force loop against the all-pairs
// reference, momentum conserved with any mix, and bit-identical results for any thread
// count and on resume.

#include "material_pairs.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <random>

#include "errors.h"
#include "forces.h"
#include "reporter.h"
#include "simulation.h"
#include "simulation_runs.h"

using namespace globular;

namespace {

MaterialSettings named(const std::string& name, const std::string& preset, double b1, double r0) {
    MaterialSettings m;
    m.name = name;
    m.preset = preset;
    m.b1 = b1;
    m.r0 = r0;
    return m;
}

TEST(MaterialPairs, MixingRuleAndOverridesGiveASymmetricTable) {
    const std::vector<MaterialSettings> materials = {named("ketchup", "liquid", 2, 1),
                                                     named("mustard", "solid", 1, 1.5),
                                                     named("oil", "powder", 3, 0.8)};
    MaterialPairSettings apart;
    apart.a = "oil";
    apart.b = "ketchup";
    apart.b1 = 0.5;  // hardly any attraction: they stay apart
    const PairTable table(materials, {apart});
    ASSERT_EQ(table.materials(), 3u);
    // A material meets itself with its own constants.
    EXPECT_EQ(table(1, 1).b1, 1.0f);
    EXPECT_EQ(table(1, 1).cr, 3.0f);  // solid: C_r = 2 r0
    // Two materials: means of b1 and r0 (b2 = b1 r0^(n-m)), the wider windows.
    const PairForce& mixed = table(0, 1);
    EXPECT_FLOAT_EQ(mixed.b1, 1.5f);
    EXPECT_FLOAT_EQ(mixed.b2, float(1.5 * std::pow(1.25, -2.0)));
    EXPECT_FLOAT_EQ(mixed.cr, 3.0f);   // the solid's 2 r0
    EXPECT_FLOAT_EQ(mixed.cd, 3.0f);
    // The pair section overrides b1 only.
    EXPECT_FLOAT_EQ(table(2, 0).b1, 0.5f);
    EXPECT_FLOAT_EQ(table(2, 0).cd, 1.5f);  // the liquid's alpha r0, wider than 0.8
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = 0; b < 3; ++b) {
            EXPECT_EQ(table(a, b).b1, table(b, a).b1);
            EXPECT_EQ(table(a, b).b2, table(b, a).b2);
            EXPECT_EQ(table(a, b).cr, table(b, a).cr);
            EXPECT_EQ(table(a, b).cd, table(b, a).cd);
        }
    }
    MaterialPairSettings unknown;
    unknown.a = "oil";
    unknown.b = "honey";
    EXPECT_THROW(PairTable(materials, {unknown}), SceneError);
}

/// @p n globules of two materials, jittered in a box, moving at random.
Globules mixedCloud(std::size_t n, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> at(-4, 4), speed(-1, 1);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        g.add({at(random), at(random), at(random)}, {speed(random), speed(random), speed(random)},
              i % 3 == 0 ? 0.7f : 1.0f, i % 3 == 0 ? 0.5f : 1.0f, int32_t(i));
        g.material.push_back(uint8_t(i % 2));
    }
    return g;
}

TEST(MaterialPairs, SplitLoopMatchesTheAllPairsReference) {
    const PairTable table({named("a", "liquid", 2, 1), named("b", "solid", 1, 1.3)}, {});
    const Globules reference = mixedCloud(600, 7);
    Accelerations exact;
    pairForcesAllPairs(reference, table, exact);
    Globules sorted = reference;
    NeighborWorkspace workspace;
    Accelerations grid;
    pairForcesSorting(sorted, table, workspace, grid);
    std::size_t checked = 0;
    for (std::size_t k = 0; k < sorted.size(); ++k) {
        const std::size_t i = std::size_t(sorted.id[k]);
        ASSERT_EQ(sorted.material[k], reference.material[i]);  // travelled with the globule
        const double scale = 1 + std::abs(exact.x[i]) + std::abs(exact.y[i]) + std::abs(exact.z[i]);
        EXPECT_NEAR(grid.x[k], exact.x[i], 1e-4 * scale) << k;
        EXPECT_NEAR(grid.y[k], exact.y[i], 1e-4 * scale) << k;
        EXPECT_NEAR(grid.z[k], exact.z[i], 1e-4 * scale) << k;
        checked += exact.x[i] != 0;
    }
    EXPECT_GT(checked, 500u);
}

/// Two materials poured side by side, weightless and off the ground.
SimulationSetup twoSauces() {
    SimulationSetup setup;
    setup.ground.enabled = false;
    setup.simulation.gravity = {0, 0, 0};
    setup.material = named("ketchup", "liquid", 2, 1);
    setup.otherMaterials = {named("mustard", "solid", 1, 1)};
    EmitterSettings left, right;
    for (EmitterSettings* e : {&left, &right}) {
        e->type = "box";
        e->count = 0;
        e->spacing = 1.0;
        e->min = {-3, 0, -1.5};
        e->max = {0, 3, 1.5};
        e->velocity = {1.5, 0, 0};
    }
    right.min = {0.5, 0, -1.5};
    right.max = {3.5, 3, 1.5};
    right.velocity = {-2.5, 0.5, 0};
    right.material = "mustard";
    right.mass = 2;
    setup.emitters = {left, right};
    return setup;
}

TEST(MaterialPairs, MomentumIsConservedWithTwoMaterials) {
    Simulation sim(twoSauces());
    NullReporter quiet;
    const auto [before, scale] = momentumOf(sim.globules());
    ASSERT_GT(sim.globules().size(), 50u);
    for (int f = 2; f <= 26; ++f) sim.advanceFrame(f, quiet);
    EXPECT_LT(length(momentumOf(sim.globules()).first - before), 1e-4 * scale);
    // They did meet: the mustard, thrown at the ketchup, has lost most of its x momentum.
    double mustard = 0;
    const Globules& g = sim.globules();
    for (std::size_t i = 0; i < g.size(); ++i) mustard += g.material[i] == 1 ? g.mass[i] * g.vx[i] : 0;
    EXPECT_GT(mustard, -0.5 * 2.5 * 2 * 27);
}

TEST(MaterialPairs, ResultsAreIdenticalForAnyThreadCountAndOnResume) {
    const SimulationSetup setup = twoSauces();
    const auto run = [&](int threads, int frames) { return stateAfter(setup, threads, frames); };
    const SimulationState one = run(1, 12), two = run(2, 12);
    EXPECT_EQ(one.globules.px, two.globules.px);
    EXPECT_EQ(one.globules.material, two.globules.material);
    Simulation resumed(setup);
    resumed.restoreState(run(2, 6));
    NullReporter quiet;
    for (int f = 7; f <= 12; ++f) resumed.advanceFrame(f, quiet);
    EXPECT_EQ(resumed.saveState().globules.px, one.globules.px);
    EXPECT_EQ(resumed.saveState().globules.vz, one.globules.vz);
    // Globules that carry materials do not fit a scene of one.
    SimulationSetup single = setup;
    single.otherMaterials.clear();
    single.emitters[1].material.clear();
    Simulation plain(single);
    EXPECT_THROW(plain.restoreState(one), Error);
}

}  // namespace
