// Adaptive time stepping (stable_step.h, simulation.adaptive): the bound against the exact
// stability limit of semi-implicit Euler, and adaptive runs against fixed-dt runs.
#include "stable_step.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <random>
#include <vector>

#include "reporter.h"
#include "simulation.h"
#include "simulation_runs.h"

using namespace globular;

namespace {

/// The spectral radius of one semi-implicit Euler step of x'' = -c x' - w2 x:
/// v' = v + dt (-c v - w2 x), x' = x + dt v'.
double spectralRadius(double c, double w2, double dt) {
    // [v'; x'] = A [v; x], A = [[1 - c dt, -w2 dt], [dt (1 - c dt), 1 - w2 dt^2]].
    const double a = 1 - c * dt, b = -w2 * dt, cc = dt * (1 - c * dt), d = 1 - w2 * dt * dt;
    const double trace = a + d, det = a * d - b * cc;
    const std::complex<double> root = std::sqrt(std::complex<double>(trace * trace - 4 * det));
    return std::max(std::abs((trace + root) / 2.0), std::abs((trace - root) / 2.0));
}

SimulationSetup groundOnly(double ks, double kd) {
    SimulationSetup setup;
    setup.ground.ks = ks;
    setup.ground.kd = kd;
    EmitterSettings one;
    one.count = 1;
    setup.emitters = {one};
    return setup;
}

/// A liquid drop of @p count globules falling onto the ground.
SimulationSetup drop(int count, bool adaptive, double dt) {
    SimulationSetup setup;
    setup.simulation.integrator = "semi_implicit_euler";
    setup.simulation.adaptive = adaptive;
    setup.simulation.dt = dt;
    EmitterSettings box;
    box.type = "box";
    box.spacing = 1.0;
    box.count = count;
    const double side = std::cbrt(double(count)) + 0.5;
    box.min = {0, 2, 0};
    box.max = {side, 2 + side, side};
    setup.emitters = {box};
    return setup;
}

/// Points in a block of 24^3 cubes of edge @p cell, some below zero, @p each in every cube
/// at random places inside it and @p crowded more in the cube (5, -3, 7).
std::vector<std::array<float, 3>> latticeOfCubes(double cell, int each, int crowded) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> inside(0.05, 0.95);
    std::vector<std::array<float, 3>> points;
    const auto addIn = [&](int i, int j, int k) {
        points.push_back({float((i + inside(random)) * cell), float((j + inside(random)) * cell),
                          float((k + inside(random)) * cell)});
    };
    for (int i = -12; i < 12; ++i) {
        for (int j = -12; j < 12; ++j) {
            for (int k = -12; k < 12; ++k) {
                for (int e = 0; e < each; ++e) addIn(i, j, k);
            }
        }
    }
    for (int e = 0; e < crowded; ++e) addIn(5, -3, 7);
    return points;
}

uint32_t mostOf(const std::vector<std::array<float, 3>>& points, double cell) {
    std::vector<float> x, y, z;
    for (const auto& p : points) {
        x.push_back(p[0]);
        y.push_back(p[1]);
        z.push_back(p[2]);
    }
    CrowdedCell count;
    return count.most(x.data(), y.data(), z.data(), points.size(), cell);
}

Vec3 centroidOf(const Globules& g) {
    Vec3 c{0, 0, 0};
    for (std::size_t i = 0; i < g.size(); ++i) c = c + g.position(i);
    return (1.0 / double(g.size())) * c;
}

}  // namespace

TEST(StableStep, GroundAloneGivesTheOscillatorsBound) {
    const double ks = 5000, kd = 300, mass = 2;
    const StableStep stable(groundOnly(ks, kd));
    const double c = kd / mass, w2 = ks / mass;
    const double expected = 4 / (c + std::sqrt(c * c + 4 * w2));
    EXPECT_NEAR(stable.contactBound(0, mass, 0.5, 1), expected, 1e-12 * expected);
}

TEST(StableStep, TheBoundIsSemiImplicitEulersExactStabilityLimit) {
    // Damped and nearly undamped springs: the step's spectral radius reaches 1 at the bound.
    for (const auto& [ks, kd] : {std::pair{5000.0, 300.0}, {5000.0, 1.0}, {100.0, 50.0}}) {
        const StableStep stable(groundOnly(ks, kd));
        const double mass = 1, bound = stable.contactBound(0, mass, 0.5, 1);
        EXPECT_LE(spectralRadius(kd, ks, bound * (1 - 1e-6)), 1 + 1e-12) << ks << " " << kd;
        EXPECT_GT(spectralRadius(kd, ks, bound * (1 + 1e-3)), 1) << ks << " " << kd;
    }
}

TEST(StableStep, DenserMediaAndFasterGlobulesShortenTheStep) {
    StableStep stable(drop(8, true, 0.01));
    const double sparse = stable.contactBound(0.05, 1, 0.5, 1);
    const double dense = stable.contactBound(0.5, 1, 0.5, 1);
    EXPECT_LT(dense, sparse);
    Globules g;
    g.add({0, 5, 0}, {0, 0, 0}, 0.5f, 1, 0);  // far apart: the ground alone
    g.add({20, 5, 0}, {50, 0, 0}, 0.5f, 1, 1);
    const StableStep::Bound fast = stable.bound(g);
    // The fastest crosses a tenth of the smallest radius in one step.
    EXPECT_NEAR(fast.speed, StableStep::kSpeedFraction * 0.5 / 50, 1e-12);
    EXPECT_DOUBLE_EQ(fast.step(), StableStep::kSafety * std::min(fast.speed, fast.contact));
}

TEST(CrowdedCell, CountsTheMostCrowdedCubeExactly) {
    // 13 824 cubes of 3 points and one of 3 + 4: a count merged with any other cube's shows.
    const double cell = 3.5;
    const auto points = latticeOfCubes(cell, 3, 4);
    EXPECT_EQ(mostOf(points, cell), 7u);
    EXPECT_EQ(mostOf(latticeOfCubes(cell, 3, 0), cell), 3u);
    // Cubes twice as wide hold 8 of the small ones.
    EXPECT_EQ(mostOf(points, 2 * cell), 8u * 3 + 4);
}

TEST(CrowdedCell, TheCountDoesNotDependOnTheOrder) {
    auto points = latticeOfCubes(1.0, 2, 9);
    const uint32_t inOrder = mostOf(points, 1.0);
    std::shuffle(points.begin(), points.end(), std::mt19937(3));
    EXPECT_EQ(mostOf(points, 1.0), inOrder);
    std::reverse(points.begin(), points.end());
    EXPECT_EQ(mostOf(points, 1.0), inOrder);
}

TEST(CrowdedCell, NonFiniteAndFarPointsShareCubesAndNeverLowerTheCount) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    CrowdedCell count;
    const std::vector<float> x{nan, 0.5f, 0.2f, 1e30f, inf, 2e30f}, y{0, 0.5f, nan, 0, 0, 0},
        z{0, 0.5f, 0.3f, 0, 0, 0};
    // Cube 0 holds the point at (0.5, 0.5, 0.5) and the two with a NaN coordinate; the
    // three far ones share the outermost cube in x.
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 3, 1.0), 3u);
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 6, 1.0), 3u);
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 0, 1.0), 0u);
}

TEST(CrowdedCell, RunsAcrossChunksAndCallsAddUp) {
    // 70 000 points in one cube come in runs cut by the parallel chunks; a second call on
    // the same table must not see the first's counts, a third none of the second's.
    const std::size_t n = 70000;
    std::vector<float> x(n), y(n, 0.25f), z(n, 0.75f);
    for (std::size_t i = 0; i < n; ++i) x[i] = float(i % 1000) / 1000.0f;  // all in [0, 1)
    CrowdedCell count;
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), n, 1.0), n);
    // Alternate cubes 0 and 1 along x: runs of one point, the two cubes counted apart.
    for (std::size_t i = 0; i < n; ++i) x[i] = i % 2 ? 1.5f : 0.5f;
    x[0] = 1.25f;  // cube 1 gets one more
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), n, 1.0), n / 2 + 1);
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 10, 1.0), 6u);
}

TEST(CrowdedCell, CubesAreFlooredExactlyOnBothSidesOfZero) {
    // Cube k is [k cell, (k + 1) cell): a point on a negative boundary belongs to the cube
    // above it, one a hair below to the cube below.
    const double cell = 3.5;
    const std::vector<float> x{-3.5f, -3.4999998f, -0.0f, 0.0f, -7.0f, std::nextafter(-3.5f, -4.0f)},
        y(6, 1.0f), z(6, 1.0f);
    CrowdedCell count;
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 2, cell), 2u);  // both in cube -1
    EXPECT_EQ(count.most(x.data() + 2, y.data(), z.data(), 2, cell), 2u);  // both in cube 0
    // -7 lies in cube -2, as does the hair below -3.5: with -3.5 and -3.4999998 in cube
    // -1, every cube holds two.
    EXPECT_EQ(count.most(x.data(), y.data(), z.data(), 6, cell), 2u);
}

TEST(StableStep, TheContactBoundFollowsTheDensestCellsTrueCount) {
    // A block of cells of 3 globules with one of 3 + 4: the bound is that of 7 per cell.
    SimulationSetup setup = drop(8, true, 0.01);
    StableStep stable(setup);
    // Cells one search reach wide: the reach in r_i + r_j, for radius 1.
    const double cell = 2.0 * PairTable(setup.materials(), setup.materialPairs).cutoff(1.0f);
    Globules g;
    for (const auto& p : latticeOfCubes(cell, 3, 4)) g.add({p[0], p[1], p[2]}, {0, 0, 0}, 1.0f, 1, 0);
    const double expected = stable.contactBound(7 / (cell * cell * cell), 1, 1, 1);
    EXPECT_NEAR(stable.bound(g).contact, expected, 1e-12 * expected);
}

TEST(AdaptiveStepping, FramesEndOnTheirInstantsWithFewerSteps) {
    const SimulationSetup adaptive = drop(125, true, 0.01), fixed = drop(125, false, 0.001);
    Simulation a(adaptive), f(fixed);
    NullReporter quiet;
    for (int frame = 2; frame <= 30; ++frame) {
        a.advanceFrame(frame, quiet);
        f.advanceFrame(frame, quiet);
        EXPECT_EQ(a.time(), f.time()) << "frame " << frame;
    }
    EXPECT_EQ(f.stepCount(), 29 * 40);
    EXPECT_LT(a.stepCount(), f.stepCount() / 2);
}

TEST(AdaptiveStepping, ADropComesToRestWhereTheFixedStepPutsIt) {
    // 4 s: the drop lands, spreads and settles; the rest state is the physics', not the step's.
    const Globules a = stateAfter(drop(125, true, 0.01), 2, 100).globules;
    const Globules f = stateAfter(drop(125, false, 0.001), 2, 100).globules;
    ASSERT_EQ(a.size(), f.size());
    const Vec3 ca = centroidOf(a), cf = centroidOf(f);
    EXPECT_NEAR(ca.y, cf.y, 0.02);  // world units; a globule's radius is 0.5
    EXPECT_NEAR(ca.x, cf.x, 0.05);
    EXPECT_NEAR(ca.z, cf.z, 0.05);
    double fastest = 0;
    for (std::size_t i = 0; i < a.size(); ++i) fastest = std::max(fastest, length(a.velocity(i)));
    EXPECT_LT(fastest, 0.5);  // at rest, not jittering
}

TEST(AdaptiveStepping, MomentumIsConservedWithoutExternalForces) {
    // No ground, no gravity: two drops collide; each pair's forces cancel.
    SimulationSetup setup = drop(64, true, 0.01);
    setup.ground.enabled = false;
    setup.simulation.gravity = {0, 0, 0};
    EmitterSettings other = setup.emitters[0];
    other.min = {6, 2, 0};
    other.max = {10, 6, 4};
    other.velocity = {-8, 0, 0};
    setup.emitters.push_back(other);
    Simulation sim(setup);
    const auto [before, scale] = momentumOf(sim.globules());
    NullReporter quiet;
    for (int f = 2; f <= 25; ++f) sim.advanceFrame(f, quiet);
    const auto [after, unused] = momentumOf(sim.globules());
    EXPECT_LT(length(after - before), 1e-4 * scale);
}

TEST(AdaptiveStepping, SameBitsOnAnyThreadCountAndWhenResumed) {
    const SimulationSetup setup = drop(216, true, 0.01);
    const SimulationState one = stateAfter(setup, 1, 20), two = stateAfter(setup, 2, 20);
    EXPECT_EQ(one.globules.px, two.globules.px);
    EXPECT_EQ(one.globules.vy, two.globules.vy);
    EXPECT_EQ(one.steps, two.steps);

    NullReporter quiet;
    Simulation first(setup);
    for (int f = 2; f <= 10; ++f) first.advanceFrame(f, quiet);
    Simulation resumed(setup);
    resumed.restoreState(first.saveState());
    for (int f = 11; f <= 20; ++f) resumed.advanceFrame(f, quiet);
    EXPECT_EQ(resumed.globules().px, two.globules.px);
    EXPECT_EQ(resumed.globules().vy, two.globules.vy);
    EXPECT_EQ(resumed.stepCount(), two.steps);
}
