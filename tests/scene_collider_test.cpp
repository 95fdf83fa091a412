// The [[collider]] sections of a scene (issue 13): keys, defaults, errors naming file,
// line and key, and the resolved scene.

#include <gtest/gtest.h>

#include "errors.h"
#include "recording_reporter.h"
#include "scene.h"

namespace globular {
namespace {

Scene parse(const std::string& text) {
    NullReporter quiet;
    return parseScene(text, "glass.toml", {}, quiet);
}

std::string parseError(const std::string& text) {
    try {
        parse(text);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a SceneError for:\n" << text;
    return "";
}

TEST(SceneColliders, NoneByDefaultAndEachSectionRead) {
    EXPECT_TRUE(parse("").colliders.empty());
    const Scene scene = parse(
        "[[collider]]\nname = \"glass\"\nshape = \"cup\"\nradius = 3\nheight = 4\n"
        "thickness = 0.3\nfriction = 0.2\n\n"
        "[[collider]]\nshape = \"plane\"\nnormal = [0, 1, 1]\ncontact = \"surface\"\n");
    ASSERT_EQ(scene.colliders.size(), 2u);
    EXPECT_EQ(scene.colliders[0].name, "glass");
    EXPECT_EQ(scene.colliders[0].shape, "cup");
    EXPECT_EQ(scene.colliders[0].thickness, 0.3);
    EXPECT_EQ(scene.colliders[0].friction, 0.2);
    EXPECT_EQ(scene.colliders[0].ks, 5000.0);  // the ground's defaults
    EXPECT_EQ(scene.colliders[1].normal, (Vec3{0, 1, 1}));
    EXPECT_EQ(scene.simulationSetup().colliders.size(), 2u);
}

TEST(SceneColliders, BadInputNamesFileLineAndKey) {
    EXPECT_EQ(parseError("[[collider]]\nshape = \"teapot\"\n"),
              "glass.toml:2:9: [collider[0]] key 'shape' = \"teapot\": must be one of plane, "
              "box, sphere, cylinder, cup");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"sphere\"\nsize = [1, 2, 3]\n"),
              "glass.toml:3:8: [collider[0]] key 'size': does not apply to a sphere collider");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"cup\"\nradius = 1\nthickness = 1\n"),
              "glass.toml:4:13: [collider[0]] key 'thickness': a cup's wall must be thinner "
              "than its radius and its height");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"plane\"\nnormal = [0, 0, 0]\n"),
              "glass.toml:3:10: [collider[0]] key 'normal': a plane needs a non-zero normal");
    EXPECT_EQ(parseError("[[collider]]\nfriction = -1\n"),
              "glass.toml:2:12: [collider[0]] key 'friction' = -1: must be >= 0");
}

TEST(SceneColliders, ResolvedSceneKeepsTheKeysThatApply) {
    const Scene scene = parse("[[collider]]\nshape = \"sphere\"\nradius = 2\ninside = true\n");
    const std::string resolved = resolvedSceneToml(scene);
    EXPECT_NE(resolved.find("[[collider]]\nname = \"\"\nshape = \"sphere\"\ncenter = "),
              std::string::npos)
        << resolved;
    EXPECT_EQ(resolved.find("thickness"), std::string::npos) << resolved;
    const Scene again = parse(resolved);
    ASSERT_EQ(again.colliders.size(), 1u);
    EXPECT_TRUE(again.colliders[0].inside);
    EXPECT_EQ(resolvedSceneToml(again), resolved);
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

TEST(SceneColliders, KeyframesAreReadInOrderAndResolved) {
    const std::string text =
        "[[collider]]\nshape = \"box\"\ninside = true\n"
        "[[collider.key]]\ntime = 0\n"
        "[[collider.key]]\ntime = 1.5\nrotation = [0, 0, 15]\n";
    const Scene scene = parse(text);
    ASSERT_EQ(scene.colliders[0].keys.size(), 2u);
    EXPECT_EQ(scene.colliders[0].keys[1].rotation, (Vec3{0, 0, 15}));
    const std::string resolved = resolvedSceneToml(scene);
    EXPECT_NE(resolved.find("[[collider.key]]\ntime = 1.5\n"), std::string::npos) << resolved;
    EXPECT_EQ(resolvedSceneToml(parse(resolved)), resolved);
    // --set reaches a key by index.
    NullReporter quiet;
    const Scene changed = parseScene(text, "tank.toml", {"collider.0.key.1.time=2"}, quiet);
    EXPECT_EQ(changed.colliders[0].keys[1].time, 2.0);
}

TEST(SceneColliders, KeyframeErrorsNameFileLineAndKey) {
    EXPECT_EQ(parseError("[[collider]]\n[[collider.key]]\ntime = 2\n[[collider.key]]\ntime = 1\n"),
              "glass.toml:5:8: [collider[0].key[1]] key 'time': keys go in time order; 1.000000 s "
              "is not later than the key before it");
    EXPECT_EQ(parseError("[[collider]]\n[[collider.key]]\nposition = [0, nan, 0]\n"),
              "glass.toml:3:12: [collider[0].key[0]] key 'position' = [0, nan, 0]: components "
              "must be finite numbers");
    EXPECT_EQ(parseError("[[collider]]\n[[collider.key]]\nspeed = 1\n"),
              "glass.toml:3:9: [collider[0].key[0]] key 'speed': unknown key");
}

}  // namespace
}  // namespace globular
