// The files that carry colliders between stages (issue 13): cache/colliders.NNNN.toml
// read back exactly, and damaged or foreign ones refused naming the file; the checkpoint
// with rigid bodies read back bit for bit, and a damaged body refused.

#include "collider_poses.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "errors.h"
#include "reporter.h"
#include "simulation.h"
#include "state_file.h"

using namespace globular;
namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("globular_collider_poses_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::vector<ColliderSettings> twoColliders() {
    ColliderSettings ball, wall;
    ball.name = "ball";
    ball.shape = "sphere";
    wall.name = "wall";
    wall.shape = "plane";
    return {ball, wall};
}

std::string errorReading(const fs::path& path, const std::vector<ColliderSettings>& colliders) {
    try {
        readColliderPoses(path, colliders);
    } catch (const IoError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an IoError for " << path;
    return "";
}

TEST(ColliderPoses, ReadBackExactly) {
    const fs::path path = freshDir("exact") / "colliders.0007.toml";
    ColliderKey a, b;
    b.time = 1;
    b.position = {1.0 / 3, 2, -7};
    b.rotation = {10, 20, 30};
    const std::vector<ColliderMotion> motions = {motionAt({a, b}, 0.37), motionAt({}, 0)};
    writeColliderPoses(path, 7, 0.24, twoColliders(), motions);
    const std::vector<Pose> poses = readColliderPoses(path, twoColliders());
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_EQ(poses[0].translation, motions[0].now.translation);  // every digit kept
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_EQ(poses[0].rotation[i][j], motions[0].now.rotation[i][j]);
    }
}

TEST(ColliderPoses, DamagedOrForeignFilesAreRefusedNamingTheFile) {
    const fs::path dir = freshDir("damaged");
    const fs::path good = dir / "good.toml";
    writeColliderPoses(good, 1, 0, twoColliders(), {motionAt({}, 0), motionAt({}, 0)});
    std::ifstream in(good);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
        std::string changed = text;
        const auto at = changed.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        changed.replace(at, from.size(), to);
        std::ofstream(dir / name) << changed;
        return dir / name;
    };
    EXPECT_NE(errorReading(variant("cut.toml", "[[collider]]", "[[collider"), twoColliders())
                  .find("cut.toml: line "),
              std::string::npos);
    EXPECT_NE(errorReading(variant("renamed.toml", "'ball'", "'knife'"), twoColliders())
                  .find("named 'knife', the scene's 'ball'"),
              std::string::npos);
    EXPECT_NE(errorReading(variant("nan.toml", "translation = [ 0.0", "translation = [ nan"),
                           twoColliders())
                  .find("non-finite"),
              std::string::npos);
    EXPECT_NE(errorReading(variant("sheared.toml", "[ 1.0, 0.0, 0.0 ]", "[ 1.0, 0.5, 0.0 ]"),
                           twoColliders())
                  .find("not a rotation matrix"),
              std::string::npos);
    EXPECT_NE(errorReading(good, {twoColliders()[0]}).find("holds 2 colliders, the scene 1"),
              std::string::npos);
    std::ofstream(dir / "binary.toml") << std::string("\0\xff\x01garbage", 11);
    EXPECT_NE(errorReading(dir / "binary.toml", twoColliders()).find("binary.toml"),
              std::string::npos);
    EXPECT_NE(errorReading(dir / "missing.toml", twoColliders()).find("missing.toml"),
              std::string::npos);
}

TEST(ColliderPoses, AbsentFileFallsBackToKeyframesUnlessAColliderIsDynamic) {
    const fs::path dir = freshDir("absent");
    std::vector<ColliderSettings> colliders = twoColliders();
    ColliderKey a, b;
    b.time = 1;
    b.position = {4, 0, 0};
    colliders[1].keys = {a, b};
    EXPECT_NEAR(colliderPosesOnFrame(colliders, dir, 26, 25)[1].translation.x, 4, 1e-12);
    colliders[0].dynamic = true;
    EXPECT_THROW(colliderPosesOnFrame(colliders, dir, 26, 25), IoError);
}

TEST(ColliderCheckpoint, BodiesAreReadBackBitForBitAndDamageIsRefused) {
    SimulationSetup setup;
    EmitterSettings e;
    e.count = 12;
    setup.emitters = {e};
    std::vector<ColliderSettings> colliders = twoColliders();
    colliders[0].dynamic = true;
    colliders[0].center = {3, 2, 0};
    colliders[0].velocity = {-4, 0, 1};
    colliders[0].angularVelocity = {30, 0, 0};
    setup.colliders = colliders;
    Simulation sim(setup);
    NullReporter quiet;
    for (int f = 2; f <= 4; ++f) sim.advanceFrame(f, quiet);
    const fs::path dir = freshDir("checkpoint");
    writeCheckpoint(dir / "state.bin", Checkpoint{4, 99, sim.saveState()});
    const Checkpoint back = readCheckpoint(dir / "state.bin");
    ASSERT_EQ(back.state.bodies.size(), 1u);
    const RigidBodyState& saved = sim.colliders().bodies()[0].state;
    EXPECT_EQ(back.state.bodies[0].position, saved.position);
    EXPECT_EQ(back.state.bodies[0].orientation, saved.orientation);
    EXPECT_EQ(back.state.bodies[0].angularMomentum, saved.angularMomentum);
    EXPECT_EQ(back.state.bodies[0].torque, saved.torque);
    // A body turned into a non-rotation is refused, even with the checksum made right.
    SimulationState bad = sim.saveState();
    bad.bodies[0].orientation = {2, 0, 0, 0};
    writeCheckpoint(dir / "bad.bin", Checkpoint{4, 99, bad});
    try {
        readCheckpoint(dir / "bad.bin");
        ADD_FAILURE() << "a bad quaternion was accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("unit quaternion"), std::string::npos) << e.what();
    }
    // A state with bodies does not fit a scene without them.
    SimulationSetup other = setup;
    other.colliders = {twoColliders()[1]};
    Simulation plain(other);
    EXPECT_THROW(plain.restoreState(back.state), Error);
}

}  // namespace
