// Dynamic colliders (issue 13): mass properties against the exact ones, free flight and
// spin against the analytic motion, linear momentum exchanged with the globules and not
// made or lost, and bit-identical results for any thread count and on resume.

#include "rigid_body.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>

#include "collider_solid.h"
#include "reporter.h"
#include "simulation.h"
#include "simulation_runs.h"

using namespace globular;

namespace {

ColliderSettings ball(double radius, double mass) {
    ColliderSettings c;
    c.name = "ball";
    c.shape = "sphere";
    c.radius = radius;
    c.dynamic = true;
    c.mass = mass;
    return c;
}

TEST(RigidBody, MassPropertiesMatchTheExactOnes) {
    const ColliderSettings sphere = ball(2, 10);
    const RigidBody s(sphere, ColliderSolid(sphere, {}, 1));
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(s.inertia()[a][a], 0.4 * 10 * 4, 0.01 * 16) << a;  // 2/5 m r^2
        EXPECT_NEAR(s.inertia()[a][(a + 1) % 3], 0, 1e-9);
    }
    EXPECT_NEAR(length(s.centreOfMass()), 0, 1e-9);
    ColliderSettings box = ball(1, 6);
    box.shape = "box";
    box.center = {1, 2, 3};
    box.size = {1, 2, 3};
    const RigidBody b(box, ColliderSolid(box, {}, 1));
    // m (b^2 + c^2) / 12, to the grid's midpoint rule (1 / 64^2 relative).
    EXPECT_NEAR(b.inertia()[0][0], 6.0 / 12 * (4 + 9), 5e-4 * 6.5);
    EXPECT_NEAR(b.inertia()[1][1], 6.0 / 12 * (1 + 9), 5e-4 * 5);
    EXPECT_NEAR(b.inertia()[2][2], 6.0 / 12 * (1 + 4), 5e-4 * 2.5);
    EXPECT_NEAR(length(b.centreOfMass() - box.center), 0, 1e-9);
    // A cup's centre of mass: the wall's and the bottom's, weighted by their volumes.
    ColliderSettings cup = ball(1, 1);
    cup.shape = "cup";
    cup.radius = 2;
    cup.height = 4;
    cup.thickness = 0.5;
    const RigidBody c(cup, ColliderSolid(cup, {}, 1));
    const double wall = M_PI * (4 - 1.5 * 1.5) * 3.5, bottom = M_PI * 4 * 0.5;
    const double y = (wall * (0.5 + 1.75) + bottom * 0.25) / (wall + bottom);
    EXPECT_NEAR(c.centreOfMass().y, y, 0.01 * y);
    EXPECT_NEAR(c.centreOfMass().x, 0, 1e-9);
}

SimulationSetup emptySetup() {
    SimulationSetup setup;
    setup.ground.enabled = false;
    return setup;
}

TEST(RigidBody, FallsFreelyAndSpinsAsTheAnalyticMotion) {
    SimulationSetup setup = emptySetup();
    ColliderSettings body = ball(1, 5);
    body.shape = "box";
    body.size = {1, 1, 1};
    body.center = {0, 10, 0};
    body.velocity = {3, 0, 0};
    body.angularVelocity = {0, 90, 0};  // a quarter turn a second about y
    setup.colliders = {body};
    setup.simulation.integrator = "velocity_verlet";
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= 26; ++f) sim.advanceFrame(f, quiet);  // 1 s at 25 fps
    const RigidBody& b = sim.colliders().bodies()[0];
    // Constant acceleration: velocity Verlet is exact up to rounding (the step is a float).
    EXPECT_NEAR(b.state.position.x, 3, 1e-6);
    EXPECT_NEAR(b.state.position.y, 10 - 0.5 * 9.8, 1e-5);
    EXPECT_NEAR(b.state.velocity.y, -9.8, 1e-5);
    // A cube's inertia is isotropic: it turns steadily about y, local x to world -z.
    const Vec3 x = b.pose().rotate({1, 0, 0});
    EXPECT_NEAR(x.x, 0, 1e-6);
    EXPECT_NEAR(x.z, -1, 1e-6);
    // Where the frame put it: the poses file's translation puts local (0, 10, 0) there.
    EXPECT_NEAR(length(b.pose().toWorld(body.center) - b.state.position), 0, 1e-9);
}

TEST(RigidBody, LandsOnTheGroundAndComesToRest) {
    SimulationSetup setup;  // the ground on, at y = 0, no globules
    ColliderSettings ball = ::ball(1.5, 150);
    ball.center = {0, 4, 0};
    ColliderSettings box = ::ball(1, 20);
    box.shape = "box";
    box.size = {2, 1, 2};
    box.center = {5, 3, 0};
    setup.colliders = {ball, box};
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= 76; ++f) sim.advanceFrame(f, quiet);  // 3 s
    const RigidBody& b = sim.colliders().bodies()[0];
    // Each surface point carries the ground's k_s per unit mass on its share: a sphere
    // sinks until the cap below the ground carries its weight, depth sqrt(4 R g / k_s)
    // (the cap holds a fraction d / 2R of the points, at mean depth d / 2).
    const double sink = std::sqrt(4 * 1.5 * 9.8 / 5000);
    EXPECT_NEAR(b.state.position.y, 1.5 - sink, 0.3 * sink);
    EXPECT_LT(length(b.state.velocity), 1e-3);
    EXPECT_LT(length(b.angularVelocity()), 1e-3);
    // A box lands flat on its bottom face, a sixth of its surface: depth about 6 g / k_s.
    const RigidBody& flat = sim.colliders().bodies()[1];
    EXPECT_NEAR(flat.state.position.y, 0.5, 0.05);
    EXPECT_LT(length(flat.state.velocity), 1e-3);
    EXPECT_NEAR(flat.pose().rotate({0, 1, 0}).y, 1, 1e-6);  // still upright
}

/// A block of the paper's solid at rest, weightless, and a ball fired into it.
SimulationSetup projectileIntoBlock() {
    SimulationSetup setup = emptySetup();
    setup.simulation.gravity = {0, 0, 0};
    setup.material.preset = "solid";
    EmitterSettings block;
    block.type = "box";
    block.count = 0;
    block.min = {-2, -2, -2};
    block.max = {2, 2, 2};
    block.spacing = 1.0;
    block.jitter = 0;
    setup.emitters = {block};
    ColliderSettings projectile = ball(1.0, 20);
    projectile.center = {-6, 0.3, 0.2};
    projectile.velocity = {15, 0, 0};
    projectile.angularVelocity = {0, 0, 200};
    projectile.friction = 0.3;  // a torque on the ball as well
    setup.colliders = {projectile};
    return setup;
}

Vec3 totalMomentum(const Simulation& sim) {
    const Globules& g = sim.globules();
    Vec3 p{0, 0, 0};
    for (std::size_t i = 0; i < g.size(); ++i) p = p + double(g.mass[i]) * g.velocity(i);
    const RigidBody& b = sim.colliders().bodies()[0];
    return p + b.mass() * b.state.velocity;
}

TEST(RigidBody, LinearMomentumIsExchangedNotMadeOrLost) {
    const SimulationSetup setup = projectileIntoBlock();
    Simulation sim(setup);
    NullReporter quiet;
    const Vec3 before = totalMomentum(sim);
    double largestError = 0, lowestBallSpeed = 15;
    for (int f = 2; f <= 26; ++f) {
        sim.advanceFrame(f, quiet);
        largestError = std::max(largestError, length(totalMomentum(sim) - before) / length(before));
        lowestBallSpeed = std::min(lowestBallSpeed, sim.colliders().bodies()[0].state.velocity.x);
    }
    EXPECT_LT(largestError, 1e-4);
    // It did hit: the ball lost speed to the block, which moves on with it.
    EXPECT_LT(lowestBallSpeed, 14);
    double blockMomentum = 0;
    for (std::size_t i = 0; i < sim.globules().size(); ++i) blockMomentum += sim.globules().vx[i];
    EXPECT_GT(blockMomentum, 10);
}

TEST(RigidBody, ResultsAreIdenticalForAnyThreadCountAndOnResume) {
    SimulationSetup setup = projectileIntoBlock();
    ColliderSettings wall;  // and a keyframed collider beside the body
    wall.name = "wall";
    wall.shape = "plane";
    wall.normal = {0, 1, 0};
    wall.center = {0, -2.5, 0};
    ColliderKey k0, k1;
    k1.time = 1;
    k1.position = {0, 1, 0};
    wall.keys = {k0, k1};
    setup.colliders.push_back(wall);
    const auto run = [&](int threads, int frames) { return stateAfter(setup, threads, frames); };
    const SimulationState one = run(1, 16), two = run(2, 16);
    EXPECT_EQ(one.globules.px, two.globules.px);
    ASSERT_EQ(one.bodies.size(), 1u);
    EXPECT_EQ(one.bodies[0].position, two.bodies[0].position);
    EXPECT_EQ(one.bodies[0].angularMomentum, two.bodies[0].angularMomentum);
    Simulation resumed(setup);
    resumed.restoreState(run(2, 8));
    NullReporter quiet;
    for (int f = 9; f <= 16; ++f) resumed.advanceFrame(f, quiet);
    const SimulationState again = resumed.saveState();
    EXPECT_EQ(again.globules.px, one.globules.px);
    EXPECT_EQ(again.bodies[0].position, one.bodies[0].position);
    EXPECT_EQ(again.bodies[0].orientation, one.bodies[0].orientation);
    EXPECT_EQ(again.bodies[0].force, one.bodies[0].force);
}

}  // namespace
