// Scene parsing: every kind of bad input gives a SceneError naming file, line, column
// and key; --set overrides; warnings; defaults; the resolved scene round trip.

#include "scene.h"
#include "scene_text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "errors.h"
#include "reporter.h"
#include "run_command.h"
#include "settings_schema.h"
#include "recording_reporter.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

Scene parse(const std::string& text, const std::vector<std::string>& overrides = {}) {
    return parseSceneText(text, "scene.toml", overrides);
}

/// The message of the SceneError that parsing throws; fails the test when none is thrown.
std::string parseError(const std::string& text, const std::vector<std::string>& overrides = {}) {
    return sceneErrorOf(text, "scene.toml", overrides);
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// --- TOML and section structure ---------------------------------------------------------

TEST(SceneErrors, TomlSyntaxErrorNamesLineAndColumn) {
    const std::string message = parseError("[simulation]\nfps = 25\ndt = = 3\n");
    EXPECT_TRUE(message.starts_with("scene.toml:3:6: ")) << message;
}

TEST(SceneErrors, UnterminatedStringNamesItsLine) {
    const std::string message = parseError("[material]\n\npreset = \"liquid\n");
    EXPECT_TRUE(message.starts_with("scene.toml:3:")) << message;
}

TEST(SceneErrors, UnknownSectionSuggestsClosest) {
    EXPECT_EQ(parseError("[simulation]\nfps = 30\n\n[materail]\nb1 = 2\n"),
              "scene.toml:4:1: unknown section 'materail' (did you mean 'material'?)");
    EXPECT_EQ(parseError("[physics]\ngravity = 1\n"), "scene.toml:1:1: unknown section 'physics'");
}

TEST(SceneErrors, UnknownKeySuggestsClosest) {
    EXPECT_EQ(parseError("[[emitter]]\ncuont = 10\n"),
              "scene.toml:2:9: [emitter[0]] key 'cuont': unknown key (did you mean 'count'?)");
    EXPECT_EQ(parseError("[simulation]\nfps = 25\nfsp = 30\n"),
              "scene.toml:3:7: [simulation] key 'fsp': unknown key (did you mean 'fps'?)");
}

TEST(SceneErrors, MaterialWrittenAsAValue) {
    const std::string message = parseError("material = 3\n");
    EXPECT_TRUE(message.starts_with("scene.toml:")) << message;
    EXPECT_TRUE(contains(message, "'material' must be a section: [material]")) << message;
}

TEST(SceneErrors, EmitterWrittenAsSingleSection) {
    const std::string message = parseError("[emitter]\ncount = 3\n");
    EXPECT_TRUE(message.starts_with("scene.toml:1:1: ")) << message;
    EXPECT_TRUE(contains(message, "'emitter' must be written as [[emitter]] sections")) << message;
}

TEST(SceneErrors, NestedTableIsNotAKey) {
    const std::string message = parseError("[material]\nb1 = 2\n[material.extra]\nx = 1\n");
    EXPECT_TRUE(message.starts_with("scene.toml:3:")) << message;
    EXPECT_TRUE(contains(message, "[material] key 'extra': nested tables")) << message;
}

TEST(SceneErrors, ArraysHoldOnlyNumbers) {
    const std::string message = parseError("[simulation]\ngravity = [0, \"down\", 0]\n");
    EXPECT_TRUE(message.starts_with("scene.toml:2:11: ")) << message;
    EXPECT_TRUE(contains(message, "key 'gravity': arrays may hold only numbers")) << message;
}

// --- values -----------------------------------------------------------------------------

TEST(SceneErrors, WrongType) {
    EXPECT_EQ(parseError("[simulation]\ndt = \"fast\"\n"),
              "scene.toml:2:6: [simulation] key 'dt' = \"fast\": expected a number, got a string");
    EXPECT_EQ(parseError("[simulation]\nframes = 2.5\n"),
              "scene.toml:2:10: [simulation] key 'frames' = 2.5: expected an integer, got a "
              "number");
    EXPECT_EQ(parseError("[ground]\nenabled = \"yes\"\n"),
              "scene.toml:2:11: [ground] key 'enabled' = \"yes\": expected true or false, got a "
              "string");
}

TEST(SceneErrors, OutOfRange) {
    EXPECT_EQ(parseError("[simulation]\ndt = -1\n"),
              "scene.toml:2:6: [simulation] key 'dt' = -1: must be > 0");
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"helix\"\nradius = 0\n"),
              "scene.toml:3:10: [emitter[0]] key 'radius' = 0: must be > 0");
    EXPECT_EQ(parseError("[material]\nm = 0\n"),
              "scene.toml:2:5: [material] key 'm' = 0: must be > 0");
    EXPECT_EQ(parseError("[simulation]\nframes = 0\n"),
              "scene.toml:2:10: [simulation] key 'frames' = 0: must be in [1, 1000000]");
    EXPECT_EQ(parseError("[material]\ncr = -0.5\n"),
              "scene.toml:2:6: [material] key 'cr' = -0.5: must be >= 0");
}

TEST(SceneErrors, NotFinite) {
    EXPECT_EQ(parseError("[material]\nb1 = nan\n"),
              "scene.toml:2:6: [material] key 'b1' = nan: must be a finite number");
    EXPECT_EQ(parseError("[material]\nb1 = inf\n"),
              "scene.toml:2:6: [material] key 'b1' = inf: must be a finite number");
    const std::string vec = parseError("[simulation]\ngravity = [0, -inf, 0]\n");
    EXPECT_TRUE(vec.starts_with("scene.toml:2:11: [simulation] key 'gravity'")) << vec;
    EXPECT_TRUE(contains(vec, "components must be finite numbers")) << vec;
}

TEST(SceneErrors, BadChoiceListsChoices) {
    EXPECT_EQ(parseError("[material]\npreset = \"lava\"\n"),
              "scene.toml:2:10: [material] key 'preset' = \"lava\": must be one of powder, "
              "liquid, solid, custom");
    EXPECT_EQ(parseError("[simulation]\nintegrator = \"verlet\"\n"),
              "scene.toml:2:14: [simulation] key 'integrator' = \"verlet\": must be one of "
              "forward_euler, semi_implicit_euler, velocity_verlet");
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"bx\"\n"),
              "scene.toml:2:8: [emitter[0]] key 'type' = \"bx\": must be one of helix, box, "
              "spout, points (did you mean box?)");
}

TEST(SceneErrors, EmitterKeyNotApplicableToItsType) {
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"helix\"\nrate = 100\n"),
              "scene.toml:3:8: [emitter[0]] key 'rate': does not apply to a helix emitter");
    // The second emitter is named by its index and its own line.
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"helix\"\n\n[[emitter]]\ntype = \"box\"\n"
                         "turn = 0.3\n"),
              "scene.toml:6:8: [emitter[1]] key 'turn': does not apply to a box emitter");
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"points\"\nfile = \"a.ply\"\ncount = 5\n"),
              "scene.toml:4:9: [emitter[0]] key 'count': does not apply to a points emitter");
}

TEST(SceneErrors, InconsistentEmitters) {
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n"),
              "scene.toml:4:7: [emitter[0]] key 'max': every component must exceed min's");
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"spout\"\ndirection = [0, 0, 0]\n"),
              "scene.toml:3:13: [emitter[0]] key 'direction': must not be [0, 0, 0]");
    EXPECT_EQ(parseError("[[emitter]]\ntype = \"points\"\n"),
              "scene.toml: [emitter[0]] key 'file': a points emitter needs a file");
    EXPECT_EQ(parseError("[[emitter]]\ncount = 0\n"),
              "scene.toml:2:9: [emitter[0]] key 'count': must be at least 1");
}

TEST(SceneErrors, CustomPresetNeedsCrAndCd) {
    EXPECT_EQ(parseError("[material]\npreset = \"custom\"\ncr = 1.0\n"),
              "scene.toml:2:10: [material] key 'preset': the custom preset needs both cr and "
              "cd set to positive numbers");
    EXPECT_NO_THROW(parse("[material]\npreset = \"custom\"\ncr = 1.0\ncd = 1.5\n"));
}

TEST(SceneErrors, TooManyStepsPerFrame) {
    EXPECT_EQ(parseError("[simulation]\ndt = 1e-9\n"),
              "scene.toml:2:6: [simulation] key 'dt': 4e+07 steps per frame (at fps 25) is "
              "more than the limit of 1000000");
    // Derived after the fact: 1e-22 s would overflow an integer count of steps.
    EXPECT_EQ(parseError("[simulation]\ndt = 1e-22\n"),
              "scene.toml:2:6: [simulation] key 'dt': 4e+20 steps per frame (at fps 25) is "
              "more than the limit of 1000000");
}

TEST(SceneErrors, FrameDurationIsBounded) {
    EXPECT_EQ(parseError("[simulation]\nfps = 1e-300\n"),
              "scene.toml:2:7: [simulation] key 'fps': frames of 1e+300 s; a frame must last "
              "between 1e-06 s and 3600 s");
    EXPECT_EQ(parseError("[simulation]\nfps = 1e9\n"),
              "scene.toml:2:7: [simulation] key 'fps': frames of 1e-09 s; a frame must last "
              "between 1e-06 s and 3600 s");
}

// --- --set --------------------------------------------------------------------------------

TEST(SceneOverrides, MalformedOverrides) {
    EXPECT_EQ(parseError("", {"material.b1"}),
              "--set material.b1: expected KEY=VALUE, e.g. --set material.b1=3");
    EXPECT_EQ(parseError("", {"=3"}), "--set =3: expected KEY=VALUE, e.g. --set material.b1=3");
    EXPECT_EQ(parseError("", {"b1=3"}),
              "--set b1=3: the key needs a section, e.g. material.b1 or emitter.0.count");
    EXPECT_EQ(parseError("[[emitter]]\ncount = 10\n", {"emitter.5.count=10"}),
              "--set emitter.5.count=10: there are only 1 [[emitter]] sections (indices start "
              "at 0)");
    EXPECT_EQ(parseError("[[emitter]]\n", {"emitter.99999999999999999999.count=1"}),
              "--set emitter.99999999999999999999.count=1: there are only 1 [[emitter]] "
              "sections (indices start at 0)");
    // An empty index is a SceneError, not std::invalid_argument from stoul.
    EXPECT_TRUE(
        parseError("[[emitter]]\n", {"emitter..count=1"}).starts_with("--set emitter..count=1: "));
    EXPECT_EQ(parseError("[material]\nb1 = 2\n", {"material.b1.x=3"}),
              "--set material.b1.x=3: 'b1' is not a section");
}

TEST(SceneOverrides, ErrorsNameTheOverride) {
    EXPECT_EQ(parseError("[material]\nb1 = 2\n", {"material.b1=-3"}),
              "--set material.b1=-3: [material] key 'b1' = -3: must be > 0");
    EXPECT_EQ(parseError("", {"material.bb=3"}),
              "--set material.bb=3: [material] key 'bb': unknown key (did you mean 'b1'?)");
    EXPECT_EQ(parseError("", {"materail.b1=3"}),
              "--set materail.b1=3: unknown section 'materail' (did you mean 'material'?)");
    EXPECT_EQ(parseError("", {"emitter.0.rate=5"}),
              "--set emitter.0.rate=5: [emitter[0]] key 'rate': does not apply to a helix "
              "emitter");
    EXPECT_EQ(parseError("", {"material.preset=lava"}),
              "--set material.preset=lava: [material] key 'preset' = \"lava\": must be one of "
              "powder, liquid, solid, custom");
}

TEST(SceneOverrides, OverrideWinsOverTheFile) {
    const Scene scene = parse("[material]\nb1 = 2.5\nm = 6\n", {"material.b1=3"});
    EXPECT_EQ(scene.material.b1, 3.0);
    EXPECT_EQ(scene.material.m, 6.0);
}

TEST(SceneOverrides, AppliesToEmittersAndVectors) {
    const Scene scene = parse("[[emitter]]\ncount = 400\n",
                              {"emitter.0.count=10", "simulation.gravity=[0, -1.5, 0]",
                               "simulation.frames=3", "output.ply=true"});
    ASSERT_EQ(scene.emitters.size(), 1u);
    EXPECT_EQ(scene.emitters[0].count, 10);
    EXPECT_EQ(scene.simulation.gravity, (Vec3{0, -1.5, 0}));
    EXPECT_EQ(scene.simulation.frames, 3);
    EXPECT_TRUE(scene.output.ply);
}

TEST(SceneOverrides, IndexOneAppendsAnEmitter) {
    const Scene scene = parse("[[emitter]]\ncount = 50\n", {"emitter.1.type=box"});
    ASSERT_EQ(scene.emitters.size(), 2u);
    EXPECT_EQ(scene.emitters[0].type, "helix");
    EXPECT_EQ(scene.emitters[0].count, 50);
    EXPECT_EQ(scene.emitters[1].type, "box");
}

TEST(SceneOverrides, EmitterOfTheDefaultScene) {
    // With no [[emitter]] in the text, emitter.0 is the one default helix.
    const Scene scene = parse("", {"emitter.0.count=12"});
    ASSERT_EQ(scene.emitters.size(), 1u);
    EXPECT_EQ(scene.emitters[0].type, "helix");
    EXPECT_EQ(scene.emitters[0].count, 12);
}

TEST(SceneOverrides, BareWordIsAString) {
    const Scene scene = parse("", {"material.preset=solid", "simulation.integrator=velocity_verlet",
                                   "ground.contact=surface"});
    EXPECT_EQ(scene.material.preset, "solid");
    EXPECT_EQ(scene.simulation.integrator, "velocity_verlet");
    EXPECT_EQ(scene.ground.contact, "surface");
    // A quoted TOML string works too.
    EXPECT_EQ(parse("", {"material.preset=\"powder\""}).material.preset, "powder");
}

TEST(SceneOverrides, WarningNamesTheOverride) {
    RecordingReporter reporter;
    parseScene("[material]\nb1 = 2\n", "scene.toml", {"material.b1=4"}, reporter);
    ASSERT_EQ(reporter.warnings.size(), 1u);
    EXPECT_TRUE(reporter.warnings[0].starts_with("--set material.b1=4: [material] key 'b1': "))
        << reporter.warnings[0];
}

// --- warnings -----------------------------------------------------------------------------

TEST(SceneWarnings, MNotGreaterThanN) {
    RecordingReporter reporter;
    const Scene scene = parseScene("[material]\nm = 3\nn = 3\n", "scene.toml", {}, reporter);
    EXPECT_EQ(scene.material.m, 3.0);
    ASSERT_EQ(reporter.warnings.size(), 1u);
    EXPECT_TRUE(reporter.warnings[0].starts_with("scene.toml:2:5: [material] key 'm': m = 3"))
        << reporter.warnings[0];
    EXPECT_TRUE(contains(reporter.warnings[0], "not greater than n = 3")) << reporter.warnings[0];
}

TEST(SceneWarnings, B1OutsideOneToThree) {
    for (const char* b1 : {"0.5", "3.5"}) {
        RecordingReporter reporter;
        parseScene(std::string("[material]\nb1 = ") + b1 + "\n", "scene.toml", {}, reporter);
        ASSERT_EQ(reporter.warnings.size(), 1u) << b1;
        EXPECT_TRUE(reporter.warnings[0].starts_with("scene.toml:2:6: [material] key 'b1': "))
            << reporter.warnings[0];
        EXPECT_TRUE(contains(reporter.warnings[0], "outside the paper's stable range [1, 3]"))
            << reporter.warnings[0];
    }
    for (const char* b1 : {"1", "3", "2.2"}) {
        RecordingReporter reporter;
        parseScene(std::string("[material]\nb1 = ") + b1 + "\n", "scene.toml", {}, reporter);
        EXPECT_TRUE(reporter.warnings.empty()) << b1 << ": " << reporter.warnings[0];
    }
}

TEST(SceneWarnings, DefaultsWarnNothing) {
    RecordingReporter reporter;
    parseScene("", "scene.toml", {}, reporter);
    EXPECT_TRUE(reporter.warnings.empty());
    EXPECT_TRUE(reporter.infos.empty());
}

// --- defaults and the resolved scene ---------------------------------------------------

TEST(SceneDefaults, EmptyTextIsTheDocumentedLiquid) {
    const Scene scene = parse("");
    EXPECT_EQ(scene.material.preset, "liquid");
    EXPECT_EQ(scene.material.r0, 1.0);
    EXPECT_EQ(scene.material.b1, 2.0);
    EXPECT_EQ(scene.material.m, 5.0);
    EXPECT_EQ(scene.material.n, 3.0);
    EXPECT_EQ(scene.material.alpha, 1.5);
    EXPECT_EQ(scene.material.resolvedCr(), 1.0);
    EXPECT_EQ(scene.material.resolvedCd(), 1.5);
    ASSERT_EQ(scene.emitters.size(), 1u);
    EXPECT_EQ(scene.emitters[0].type, "helix");
    EXPECT_EQ(scene.emitters[0].count, 400);
    EXPECT_EQ(scene.emitters[0].radius, 1.0);
    EXPECT_EQ(scene.simulation.dt, 0.001);
    EXPECT_EQ(scene.simulation.fps, 25.0);
    EXPECT_EQ(scene.simulation.frames, 150);
    EXPECT_EQ(scene.simulation.integrator, "forward_euler");
    EXPECT_EQ(scene.simulation.gravity, (Vec3{0, -9.8, 0}));
    EXPECT_EQ(scene.simulation.substepsPerFrame(), 40);
    EXPECT_TRUE(scene.ground.enabled);
    EXPECT_EQ(scene.ground.ks, 5000.0);
    EXPECT_EQ(scene.ground.kd, 300.0);
    EXPECT_FALSE(scene.output.ply);
    EXPECT_TRUE(scene.file.empty());
}

TEST(SceneDefaults, DefaultSceneTextParses) {
    RecordingReporter reporter;
    const Scene scene = parseScene(defaultSceneText(), "<default scene>", {}, reporter);
    EXPECT_TRUE(reporter.warnings.empty());
    EXPECT_EQ(scene.material.preset, "liquid");
    ASSERT_EQ(scene.emitters.size(), 1u);
    EXPECT_EQ(scene.material.alpha, 1.5);  // the paper's best liquid, Fig. 1
    EXPECT_EQ(scene.emitters[0].type, "spout");
    EXPECT_EQ(scene.emitters[0].count, 800);
    EXPECT_EQ(scene.emitters[0].center, (Vec3{0, 16, 0}));
    EXPECT_EQ(scene.simulation.frames, 100);
    EXPECT_EQ(scene.simulation.dt, 0.001);
    ASSERT_EQ(scene.colliders.size(), 1u);  // the glass
    EXPECT_EQ(scene.render.mode, "surface");
    EXPECT_EQ(scene.render.toneMapping, "aces");
}

/// Keys of each section of a resolved scene, in the order met ("emitter[1]" for arrays).
std::map<std::string, std::set<std::string>> keysBySection(const std::string& toml) {
    std::map<std::string, std::set<std::string>> out;
    std::map<std::string, int> arrayCounts;
    std::string section;
    std::istringstream in(toml);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        if (line.starts_with("[[")) {
            const std::string name = line.substr(2, line.find("]]") - 2);
            section = name + "[" + std::to_string(arrayCounts[name]++) + "]";
            out[section];
        } else if (line[0] == '[') {
            section = line.substr(1, line.find(']') - 1);
            out[section];
        } else if (auto eq = line.find(" = "); eq != std::string::npos) {
            out[section].insert(line.substr(0, eq));
        }
    }
    return out;
}

const char* kRichScene = R"(
[simulation]
dt = 0.0005
frames = 12
integrator = "velocity_verlet"
gravity = [0.1, -3, 0]
seed = 7

[material]
preset = "solid"
b1 = 2.25
m = 6
n = 2.5
t_solid = 30
t_liquid = 45

[material.liquid]
preset = "liquid"
b1 = 1.5

[ground]
enabled = false
contact = "surface"

[thermal]
enabled = true
cooling = 0.5

[output]
ply = true

[[emitter]]
type = "box"
min = [-1, 1, -1]
max = [1, 2, 1]
count = 0

[[emitter]]
type = "spout"
rate = 120
direction = [0.3, -1, 0]

[[emitter]]
type = "points"
file = "cloud.ply"
offset = [0, 0.3, 0]
)";

TEST(SceneResolved, RoundTripIsIdentical) {
    const Scene scene = parse(kRichScene, {"material.b1=2.75", "emitter.0.jitter=0"});
    const std::string resolved = resolvedSceneToml(scene);
    const Scene again = parse(resolved);
    EXPECT_EQ(resolvedSceneToml(again), resolved);

    EXPECT_EQ(again.simulation.dt, 0.0005);
    EXPECT_EQ(again.simulation.frames, 12);
    EXPECT_EQ(again.simulation.integrator, "velocity_verlet");
    EXPECT_EQ(again.simulation.gravity, (Vec3{0.1, -3, 0}));
    EXPECT_EQ(again.simulation.seed, 7);
    EXPECT_EQ(again.material.preset, "solid");
    EXPECT_EQ(again.material.b1, 2.75);
    EXPECT_FALSE(again.ground.enabled);
    EXPECT_TRUE(again.output.ply);
    ASSERT_EQ(again.emitters.size(), 3u);
    EXPECT_EQ(again.emitters[0].type, "box");
    EXPECT_EQ(again.emitters[0].jitter, 0.0);
    EXPECT_EQ(again.emitters[1].rate, 120.0);
    EXPECT_EQ(again.emitters[1].direction, (Vec3{0.3, -1, 0}));
    // Relative to the scene file's folder (here the working directory): named absolutely,
    // so DIR/scene.toml re-runs from any directory.
    EXPECT_EQ(again.emitters[2].file, (fs::current_path() / "cloud.ply").string());
}

TEST(SceneResolved, DefaultSceneRoundTrips) {
    const std::string resolved = resolvedSceneToml(parse(defaultSceneText()));
    EXPECT_EQ(resolvedSceneToml(parse(resolved)), resolved);
    EXPECT_TRUE(contains(resolved, "# Source: <default scene>")) << resolved;
}

TEST(SceneResolved, ContainsEveryKeyThatApplies) {
    Scene scene = parse(kRichScene);
    const auto keys = keysBySection(resolvedSceneToml(scene));

    SceneSections sections = bindSections(scene, {});
    for (const auto& section : sections.singles) {
        const std::vector<std::string> expected = section.keys();
        ASSERT_TRUE(keys.count(section.name())) << section.name();
        EXPECT_EQ(keys.at(section.name()), std::set<std::string>(expected.begin(), expected.end()))
            << section.name();
    }
    using Keys = std::set<std::string>;
    const Keys common = {"type", "radius", "mass", "jitter", "material", "temperature"};
    auto with = [&](Keys extra) {
        extra.insert(common.begin(), common.end());
        return extra;
    };
    std::size_t elements = 0;
    for (const auto& [name, array] : sections.arrays) {
        elements += array.size();
        if (name == "emitter") continue;  // which keys apply depends on the type: below
        for (std::size_t i = 0; i < array.size(); ++i) {
            const std::string element = name + "[" + std::to_string(i) + "]";
            const std::vector<std::string> expected = array[i].keys();
            ASSERT_TRUE(keys.count(element)) << element;
            EXPECT_EQ(keys.at(element), std::set<std::string>(expected.begin(), expected.end()))
                << element;
        }
    }
    EXPECT_EQ(scene.emitters.size(), 3u);
    // The phases: each a table of the material's constants (the one not given, its own).
    const std::set<std::string> constants = {"preset", "r0", "b1", "m", "n", "alpha", "cr", "cd"};
    EXPECT_EQ(keys.at("material.solid"), constants);
    EXPECT_EQ(keys.at("material.liquid"), constants);
    ASSERT_EQ(keys.size(), sections.singles.size() + elements + 2);
    EXPECT_EQ(keys.at("emitter[0]"), with({"count", "velocity", "min", "max", "spacing"}));
    EXPECT_EQ(keys.at("emitter[1]"), with({"count", "center", "spacing", "direction", "speed",
                                           "rate", "nozzle_radius", "start"}));
    EXPECT_EQ(keys.at("emitter[2]"), with({"velocity", "file", "offset"}));

    // Without temperature, its keys are left out: read back, they would be an error.
    const auto defaults = keysBySection(resolvedSceneToml(parse("")));
    Keys helix = with({"count", "velocity", "center", "helix_radius", "spacing", "turn"});
    helix.erase("temperature");
    EXPECT_EQ(defaults.at("emitter[0]"), helix);
    EXPECT_EQ(defaults.at("thermal"), Keys{"enabled"});
    for (const char* key : {"heat_capacity", "conductivity", "expansion", "t_solid", "t_liquid"}) {
        EXPECT_FALSE(defaults.at("material").count(key)) << key;
    }
}

TEST(SceneResolved, NamesTheSourceFile) {
    Scene scene = parse("");
    scene.file = "/tmp/some/scene.toml";
    EXPECT_TRUE(contains(resolvedSceneToml(scene), "# Source: /tmp/some/scene.toml\n"));
}

// --- files ----------------------------------------------------------------------------------

TEST(SceneFiles, LoadSceneNamesTheFile) {
    const fs::path dir = fs::temp_directory_path() / "globular_scene_test";
    fs::create_directories(dir);
    const fs::path file = dir / "bad.toml";
    {
        std::ofstream out(file);
        out << "[simulation]\nframes = 4\n\n[[emitter]]\nradius = -2\n";
    }
    NullReporter quiet;
    try {
        loadScene(file, {}, quiet);
        ADD_FAILURE() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  file.string() + ":5:10: [emitter[0]] key 'radius' = -2: must be > 0");
    }
    {
        std::ofstream out(file);
        out << "[simulation]\nframes = 4\n";
    }
    const Scene scene = loadScene(file, {"simulation.frames=6"}, quiet);
    EXPECT_EQ(scene.simulation.frames, 6);
    EXPECT_EQ(scene.file, fs::absolute(file));
    EXPECT_EQ(scene.directory(), fs::absolute(dir));
    fs::remove_all(dir);
}

TEST(SceneFiles, MissingFileIsBadUsageNamingThePath) {
    NullReporter quiet;
    const fs::path missing = fs::temp_directory_path() / "globular_no_such_scene.toml";
    try {
        loadScene(missing, {}, quiet);
        ADD_FAILURE() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_TRUE(contains(e.what(), missing.string())) << e.what();
    }
}

}  // namespace
}  // namespace globular
