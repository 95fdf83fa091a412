// The [[collider]] sections of a scene (issue 13): keys, defaults, errors naming file,
// line and key, and the resolved scene.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "errors.h"
#include "recording_reporter.h"
#include "scene.h"
#include "scene_text.h"

namespace globular {
namespace {

Scene parse(const std::string& text) { return parseSceneText(text, "glass.toml"); }
std::string parseError(const std::string& text) { return sceneErrorOf(text, "glass.toml"); }

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
              "box, sphere, cylinder, cup, mesh");
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

namespace globular {
namespace {

namespace fs = std::filesystem;

/// A file under a fresh temporary folder with @p text.
fs::path writeTemp(const std::string& name, const std::string& text) {
    const fs::path dir = fs::temp_directory_path() / "globular_scene_collider_test";
    fs::create_directories(dir);
    const fs::path path = dir / name;
    std::ofstream(path) << text;
    return path;
}

/// @return whether @p text contains every one of @p parts.
::testing::AssertionResult mentions(const std::string& text, std::initializer_list<std::string> parts) {
    for (const std::string& part : parts) {
        if (text.find(part) == std::string::npos) {
            return ::testing::AssertionFailure() << "'" << part << "' not in: " << text;
        }
    }
    return ::testing::AssertionSuccess();
}

const char* kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(SceneColliders, MeshCollidersReadTheirFileWhenTheSceneIsRead) {
    const fs::path closed = writeTemp("tetrahedron.obj", kTetrahedron);
    const Scene scene = parse("[[collider]]\nshape = \"mesh\"\nfile = \"" + closed.string() +
                              "\"\nscale = 2\ninside = false\n");
    ASSERT_EQ(scene.colliders.size(), 1u);
    EXPECT_EQ(scene.colliders[0].scale, 2.0);
    // An open mesh (one triangle) is a solid only with a thickness.
    const fs::path open = writeTemp("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NO_THROW(parse("[[collider]]\nshape = \"mesh\"\nthickness = 0.1\nfile = \"" +
                          open.string() + "\"\n"));
}

TEST(SceneColliders, AMeshFileIsFoundBesideTheSceneFileFromAnyFolder) {
    const fs::path mesh = writeTemp("beside.obj", kTetrahedron);
    const fs::path scene = writeTemp("beside.toml", "[[collider]]\nshape = \"mesh\"\nfile = \"beside.obj\"\n");
    NullReporter quiet;
    const Scene loaded = loadScene(scene, {}, quiet);  // the tests run in another folder
    ASSERT_NE(fs::current_path(), mesh.parent_path());
    EXPECT_EQ(loaded.colliderScene().solids().size(), 1u);
    EXPECT_NE(resolvedSceneToml(loaded).find("file = \"" + mesh.string() + "\""), std::string::npos);
}

TEST(SceneColliders, BadMeshesAndBodiesNameFileLineAndKey) {
    const fs::path open = writeTemp("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_TRUE(mentions(
        parseError("[[collider]]\nshape = \"mesh\"\nfile = \"" + open.string() + "\"\n"),
        {"glass.toml:3:8: [collider[0]] key 'file': mesh ", "open.obj is not closed",
         "give the collider a thickness"}));
    EXPECT_TRUE(mentions(parseError("[[collider]]\nshape = \"mesh\"\nfile = \"/no/such/bowl.obj\"\n"),
                         {"glass.toml:3:8: [collider[0]] key 'file': ", "/no/such/bowl.obj"}));
    const fs::path garbage = writeTemp("garbage.obj", "v 0 0 0\nf 1 2 x\n");
    EXPECT_TRUE(mentions(
        parseError("[[collider]]\nshape = \"mesh\"\nfile = \"" + garbage.string() + "\"\n"),
        {"key 'file': ", "garbage.obj:2: "}));
    const fs::path text = writeTemp("bowl.stl", "solid\n");
    EXPECT_TRUE(mentions(
        parseError("[[collider]]\nshape = \"mesh\"\nfile = \"" + text.string() + "\"\n"),
        {"key 'file': ", "expected an .obj or .ply file"}));
    EXPECT_EQ(parseError("[[collider]]\nshape = \"mesh\"\n"),
              "glass.toml:2:9: [collider[0]] key 'shape': a mesh collider needs a file (OBJ or PLY)");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"cup\"\n"),
              "glass.toml:2:9: [collider[0]] key 'shape': a cup needs a thickness > 0 (its wall)");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"sphere\"\nmass = 3\n"),
              "glass.toml:3:8: [collider[0]] key 'mass': does not apply to a collider without "
              "dynamic = true");
    EXPECT_EQ(parseError("[[collider]]\nshape = \"plane\"\ndynamic = true\n"),
              "glass.toml:3:11: [collider[0]] key 'dynamic': does not apply to a plane collider");
    EXPECT_TRUE(mentions(
        parseError("[[collider]]\nshape = \"box\"\ninside = true\ndynamic = true\n"),
        {"key 'dynamic': a container (inside = true) cannot be dynamic"}));
    EXPECT_TRUE(mentions(
        parseError("[[collider]]\ndynamic = true\n[[collider.key]]\ntime = 0\n"),
        {"key 'dynamic': a collider is moved by [[collider.key]] keyframes or is dynamic"}));
    EXPECT_EQ(parseError("[[collider]]\ndynamic = true\nmass = 0\n"),
              "glass.toml:3:8: [collider[0]] key 'mass' = 0: must be in (0, 1e+12]");
}

TEST(SceneColliders, DynamicCollidersResolveWithTheirBodyKeys) {
    const Scene scene = parse(
        "[[collider]]\nshape = \"sphere\"\ndynamic = true\nmass = 40\n"
        "velocity = [12, 0, 0]\nangular_velocity = [0, 90, 0]\n");
    EXPECT_TRUE(scene.colliders[0].dynamic);
    EXPECT_EQ(scene.colliders[0].velocity, (Vec3{12, 0, 0}));
    const std::string resolved = resolvedSceneToml(scene);
    EXPECT_NE(resolved.find("mass = 40"), std::string::npos) << resolved;
    EXPECT_EQ(resolvedSceneToml(parse(resolved)), resolved);
    // Without dynamic the body's keys are left out of the resolved scene.
    EXPECT_EQ(resolvedSceneToml(parse("[[collider]]\nshape = \"sphere\"\n"))
                  .find("angular_velocity"),
              std::string::npos);
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

// Several materials (issue 14): [[material]] and [[material_pair]] sections.

TEST(SceneMaterials, SeveralMaterialsAreReadNamedAndResolved) {
    const std::string text =
        "[[material]]\nname = \"ketchup\"\npreset = \"liquid\"\ncolor = [0.7, 0.1, 0.05]\n"
        "[[material]]\nname = \"mustard\"\npreset = \"solid\"\nb1 = 1.0\n"
        "[[material_pair]]\na = \"ketchup\"\nb = \"mustard\"\nb1 = 0.5\n"
        "[[emitter]]\nmaterial = \"mustard\"\n[[emitter]]\n";
    const Scene scene = parse(text);
    EXPECT_EQ(scene.material.name, "ketchup");
    ASSERT_EQ(scene.otherMaterials.size(), 1u);
    EXPECT_EQ(scene.otherMaterials[0].preset, "solid");
    EXPECT_EQ(scene.materialPairs.at(0).b1, 0.5);
    const SimulationSetup setup = scene.simulationSetup();
    EXPECT_EQ(setup.materials().size(), 2u);
    EXPECT_EQ(setup.emitters[0].material, "mustard");
    const std::string resolved = resolvedSceneToml(scene);
    EXPECT_NE(resolved.find("[[material]]\nname = \"mustard\""), std::string::npos) << resolved;
    EXPECT_EQ(resolved.find("\n[material]\n"), std::string::npos) << resolved;
    EXPECT_EQ(resolvedSceneToml(parse(resolved)), resolved);
    // One unnamed [material] stays as it was.
    EXPECT_NE(resolvedSceneToml(parse("[material]\nb1 = 3\n")).find("\n[material]\n"),
              std::string::npos);
}

TEST(SceneMaterials, BadMaterialNamesNameFileLineAndKey) {
    const std::string two = "[[material]]\nname = \"a\"\n[[material]]\nname = \"b\"\n";
    EXPECT_EQ(parseError(two + "[[emitter]]\nmaterial = \"honey\"\n"),
              "glass.toml:6:12: [emitter[0]] key 'material' = \"honey\": no [[material]] has "
              "this name (there are: a, b)");
    EXPECT_EQ(parseError("[[material]]\nname = \"a\"\n[[material]]\npreset = \"solid\"\n"),
              "glass.toml: [material[1]] key 'name': with several [[material]] sections each "
              "needs a name");
    EXPECT_EQ(parseError("[[material]]\nname = \"a\"\n[[material]]\nname = \"a\"\n"),
              "glass.toml:4:8: [material[1]] key 'name' = \"a\": another [[material]] has this "
              "name");
    EXPECT_EQ(parseError(two + "[[material_pair]]\na = \"a\"\nb = \"c\"\n"),
              "glass.toml:7:5: [material_pair[0]] key 'b' = \"c\": no [[material]] has this "
              "name (there are: a, b)");
    EXPECT_EQ(parseError(two + "[[material_pair]]\na = \"a\"\nb = \"a\"\n"),
              "glass.toml:7:5: [material_pair[0]] key 'b': a pair names two different "
              "materials");
    EXPECT_EQ(parseError(two + "[[material_pair]]\na = \"a\"\nb = \"b\"\n"
                               "[[material_pair]]\na = \"b\"\nb = \"a\"\n"),
              "glass.toml:9:5: [material_pair[1]] key 'a': the pair 'b', 'a' is given twice");
    EXPECT_EQ(parseError(two + "[[material_pair]]\na = \"a\"\nb = \"b\"\ncr = -1\n"),
              "glass.toml:8:6: [material_pair[0]] key 'cr' = -1: must be >= 0");
}

}  // namespace
}  // namespace globular
