// The scene's thermal keys (issue 14): [thermal], [[heater]], a material's melting range
// and its [material.solid] / [material.liquid] tables, emitter and collider temperatures:
// read, resolved and read back the same, and every bad value named by file, line and key.

#include <gtest/gtest.h>

#include <filesystem>

#include "errors.h"
#include "reporter.h"
#include "scene.h"
#include "scene_text.h"

namespace globular {
namespace {

Scene parse(const std::string& text) { return parseSceneText(text, "lamp.toml"); }
std::string parseError(const std::string& text) { return sceneErrorOf(text, "lamp.toml"); }

const char* kWax =
    "[thermal]\nenabled = true\nambient = 15\ncooling = 0.2\n"
    "[[material]]\nname = \"wax\"\nexpansion = 0.03\nt_solid = 40\nt_liquid = 55\n"
    "[material.solid]\npreset = \"solid\"\nb1 = 2.5\n"
    "[[material]]\nname = \"water\"\n"
    "[[heater]]\nmin = [-1, 0, -1]\nmax = [1, 1, 1]\npower = 40\n"
    "[[emitter]]\nmaterial = \"wax\"\ntemperature = 30\n"
    "[[collider]]\nshape = \"box\"\ntemperature = 90\nheat_transfer = 3\n";

TEST(SceneThermal, ThermalKeysAreReadAndResolved) {
    const Scene scene = parse(kWax);
    EXPECT_TRUE(scene.thermal.enabled);
    EXPECT_EQ(scene.thermal.cooling, 0.2);
    const MaterialSettings& wax = scene.material;
    EXPECT_TRUE(wax.phases);
    EXPECT_EQ(wax.tSolid, 40);
    EXPECT_EQ(wax.solid.preset, "solid");
    EXPECT_EQ(wax.solid.b1, 2.5);
    EXPECT_EQ(wax.liquid.b1, wax.b1);  // not given: the material's own
    EXPECT_FALSE(scene.otherMaterials.at(0).phases);
    ASSERT_EQ(scene.heaters.size(), 1u);
    EXPECT_EQ(scene.heaters[0].power, 40);
    EXPECT_EQ(scene.emitters.at(0).temperature, 30);
    EXPECT_EQ(scene.colliders.at(0).heatTransfer, 3);
    const SimulationSetup setup = scene.simulationSetup();
    EXPECT_TRUE(setup.thermal.enabled);
    EXPECT_EQ(setup.heaters.size(), 1u);
    const std::string resolved = resolvedSceneToml(scene);
    EXPECT_NE(resolved.find("[material.solid]\npreset = \"solid\""), std::string::npos) << resolved;
    EXPECT_EQ(resolvedSceneToml(parse(resolved)), resolved);
    // A single [material] takes its phase tables as well.
    const Scene one = parse("[thermal]\nenabled = true\n[material]\nt_solid = 1\nt_liquid = 2\n"
                            "[material.liquid]\nb1 = 1.25\n");
    EXPECT_EQ(one.material.liquid.b1, 1.25);
    EXPECT_EQ(resolvedSceneToml(parse(resolvedSceneToml(one))), resolvedSceneToml(one));
}

TEST(SceneThermal, BadThermalKeysNameFileLineAndKey) {
    const std::string on = "[thermal]\nenabled = true\n";
    EXPECT_EQ(parseError(on + "[material]\nt_solid = 60\nt_liquid = 40\n[material.solid]\n"),
              "lamp.toml:4:11: [material] key 't_solid' = 60 must lie below t_liquid = 40");
    EXPECT_EQ(parseError(on + "[material]\nt_solid = 40\n[material.solid]\n"),
              "lamp.toml: [material] key 't_liquid': a material with phases needs both t_solid "
              "and t_liquid");
    EXPECT_EQ(parseError(on + "[material]\nt_solid = 40\nt_liquid = 60\n"),
              "lamp.toml:4:11: [material] key 't_solid': a melting range needs a "
              "[material.solid] or [material.liquid] table of constants");
    EXPECT_EQ(parseError(on + "[material]\nsolid = 3\n"),
              "lamp.toml:4:9: 'solid' of a material must be a table: [material.solid]");
    EXPECT_EQ(parseError(on + "[material]\nt_solid = 1\nt_liquid = 2\n[material.solid]\nbee = 2\n"),
              "lamp.toml:7:7: [material.solid] key 'bee': unknown key (did you mean 'b1'?)");
    EXPECT_EQ(parseError(on + "[[material]]\nname = \"a\"\nt_solid = 1\nt_liquid = 2\n"
                              "[material.liquid]\nb1 = -1\n"),
              "lamp.toml:8:6: [material[0].liquid] key 'b1' = -1: must be > 0");
    EXPECT_EQ(parseError(on + "[[heater]]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n"),
              "lamp.toml:5:7: [heater[0]] key 'max': every coordinate of max must exceed min's");
    // Temperature keys while temperature is off are errors, not silently ignored.
    EXPECT_EQ(parseError("[[emitter]]\ntemperature = 90\n"),
              "lamp.toml:2:15: [emitter[0]] key 'temperature': temperature is off; set "
              "[thermal] enabled = true");
    EXPECT_EQ(parseError("[thermal]\ncooling = 1\n"),
              "lamp.toml:2:11: [thermal] key 'cooling': temperature is off; set [thermal] "
              "enabled = true");
    EXPECT_EQ(parseError("[material.solid]\nb1 = 2\n"),
              "lamp.toml: [material.solid]: phases need temperature; set [thermal] enabled = true");
    EXPECT_EQ(parseError("[[heater]]\npower = 2\n"),
              "lamp.toml: [[heater]]: heaters need temperature; set [thermal] enabled = true");
}

}  // namespace
}  // namespace globular

namespace globular {
namespace {

/// Every scene shipped in scenes/ reads without an error (with its mesh files).
TEST(ShippedScenes, EveryOneReads) {
    std::size_t read = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(
             std::filesystem::path(GLOBULAR_SOURCE_DIR) / "scenes")) {
        if (entry.path().extension() != ".toml") continue;
        NullReporter quiet;
        EXPECT_NO_THROW(loadScene(entry.path(), {}, quiet)) << entry.path();
        ++read;
    }
    EXPECT_GE(read, 20u);
}

}  // namespace
}  // namespace globular
