#include "simulation.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "errors.h"
#include "recording_reporter.h"
#include "reporter.h"

using namespace globular;

namespace {

SimulationSetup liquidHelix(int count, const std::string& integrator = "forward_euler") {
    SimulationSetup setup;
    setup.simulation.integrator = integrator;
    EmitterSettings helix;
    helix.count = count;
    setup.emitters = {helix};
    return setup;
}

Globules runFrames(const SimulationSetup& setup, int frames) {
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= frames; ++f) sim.advanceFrame(f, quiet);
    return sim.globules();
}

void expectIdentical(const Globules& a, const Globules& b) {
    EXPECT_EQ(a.px, b.px);
    EXPECT_EQ(a.py, b.py);
    EXPECT_EQ(a.pz, b.pz);
    EXPECT_EQ(a.vx, b.vx);
    EXPECT_EQ(a.vy, b.vy);
    EXPECT_EQ(a.vz, b.vz);
    EXPECT_EQ(a.id, b.id);
}

}  // namespace

TEST(Simulation, IdenticalResultsForOneAndTwoThreads) {
    SimulationSetup setup = liquidHelix(600);
    EmitterSettings spout;
    spout.type = "spout";
    spout.count = 300;
    spout.center = {8, 10, 0};
    setup.emitters.push_back(spout);
    Globules one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = runFrames(setup, 6);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = runFrames(setup, 6);
    }
    ASSERT_GT(one.size(), 600u);
    expectIdentical(one, two);
}

TEST(Simulation, GridAndAllPairsAgree) {
    SimulationSetup grid = liquidHelix(200), allPairs = liquidHelix(200);
    allPairs.simulation.neighbors = "all_pairs";
    const Globules a = runFrames(grid, 4), b = runFrames(allPairs, 4);
    ASSERT_EQ(a.size(), b.size());
    // The grid keeps the globules in its own order: match them by id.
    std::vector<std::size_t> indexOfId(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) indexOfId[std::size_t(b.id[i])] = i;
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a.py[i], b.py[indexOfId[std::size_t(a.id[i])]], 1e-3) << "id " << a.id[i];
    }
}

TEST(Simulation, GlobulesFallAndComeToRestOnTheGround) {
    SimulationSetup setup = liquidHelix(40);
    const Globules g = runFrames(setup, 100);  // 4 s
    for (std::size_t i = 0; i < g.size(); ++i) {
        EXPECT_GT(g.py[i], -1.0f);
        EXPECT_LT(g.py[i], 6.0f);
    }
}

TEST(Simulation, SavedStateResumesBitForBit) {
    for (const char* integrator : {"forward_euler", "velocity_verlet"}) {
        SimulationSetup setup = liquidHelix(100, integrator);
        EmitterSettings spout;
        spout.type = "spout";
        spout.count = 200;
        spout.center = {6, 8, 0};
        setup.emitters.push_back(spout);
        NullReporter quiet;
        Simulation whole(setup);
        for (int f = 2; f <= 10; ++f) whole.advanceFrame(f, quiet);

        Simulation first(setup);
        for (int f = 2; f <= 5; ++f) first.advanceFrame(f, quiet);
        const SimulationState saved = first.saveState();
        Simulation resumed(setup);
        resumed.restoreState(saved);
        for (int f = 6; f <= 10; ++f) resumed.advanceFrame(f, quiet);
        expectIdentical(whole.globules(), resumed.globules());
        EXPECT_EQ(whole.stepCount(), resumed.stepCount());
    }
}

TEST(Simulation, ExplosionStopsNamingFrameStepAndCause) {
    SimulationSetup setup = liquidHelix(40);
    setup.emitters[0].spacing = 0.05;  // globules start nearly on top of each other
    setup.emitters[0].helixRadius = 0.02;
    setup.simulation.dt = 0.01;
    setup.simulation.fps = 25;
    Simulation sim(setup);
    NullReporter quiet;
    try {
        sim.advanceFrame(2, quiet);
        FAIL() << "expected an explosion";
    } catch (const SimulationError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("frame 2"), std::string::npos) << message;
        EXPECT_NE(message.find("step"), std::string::npos) << message;
        EXPECT_NE(message.find("try dt"), std::string::npos) << message;
    }
}

TEST(Simulation, SubstepModeRetriesBeforeGivingUp) {
    RecordingReporter reporter;
    SimulationSetup setup = liquidHelix(40);
    setup.emitters[0].spacing = 0.05;
    setup.emitters[0].helixRadius = 0.02;
    setup.simulation.onExplosion = "substep";
    setup.simulation.dt = 0.01;
    Simulation sim(setup);
    EXPECT_THROW(sim.advanceFrame(2, reporter), SimulationError);
    EXPECT_GE(reporter.warnings.size(), 3u);  // 2x, 4x, ... retries were reported
}
