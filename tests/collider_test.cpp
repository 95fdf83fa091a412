// Colliders (issue 13): each shape's signed distance and normal against exact values, the
// contact force against the ground's, friction on an incline against tan(theta) vs mu,
// and containers that lose no globule at the paper's dt.

#include "collider.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <tbb/global_control.h>

#include "collider_contact.h"
#include "collider_solid.h"
#include "forces.h"
#include "reporter.h"
#include "simulation.h"

using namespace globular;

namespace {

SurfaceSample sampleCollider(const ColliderSettings& c, Vec3 p) {
    return ColliderSolid(c, {}, 1).sample(p);
}

SurfaceSample sampleCollider(const ColliderSettings& c, const ColliderMotion& motion, Vec3 p) {
    const ColliderSolid solid(c, {}, 1);
    return PlacedSolid{&solid, motion.now}.sample(p);
}

ColliderSettings shape(const std::string& name) {
    ColliderSettings c;
    c.shape = name;
    return c;
}

void expectSample(const ColliderSettings& c, Vec3 p, double phi, Vec3 normal) {
    const SurfaceSample s = sampleCollider(c, p);
    EXPECT_NEAR(s.phi, phi, 1e-12) << c.shape << " at " << p.x << " " << p.y << " " << p.z;
    EXPECT_NEAR(s.normal.x, normal.x, 1e-12) << c.shape;
    EXPECT_NEAR(s.normal.y, normal.y, 1e-12) << c.shape;
    EXPECT_NEAR(s.normal.z, normal.z, 1e-12) << c.shape;
}

TEST(ColliderShapes, PlaneSphereBoxCylinderCupMatchExactValues) {
    ColliderSettings plane = shape("plane");
    plane.center = {0, 1, 0};
    plane.normal = {0, 2, 0};
    expectSample(plane, {3, 4, 5}, 3, {0, 1, 0});
    expectSample(plane, {3, 0.5, 5}, -0.5, {0, 1, 0});

    ColliderSettings sphere = shape("sphere");
    sphere.radius = 2;
    expectSample(sphere, {0, 3, 0}, 1, {0, 1, 0});
    expectSample(sphere, {0, 0, -0.5}, -1.5, {0, 0, -1});
    sphere.inside = true;  // a spherical container: its wall is outward of the globules
    expectSample(sphere, {0, 0, -0.5}, 1.5, {0, 0, 1});
    expectSample(sphere, {0, 3, 0}, -1, {0, -1, 0});

    ColliderSettings box = shape("box");
    box.size = {2, 4, 6};
    expectSample(box, {3, 0, 0}, 2, {1, 0, 0});
    expectSample(box, {0.5, 0, 0}, -0.5, {1, 0, 0});
    expectSample(box, {0, -1.5, 0}, -0.5, {0, -1, 0});
    expectSample(box, {4, 6, 3}, 5, {0.6, 0.8, 0});  // nearest a corner edge: 3-4-5

    ColliderSettings cylinder = shape("cylinder");
    cylinder.center = {1, 1, 1};
    cylinder.height = 2;
    expectSample(cylinder, {4, 2, 1}, 2, {1, 0, 0});
    expectSample(cylinder, {1, 6, 1}, 3, {0, 1, 0});
    expectSample(cylinder, {1, 0, 1}, 1, {0, -1, 0});
    expectSample(cylinder, {1.5, 2, 1}, -0.5, {1, 0, 0});
    expectSample(cylinder, {5, 7, 1}, 5, {0.6, 0.8, 0});  // beyond the rim

    ColliderSettings cup = shape("cup");
    cup.height = 2;
    cup.thickness = 0.2;
    expectSample(cup, {0, 0.5, 0}, 0.3, {0, 1, 0});    // above the bottom, in the hollow
    expectSample(cup, {0.5, 1.5, 0}, 0.3, {-1, 0, 0});  // 0.3 from the wall's inner face
    expectSample(cup, {0.9, 1, 0}, -0.1, {1, 0, 0});    // inside the wall
    expectSample(cup, {1.5, 1, 0}, 0.5, {1, 0, 0});     // outside the glass
    expectSample(cup, {0, -1, 0}, 1, {0, -1, 0});       // below it
}

TEST(ColliderShapes, NormalIsTheGradientOfTheDistance) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> coordinate(-3, 3);
    for (const char* name : {"sphere", "box", "cylinder"}) {
        for (bool inside : {false, true}) {
            ColliderSettings c = shape(name);
            c.size = {2, 3, 1.5};
            c.radius = 1.2;
            c.height = 2.5;
            c.inside = inside;
            int checked = 0;
            for (int k = 0; k < 200; ++k) {
                const Vec3 p{coordinate(random), coordinate(random), coordinate(random)};
                const double h = 1e-6;
                const Vec3 gradient{
                    (sampleCollider(c, p + Vec3{h, 0, 0}).phi - sampleCollider(c, p - Vec3{h, 0, 0}).phi) / (2 * h),
                    (sampleCollider(c, p + Vec3{0, h, 0}).phi - sampleCollider(c, p - Vec3{0, h, 0}).phi) / (2 * h),
                    (sampleCollider(c, p + Vec3{0, 0, h}).phi - sampleCollider(c, p - Vec3{0, 0, h}).phi) / (2 * h)};
                const Vec3 n = sampleCollider(c, p).normal;
                // Away from edges and the medial surface the gradient is the unit normal.
                if (std::abs(length(gradient) - 1) > 1e-4) continue;
                EXPECT_NEAR(dot(gradient, n), 1.0, 1e-4) << name << " inside " << inside;
                ++checked;
            }
            EXPECT_GT(checked, 150) << name;
        }
    }
}

/// One globule of mass 1 and radius 0.5, at rest at height @p y (x = z = 0), no jitter.
SimulationSetup oneGlobule(double y) {
    SimulationSetup setup;
    EmitterSettings e;
    e.count = 1;
    e.helixRadius = 0;
    e.jitter = 0;
    e.radius = 0.5;
    e.center = {0, y, 0};
    setup.emitters = {e};
    return setup;
}

Globules settle(const SimulationSetup& setup, int frames) {
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= frames; ++f) sim.advanceFrame(f, quiet);
    return sim.globules();
}

TEST(ColliderContact, RestsOnABoxTopAsDeepAsOnTheGround) {
    SimulationSetup onGround = oneGlobule(0.2);
    SimulationSetup onBox = oneGlobule(0.2);
    onBox.ground.enabled = false;
    ColliderSettings box = shape("box");
    box.center = {0, -1, 0};
    box.size = {10, 2, 10};
    onBox.colliders = {box};
    const float groundY = settle(onGround, 75).py[0], boxY = settle(onBox, 75).py[0];
    // At rest the penalty carries the weight: depth m g / k_s below the surface.
    EXPECT_NEAR(groundY, -9.8 / 5000, 1e-5);
    EXPECT_NEAR(boxY, groundY, 1e-6);
}

/// Slides a globule down a plane tilted by @p degrees with friction @p mu for 2 s;
/// @return the distance it moved down the slope (its sinking into the plane, along the
/// normal, does not count) and its final speed.
std::pair<double, double> slide(double degrees, double mu) {
    const double theta = degrees * M_PI / 180;
    SimulationSetup setup = oneGlobule(0);
    setup.ground.enabled = false;
    setup.simulation.fps = 25;
    ColliderSettings plane = shape("plane");
    plane.normal = {-std::sin(theta), std::cos(theta), 0};
    plane.friction = mu;
    setup.colliders = {plane};
    const Globules g = settle(setup, 51);
    const Vec3 downhill{-std::cos(theta), -std::sin(theta), 0};
    return {dot(g.position(0), downhill), length(g.velocity(0))};
}

double slideDistance(double degrees, double mu) { return slide(degrees, mu).first; }

TEST(ColliderContact, FrictionHoldsBelowTheAngleOfReposeAndSlidesAbove) {
    // tan(26.57 degrees) = 0.5: held by mu = 0.6, sliding with mu = 0.4.
    const double degrees = std::atan(0.5) * 180 / M_PI;
    // Held: at rest (a tenth of a millimetre of slip while it settles into the plane).
    const auto [held, heldSpeed] = slide(degrees, 0.6);
    EXPECT_LT(std::abs(held), 1e-3);
    EXPECT_LT(heldSpeed, 1e-6);
    const double slid = slideDistance(degrees, 0.4);
    const double theta = std::atan(0.5);
    const double expected = 0.5 * 9.8 * (std::sin(theta) - 0.4 * std::cos(theta)) * 2.0 * 2.0;
    EXPECT_NEAR(slid, expected, 0.05 * expected);
    // Frictionless, it slides as on the paper's plane: g sin(theta) t^2 / 2.
    EXPECT_NEAR(slideDistance(degrees, 0), 0.5 * 9.8 * std::sin(theta) * 4, 0.05 * 9.8);
}

TEST(ColliderContainers, ClosedBoxOfLiquidLosesNoGlobule) {
    SimulationSetup setup;
    EmitterSettings liquid;
    liquid.type = "box";
    liquid.count = 0;
    liquid.min = {-2, 0.6, -2};
    liquid.max = {2, 3, 2};
    liquid.spacing = 1.0;
    liquid.velocity = {4, 0, 2};  // thrown at a wall
    setup.emitters = {liquid};
    setup.ground.enabled = false;
    ColliderSettings tank = shape("box");
    tank.inside = true;
    tank.center = {0, 2, 0};
    tank.size = {5, 4, 5};
    setup.colliders = {tank};
    const Globules g = settle(setup, 50);
    ASSERT_GT(g.size(), 30u);
    for (std::size_t i = 0; i < g.size(); ++i) {
        // Inside the tank is outside its solid (phi > 0); a centre may sink into the wall
        // by the penalty's depth, never through it.
        EXPECT_GT(sampleCollider(tank, g.position(i)).phi, -0.1) << "globule " << g.id[i];
    }
}

TEST(ColliderContainers, CupHoldsWhatIsPouredIntoIt) {
    SimulationSetup setup;
    EmitterSettings pour;
    pour.count = 120;
    pour.center = {0, 3, 0};
    pour.helixRadius = 0.6;
    setup.emitters = {pour};
    ColliderSettings cup = shape("cup");
    cup.radius = 3;
    cup.height = 2.5;
    cup.thickness = 0.4;
    setup.colliders = {cup};
    const Globules g = settle(setup, 75);
    for (std::size_t i = 0; i < g.size(); ++i) {
        // Inside the hollow: within the inner wall and above the bottom.
        EXPECT_LT(std::hypot(g.px[i], g.pz[i]), 3.0 - 0.4 + 0.05) << "globule " << g.id[i];
        EXPECT_GT(g.py[i], 0.4 - 0.05) << "globule " << g.id[i];
    }
}

}  // namespace

namespace {

ColliderKey key(double time, Vec3 position, Vec3 rotation = {0, 0, 0}) {
    ColliderKey k;
    k.time = time;
    k.position = position;
    k.rotation = rotation;
    return k;
}

TEST(ColliderMotion, KeysAreHitAndStraightMotionStaysStraight) {
    const std::vector<ColliderKey> keys = {key(0, {0, 0, 0}), key(1, {2, 0, 0}),
                                           key(2, {4, 0, 0}, {0, 0, 90})};
    EXPECT_NEAR(poseAt(keys, 1).translation.x, 2, 1e-12);
    EXPECT_NEAR(poseAt(keys, -5).translation.x, 0, 1e-12);  // held before the first key
    EXPECT_NEAR(poseAt(keys, 9).translation.x, 4, 1e-12);   // and after the last
    // Evenly spaced keys on a line: the spline is the line, at constant speed.
    for (double t : {0.1, 0.5, 1.3, 1.9}) {
        EXPECT_NEAR(poseAt(keys, t).translation.x, 2 * t, 1e-12) << t;
        EXPECT_NEAR(motionAt(keys, t).velocityAt({0, 0, 0}).x, 2, 1e-6) << t;
    }
    // 90 degrees about z at the last key: local x points along world y.
    const Vec3 x = poseAt(keys, 2).rotate({1, 0, 0});
    EXPECT_NEAR(x.x, 0, 1e-12);
    EXPECT_NEAR(x.y, 1, 1e-12);
}

TEST(ColliderMotion, AMovingPlanePushesRestingGlobules) {
    SimulationSetup setup = oneGlobule(0.5);
    ColliderSettings wall = shape("plane");
    wall.normal = {1, 0, 0};
    wall.keys = {key(0, {-1, 0, 0}), key(1, {0.5, 0, 0}), key(2, {2, 0, 0})};  // 1.5 units/s
    setup.colliders = {wall};
    const Globules g = settle(setup, 51);
    // The wall ends at x = 2; the globule rides just ahead of it, sunk in by the push.
    EXPECT_GT(g.px[0], 1.95);
    EXPECT_LT(g.px[0], 2.5);
}

/// A closed box of liquid that tilts about z by keyframes (0, 20, -20, 20, 0 degrees
/// over 2 s); @p spacing and @p radius size the globules.
SimulationSetup tiltingTank(double spacing = 1.0, double radius = 1.0) {
    SimulationSetup setup;
    EmitterSettings liquid;
    liquid.type = "box";
    liquid.count = 0;  // fill the box
    liquid.min = {-2, 0.6, -2};
    liquid.max = {2, 2.7, 2};
    liquid.spacing = spacing;
    liquid.radius = radius;
    setup.emitters = {liquid};
    setup.ground.enabled = false;
    ColliderSettings tank = shape("box");
    tank.inside = true;
    tank.center = {0, 2, 0};
    tank.size = {5, 4, 5};
    tank.keys = {key(0, {0, 0, 0}), key(0.5, {0, 0, 0}, {0, 0, 20}), key(1, {0, 0, 0}, {0, 0, -20}),
                 key(1.5, {0, 0, 0}, {0, 0, 20}), key(2, {0, 0, 0})};
    setup.colliders = {tank};
    return setup;
}

TEST(ColliderContainers, TiltingTankLosesNoGlobule) {
    const SimulationSetup setup = tiltingTank();
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= 51; ++f) {
        sim.advanceFrame(f, quiet);
        const ColliderMotion motion = motionAt(setup.colliders[0].keys, sim.time());
        const Globules& g = sim.globules();
        for (std::size_t i = 0; i < g.size(); ++i) {
            ASSERT_GT(sampleCollider(setup.colliders[0], motion, g.position(i)).phi, -0.1)
                << "globule " << g.id[i] << " at frame " << f;
        }
    }
}

TEST(ColliderMotion, ResultsAreIdenticalForAnyThreadCountAndOnResume) {
    // Enough globules (1183) that the collider loop splits across threads.
    SimulationSetup setup = tiltingTank(0.3, 0.15);
    // The same liquid at a fifth of the size: rest distance and windows scaled with it.
    setup.material.r0 = 0.3;
    setup.material.preset = "custom";
    setup.material.cr = 1.0;
    setup.material.cd = 1.5;
    // Half the default step: at 1 ms this stiffer small-scale liquid is on the edge of
    // stability, and the scalar and AVX2 force loops (simd_path.h) tip it over at frame 20.
    setup.simulation.dt = 0.0005;
    Globules oneThread, twoThreads;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        oneThread = settle(setup, 20);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        twoThreads = settle(setup, 20);
    }
    ASSERT_GT(oneThread.size(), 1100u);
    EXPECT_EQ(oneThread.px, twoThreads.px);
    EXPECT_EQ(oneThread.vy, twoThreads.vy);
    // Resumed from the state of frame 10, frame 20 is the same bit for bit.
    Simulation first(setup);
    NullReporter quiet;
    for (int f = 2; f <= 10; ++f) first.advanceFrame(f, quiet);
    Simulation resumed(setup);
    resumed.restoreState(first.saveState());
    for (int f = 11; f <= 20; ++f) resumed.advanceFrame(f, quiet);
    EXPECT_EQ(resumed.globules().px, oneThread.px);
    EXPECT_EQ(resumed.globules().vz, oneThread.vz);
}

}  // namespace

namespace {

/// Pieces of @p g: globules closer than @p link belong to one piece (union-find).
std::size_t pieces(const Globules& g, double link) {
    std::vector<std::size_t> parent(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) parent[i] = i;
    const auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (std::size_t i = 0; i < g.size(); ++i) {
        for (std::size_t j = i + 1; j < g.size(); ++j) {
            if (length(g.position(i) - g.position(j)) < link) parent[root(i)] = root(j);
        }
    }
    std::size_t count = 0;
    for (std::size_t i = 0; i < g.size(); ++i) count += root(i) == i;
    return count;
}

TEST(ColliderEffectors, TheKnifeLeavesTheSolidInTwoPieces) {
    // scenes/effectors/knife.toml, smaller: a block of the paper's best solid on the
    // ground and a blade 0.8 wide that sweeps down through it and stays.
    SimulationSetup setup;
    setup.material.preset = "solid";
    setup.material.m = 5;
    setup.material.n = 3;
    EmitterSettings block;
    block.type = "box";
    block.count = 0;
    block.min = {-4, 1, -1};
    block.max = {4, 3, 1};
    block.spacing = 1.0;
    block.jitter = 0;
    setup.emitters = {block};
    ColliderSettings knife = shape("box");
    knife.size = {0.8, 6, 6};
    knife.contact = "surface";
    knife.keys = {key(0, {0, 8, 0}), key(1.2, {0, 3, 0})};
    setup.colliders = {knife};
    // Pieces as stats.csv counts clusters: globules that overlap (centres closer than
    // r_i + r_j) are joined. (The solid's attraction reaches further, 2 r0 (r_i + r_j),
    // and pulls the halves against the blade, which keeps them apart.)
    const double reach = 2 * block.radius;
    Simulation sim(setup);
    NullReporter quiet;
    EXPECT_EQ(pieces(sim.globules(), reach), 1u);
    for (int f = 2; f <= 40; ++f) sim.advanceFrame(f, quiet);
    const Globules& g = sim.globules();
    EXPECT_EQ(pieces(g, reach), 2u);
    // One piece on each side of the blade, none left under it.
    std::size_t left = 0, right = 0;
    for (std::size_t i = 0; i < g.size(); ++i) (g.px[i] < 0 ? left : right) += 1;
    EXPECT_EQ(left, right);
    for (std::size_t i = 0; i < g.size(); ++i) EXPECT_GT(std::abs(g.px[i]), 0.4) << g.id[i];
}

}  // namespace
