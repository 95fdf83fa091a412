// Temperature (issue 14): conduction conserves heat and brings two globules to their
// mean, Newton cooling follows the exponential, the phase blend is exactly the solid's
// force at T_solid and the liquid's at T_liquid, the thermal loop matches its all-pairs
// reference, momentum is conserved with two materials, a block on a hot plate heats up
// and slumps, buoyancy lifts, and results are identical for any thread count and on
// resume, through the checkpoint file too.

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "errors.h"
#include "forces.h"
#include "integrator.h"
#include "reporter.h"
#include "simulation.h"
#include "simulation_runs.h"
#include "state_file.h"
#include "thermal_kernel.h"

using namespace globular;

namespace {

ThermalSettings thermalOn() {
    ThermalSettings t;
    t.enabled = true;
    return t;
}

/// A weightless world without ground: only what the test adds acts.
ExternalForces weightless(const std::vector<MaterialSettings>& materials,
                          ThermalSettings thermal = thermalOn(), std::vector<HeaterSettings> heaters = {}) {
    GroundSettings ground;
    ground.enabled = false;
    return ExternalForces{{0, 0, 0}, ground, ColliderSet(),
                          ThermalSources(thermal, std::move(heaters), materials, {0, 0, 0}, ground)};
}

MaterialSettings wax(const std::string& name = "wax") {
    MaterialSettings m;
    m.name = name;
    m.phases = true;
    m.tSolid = 40;
    m.tLiquid = 60;
    m.solid.preset = "solid";
    m.liquid.preset = "liquid";
    return m;
}

/// @p n globules jittered in a box, at random temperatures in [0, 100]; two materials
/// when @p two.
/// @p uniformRadius: every radius 1, not 0.7 and 1 (the AVX-512 loop then sums straight
/// over the candidates: pair_kernel.h).
Globules warmCloud(std::size_t n, uint32_t seed, bool two, bool uniformRadius = false) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> at(-3, 3), speed(-0.5, 0.5), hot(0, 100);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        const float radius = i % 3 == 0 && !uniformRadius ? 0.7f : 1.0f;
        g.add({at(random), at(random), at(random)}, {speed(random), speed(random), speed(random)},
              radius, i % 4 == 0 ? 2.0f : 1.0f, int32_t(i));
        g.temperature.push_back(hot(random));
        if (two) g.material.push_back(uint8_t(i % 2));
    }
    return g;
}

double totalHeat(const Globules& g, const std::vector<MaterialSettings>& materials) {
    double heat = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        heat += double(g.mass[i]) * materials[g.materialOf(i)].heatCapacity * g.temperature[i];
    }
    return heat;
}

TEST(Thermal, ConductionConservesHeat) {
    MaterialSettings cold = wax("a"), other = wax("b");
    other.heatCapacity = 3;
    other.conductivity = 0.5;
    const std::vector<MaterialSettings> materials = {cold, other};
    ForceField field(PairTable(materials, {}), weightless(materials));
    Globules g = warmCloud(400, 3, true);
    const double before = totalHeat(g, materials);
    double spreadBefore = 0, spreadAfter = 0;
    for (float t : g.temperature) spreadBefore += std::abs(t - 50);
    ForwardEuler euler;
    for (int s = 0; s < 400; ++s) {
        euler.step(g, 0.001f, [&](Globules& x, Accelerations& a) { field.compute(x, a); });
    }
    for (float t : g.temperature) spreadAfter += std::abs(t - 50);
    EXPECT_NEAR(totalHeat(g, materials), before, 1e-5 * before);
    EXPECT_LT(spreadAfter, 0.8 * spreadBefore);  // heat did flow
}

TEST(Thermal, TwoGlobulesEquilibrateToTheirMean) {
    MaterialSettings m = wax();
    m.conductivity = 5;
    const std::vector<MaterialSettings> materials = {m};
    ForceField field(PairTable(materials, {}), weightless(materials));
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1.0f, 0);
    g.add({1, 0, 0}, {0, 0, 0}, 0.5f, 3.0f, 1);  // three times the heat capacity
    g.temperature = {100, 0};
    SemiImplicitEuler integrator;
    for (int s = 0; s < 5000; ++s) {
        integrator.step(g, 0.001f, [&](Globules& x, Accelerations& a) { field.compute(x, a); });
    }
    const double mean = (1.0 * 100 + 3.0 * 0) / 4.0;  // sum C T / sum C
    EXPECT_NEAR(g.temperature[0], mean, 1e-3);
    EXPECT_NEAR(g.temperature[1], mean, 1e-3);
}

TEST(Thermal, NewtonCoolingFollowsTheExponential) {
    ThermalSettings t = thermalOn();
    t.ambient = 20;
    t.cooling = 0.8;
    const std::vector<MaterialSettings> materials(1);
    ForceField field(PairTable(materials, {}), weightless(materials, t));
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1.0f, 0);
    g.temperature = {90};
    ForwardEuler euler;
    const float dt = 0.0005f;
    for (int s = 1; s <= 4000; ++s) {
        euler.step(g, dt, [&](Globules& x, Accelerations& a) { field.compute(x, a); });
        if (s % 1000 == 0) {
            const double exact = 20 + 70 * std::exp(-0.8 * s * dt);
            EXPECT_NEAR(g.temperature[0], exact, 1e-3 * 70) << s;
        }
    }
}

TEST(Thermal, HeaterAddsItsPowerInsideTheBox) {
    HeaterSettings heater;
    heater.min = {-1, -1, -1};
    heater.max = {1, 1, 1};
    heater.power = 6;
    MaterialSettings m;
    m.heatCapacity = 2;
    const std::vector<MaterialSettings> materials = {m};
    ForceField field(PairTable(materials, {}), weightless(materials, thermalOn(), {heater}));
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 1.5f, 0);
    g.add({50, 0, 0}, {0, 0, 0}, 0.5f, 1.0f, 1);
    g.temperature = {10, 10};
    Accelerations a;
    field.compute(g, a);
    const std::size_t inside = g.id[0] == 0 ? 0 : 1;
    EXPECT_FLOAT_EQ(a.heat[inside], 6.0f / (1.5f * 2.0f));  // P / (m c)
    EXPECT_EQ(a.heat[1 - inside], 0.0f);
}

/// Wax whose phases share their windows (so both loops build the same grid and sum in the
/// same order) and differ in strength.
MaterialSettings evenWax() {
    MaterialSettings m = wax();
    m.liquid.preset = "custom";
    m.liquid.cr = m.liquid.cd = 2;  // the solid's 2 r0
    m.liquid.b1 = 1.2;
    return m;
}

/// A dense cloud all at temperature @p t: its forces with a thermal table of phases and
/// with the plain loop of @p constants alone.
void expectSameForces(float t, const ForceConstants& constants) {
    const std::vector<MaterialSettings> phased = {evenWax()};
    Globules thermal = warmCloud(500, 11, false);
    for (float& x : thermal.temperature) x = t;
    Globules plain = thermal;
    plain.temperature.clear();
    NeighborWorkspace w1, w2;
    Accelerations a, b;
    pairForcesThermal(thermal, PairTable(phased, {}), w1, a);
    pairForcesSorting(plain, PairForce::fromMaterial(constants), w2, b);
    ASSERT_EQ(thermal.id, plain.id);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
}

TEST(Thermal, BlendIsExactlyTheSolidAtTSolidAndTheLiquidAtTLiquid) {
    const MaterialSettings m = evenWax();
    expectSameForces(40, m.solid);
    expectSameForces(-10, m.solid);
    expectSameForces(60, m.liquid);
    expectSameForces(500, m.liquid);
    const PairTable table({m}, {});
    const ThermalPair& pair = table.thermal(0, 0);
    EXPECT_EQ(meltFraction(40, pair), 0.0f);
    EXPECT_EQ(meltFraction(60, pair), 1.0f);
    EXPECT_FLOAT_EQ(meltFraction(50, pair), 0.5f);      // smoothstep's midpoint
    EXPECT_FLOAT_EQ(meltFraction(45, pair), 0.15625f);  // x = 1/4: 3/16 - 2/64
}

/// HeatAndForceDoNotDependOnTheKernelThePhasePicks for @p material; radii 0.7 and 1, or
/// with @p uniformRadius all 1 (the AVX-512 loop then sums straight over the candidates).
void expectSameResultsWhicheverKernel(const MaterialSettings& material, bool uniformRadius) {
    const PairTable table({material}, {});
    const ThermalPair& pair = table.thermal(0, 0);
    const float reach = std::max(pair.solid.cutoff(1.0f), pair.liquid.cutoff(1.0f));
    std::mt19937 random(21);
    std::uniform_real_distribution<float> at(-9, 9), speed(-0.5, 0.5), warm(60, 100);
    Globules liquid;
    for (int i = 0; i < 2500; ++i) {
        const float radius = i % 3 == 0 && !uniformRadius ? 0.7f : 1.0f;
        liquid.add({at(random), at(random), at(random)},
                   {speed(random), speed(random), speed(random)}, radius, 1.0f, i);
        liquid.temperature.push_back(warm(random));  // every pair's mean is above T_liquid
    }
    // Two globules chilled where they are: every candidate list stays as it was, but
    // the groups that take a cold one as a candidate pick the blended kernel.
    Globules chilled = liquid;
    const std::vector<std::size_t> cold = {1, 2};  // (radius 1 in both clouds)
    for (std::size_t c : cold) chilled.temperature[c] = 0;
    // The globules beyond reach of every cold one, and how many of them are within two
    // reaches of one (where groups take the cold ones as candidates).
    std::vector<bool> untouched(liquid.size(), true);
    std::size_t nearby = 0;
    for (std::size_t i = 0; i < liquid.size(); ++i) {
        double closest = 1e30;
        for (std::size_t c : cold) {
            closest = std::min(closest, length(liquid.position(i) - liquid.position(c)));
        }
        const double limit = reach * (liquid.radius[i] + 1.0f) * 1.01;
        untouched[i] = closest > limit;
        nearby += untouched[i] && closest < 2 * limit;
    }
    ASSERT_GT(nearby, 50u);
    Accelerations alone, withCold;
    NeighborWorkspace w1, w2;
    pairForcesThermal(liquid, table, w1, alone);
    pairForcesThermal(chilled, table, w2, withCold);
    std::vector<std::size_t> byId(chilled.size());
    for (std::size_t k = 0; k < chilled.size(); ++k) byId[std::size_t(chilled.id[k])] = k;
    std::size_t compared = 0, heated = 0;
    for (std::size_t k = 0; k < liquid.size(); ++k) {
        const std::size_t original = std::size_t(liquid.id[k]);
        if (!untouched[original]) continue;
        const std::size_t other = byId[original];
        SCOPED_TRACE("globule " + std::to_string(original));
        ASSERT_EQ(alone.heat[k], withCold.heat[other]);
        ASSERT_EQ(alone.x[k], withCold.x[other]);
        ASSERT_EQ(alone.y[k], withCold.y[other]);
        ASSERT_EQ(alone.z[k], withCold.z[other]);
        ++compared;
        heated += alone.heat[k] != 0;
    }
    EXPECT_GT(heated, compared / 2);  // the heat is a real sum, not zero
}

/// A globule's heat and force have the same bits whichever kernel the loop picks for its
/// pairs' phase (force_kernels.cpp): the pure phase's, or the blend's, which the loop takes
/// when any of the group's candidates is outside the pure range, neighbour or not. A
/// liquid cloud is summed as it is and then with two of its globules chilled: every
/// globule that has no cold one within reach forms the same liquid pairs from the same
/// candidates either way, though near the cold ones it is summed by the blended kernel, so
/// its results must not change by a bit.
TEST(Thermal, HeatAndForceDoNotDependOnTheKernelThePhasePicks) {
    MaterialSettings unshared = evenWax();  // the phases' exponents differ: pow() kernels
    unshared.liquid.n = 4;
    for (const MaterialSettings& material : {evenWax(), unshared}) {
        for (bool uniformRadius : {false, true}) {
            const bool differ = material.liquid.n == 4;
            SCOPED_TRACE(std::string(differ ? "exponents differ" : "exponents shared") +
                         (uniformRadius ? ", uniform radius" : ""));
            expectSameResultsWhicheverKernel(material, uniformRadius);
        }
    }
}

TEST(Thermal, PairPhasesAreSymmetric) {
    MaterialSettings other = wax("b");
    other.tSolid = 10;
    other.tLiquid = 90;
    other.solid.b1 = 3;
    other.conductivity = 2;
    MaterialSettings plain;
    plain.name = "c";
    plain.conductivity = 0;  // insulates: no heat flows to or from it
    const PairTable table({wax("a"), other, plain}, {});
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = 0; b < 3; ++b) {
            const ThermalPair &ab = table.thermal(a, b), &ba = table.thermal(b, a);
            EXPECT_EQ(ab.solid.b1, ba.solid.b1);
            EXPECT_EQ(ab.liquid.cd, ba.liquid.cd);
            EXPECT_EQ(ab.tSolid, ba.tSolid);
            EXPECT_EQ(ab.tLiquid, ba.tLiquid);
            EXPECT_EQ(ab.conductance, ba.conductance);
        }
    }
    EXPECT_FLOAT_EQ(table.thermal(0, 1).tSolid, 25);   // the mean of the two ranges
    EXPECT_FLOAT_EQ(table.thermal(0, 1).tLiquid, 75);
    EXPECT_FLOAT_EQ(table.thermal(0, 1).conductance, 2 * 1 * 2 / 3.0f);  // harmonic mean
    EXPECT_EQ(table.thermal(0, 2).conductance, 0.0f);
    EXPECT_FLOAT_EQ(table.thermal(0, 2).tSolid, 40);  // the one with phases gives its range
}

TEST(Thermal, GridLoopMatchesTheAllPairsReference) {
    MaterialSettings other = wax("b");
    other.tSolid = 20;
    other.tLiquid = 90;
    other.liquid.b1 = 1.5;
    other.conductivity = 2;
    // The pair of the two with exponents of its own (10, 3): the loop that evaluates each
    // pair once then calls each pair's kernels through pointers, not by name.
    MaterialPairSettings ownExponents;
    ownExponents.a = "a";
    ownExponents.b = "b";
    ownExponents.m = 10;
    for (int variant = 0; variant < 4; ++variant) {
        const bool uniformRadius = variant % 2 == 1, shared = variant < 2;
        const PairTable table({wax("a"), other},
                              shared ? std::vector<MaterialPairSettings>{}
                                     : std::vector<MaterialPairSettings>{ownExponents});
        SCOPED_TRACE(std::string(uniformRadius ? "uniform radius" : "two radii") +
                     (shared ? "" : ", a pair with exponents of its own"));
        const Globules reference = warmCloud(600, 5, true, uniformRadius);
        Accelerations exact;
        pairForcesThermalAllPairs(reference, table, exact);
        Globules sorted = reference;
        NeighborWorkspace workspace;
        Accelerations grid;
        pairForcesThermal(sorted, table, workspace, grid);
        std::size_t checked = 0;
        for (std::size_t k = 0; k < sorted.size(); ++k) {
            const std::size_t i = std::size_t(sorted.id[k]);
            ASSERT_EQ(sorted.temperature[k], reference.temperature[i]);
            const double scale =
                1 + std::abs(exact.x[i]) + std::abs(exact.y[i]) + std::abs(exact.z[i]);
            EXPECT_NEAR(grid.x[k], exact.x[i], 1e-4 * scale) << k;
            EXPECT_NEAR(grid.y[k], exact.y[i], 1e-4 * scale) << k;
            EXPECT_NEAR(grid.z[k], exact.z[i], 1e-4 * scale) << k;
            EXPECT_NEAR(grid.heat[k], exact.heat[i], 1e-4 * (1 + std::abs(exact.heat[i]))) << k;
            checked += exact.heat[i] != 0;
        }
        EXPECT_GT(checked, 500u);
    }
}

// Crowded cells (about 180 globules a cell group, split in parts), cut at other places by
// other thread counts' ranges and by a small grain (a few globules per task): the heat and
// the forces are the same bits, also where (a uniform radius, AVX-512) they are summed in
// the candidates' lanes, which follow the cell's group.
TEST(Thermal, CrowdedCellsGiveTheSameBitsOnAnyThreadCount) {
    MaterialSettings other = wax("b");
    other.tSolid = 20;
    other.tLiquid = 90;
    other.conductivity = 2;
    for (int variant = 0; variant < 4; ++variant) {
        const bool two = variant % 2 == 1, uniformRadius = variant >= 2;
        const PairTable table = two ? PairTable({wax("a"), other}, {}) : PairTable({other}, {});
        const Globules cloud = warmCloud(3000, 9, two, uniformRadius);
        std::vector<Accelerations> byThreads;
        std::vector<std::string> runs;
        for (std::size_t grain : {std::size_t(256), std::size_t(5)}) {
            for (std::size_t threads : {1u, 2u, 3u, 4u}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
                Globules sorted = cloud;
                NeighborWorkspace workspace;
                workspace.grain = grain;
                Accelerations forces;
                pairForcesThermal(sorted, table, workspace, forces);
                byThreads.push_back(forces);
                runs.push_back(std::to_string(threads) + " threads, grain " + std::to_string(grain));
            }
        }
        for (std::size_t t = 1; t < byThreads.size(); ++t) {
            SCOPED_TRACE(runs[t] + (two ? ", two materials" : "") +
                         (uniformRadius ? ", uniform radius" : ""));
            EXPECT_EQ(byThreads[t].heat, byThreads[0].heat);
            EXPECT_EQ(byThreads[t].x, byThreads[0].x);
            EXPECT_EQ(byThreads[t].z, byThreads[0].z);
        }
    }
}

/// Two materials with temperatures, thrown at each other, weightless and off the ground.
SimulationSetup warmSauces() {
    SimulationSetup setup;
    setup.ground.enabled = false;
    setup.simulation.gravity = {0, 0, 0};
    setup.thermal = thermalOn();
    setup.material = wax("ketchup");
    setup.otherMaterials = {wax("mustard")};
    setup.otherMaterials[0].heatCapacity = 2;
    EmitterSettings left, right;
    for (EmitterSettings* e : {&left, &right}) {
        e->type = "box";
        e->count = 0;
        e->spacing = 1.0;
        e->min = {-3, 0, -1.5};
        e->max = {0, 3, 1.5};
        e->velocity = {1.5, 0, 0};
        e->temperature = 20;
    }
    right.min = {0.5, 0, -1.5};
    right.max = {3.5, 3, 1.5};
    right.velocity = {-2.5, 0.5, 0};
    right.material = "mustard";
    right.temperature = 90;
    right.mass = 2;
    setup.emitters = {left, right};
    return setup;
}

TEST(Thermal, MomentumAndHeatAreConservedWithTwoMaterials) {
    const SimulationSetup setup = warmSauces();
    Simulation sim(setup);
    NullReporter quiet;
    const auto [before, scale] = momentumOf(sim.globules());
    const double heat = totalHeat(sim.globules(), setup.materials());
    for (int f = 2; f <= 26; ++f) sim.advanceFrame(f, quiet);
    EXPECT_LT(length(momentumOf(sim.globules()).first - before), 1e-4 * scale);
    EXPECT_NEAR(totalHeat(sim.globules(), setup.materials()), heat, 1e-5 * heat);
    // They met: the cold ketchup took heat from the hot mustard.
    float warmest = 0;
    const Globules& g = sim.globules();
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (g.material[i] == 0) warmest = std::max(warmest, g.temperature[i]);
    }
    EXPECT_GT(warmest, 25.0f);
}

TEST(Thermal, BuoyancyLiftsHotGlobulesAndSinksColdOnes) {
    MaterialSettings m;
    m.expansion = 0.05;
    ThermalSettings t = thermalOn();
    t.reference = 20;
    const std::vector<MaterialSettings> materials = {m};
    GroundSettings ground;
    ground.enabled = false;
    ForceField field(PairTable(materials, {}),
                     ExternalForces{{0, -10, 0}, ground, ColliderSet(),
                                    ThermalSources(t, {}, materials, {0, -10, 0}, ground)});
    Globules g;
    g.add({0, 0, 0}, {0, 0, 0}, 0.5f, 2.0f, 0);
    g.add({50, 0, 0}, {0, 0, 0}, 0.5f, 1.0f, 1);
    g.temperature = {60, 20};
    Accelerations a;
    field.compute(g, a);
    const std::size_t hot = g.id[0] == 0 ? 0 : 1;
    EXPECT_FLOAT_EQ(a.y[hot], -10.0f + 0.05f * 40 * 10);  // -g - beta (T - T_ref) g
    EXPECT_FLOAT_EQ(a.y[1 - hot], -10.0f);
}

/// A solid block resting on a hot plate (the ground).
SimulationSetup blockOnHotPlate() {
    SimulationSetup setup;
    setup.thermal = thermalOn();
    setup.thermal.groundTemperature = 150;
    setup.thermal.groundTransfer = 8;
    setup.material = wax();
    setup.material.conductivity = 4;
    EmitterSettings block;
    block.type = "box";
    block.count = 0;
    block.radius = 0.5;
    block.spacing = 0.95;
    block.min = {-1.5, 0.5, -1.5};
    block.max = {1.5, 4.5, 1.5};
    block.temperature = 20;
    setup.emitters = {block};
    return setup;
}

TEST(Thermal, ABlockOnAHotPlateHeatsUpAndSlumps) {
    Simulation sim(blockOnHotPlate());
    NullReporter quiet;
    const auto measure = [&] {
        const Globules& g = sim.globules();
        std::vector<float> y(g.py);
        std::sort(y.begin(), y.end());
        double t = 0;
        for (float x : g.temperature) t += x;
        return std::pair{double(y[y.size() * 95 / 100]), t / double(g.size())};
    };
    for (int f = 2; f <= 13; ++f) sim.advanceFrame(f, quiet);  // settles as a solid
    const auto [settled, cool] = measure();
    EXPECT_LT(cool, 40.0);  // still solid
    double lastHeight = settled, lastTemperature = cool;
    for (int f = 14, round = 0; round < 3; ++round) {
        for (int end = f + 25; f < end; ++f) sim.advanceFrame(f, quiet);
        const auto [height, temperature] = measure();
        EXPECT_GT(temperature, lastTemperature) << round;
        lastHeight = std::min(lastHeight, height);
        lastTemperature = temperature;
    }
    EXPECT_GT(lastTemperature, 60.0);  // melted through
    EXPECT_LT(lastHeight, 0.75 * settled);  // and slumped
}

TEST(Thermal, ResultsAreIdenticalForAnyThreadCountAndOnResume) {
    SimulationSetup setup = warmSauces();
    setup.simulation.integrator = "velocity_verlet";  // carries its heating rates
    const SimulationState one = stateAfter(setup, 1, 10), two = stateAfter(setup, 2, 10);
    EXPECT_EQ(one.globules.px, two.globules.px);
    EXPECT_EQ(one.globules.temperature, two.globules.temperature);
    // Resumed from a checkpoint written at frame 5.
    const auto file = std::filesystem::temp_directory_path() / "globular_thermal_resume.state";
    Checkpoint saved;
    saved.frame = 5;
    saved.state = stateAfter(setup, 2, 5);
    writeCheckpoint(file, saved);
    const Checkpoint read = readCheckpoint(file);
    std::filesystem::remove(file);
    Simulation resumed(setup);
    resumed.restoreState(read.state);
    NullReporter quiet;
    for (int f = 6; f <= 10; ++f) resumed.advanceFrame(f, quiet);
    EXPECT_EQ(resumed.saveState().globules.px, one.globules.px);
    EXPECT_EQ(resumed.saveState().globules.temperature, one.globules.temperature);
    // Temperatures do not fit a scene without them, nor the reverse.
    SimulationSetup cold = setup;
    cold.thermal.enabled = false;
    Simulation plain(cold);
    EXPECT_THROW(plain.restoreState(one), Error);
    Simulation warm(setup);
    EXPECT_THROW(warm.restoreState(stateAfter(cold, 1, 2)), Error);
}

}  // namespace
