// SettingsSection: typed, ranged binding of scene keys to fields, with errors that name
// the place, the section, the key and the offending value.

#include "settings_schema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "errors.h"

namespace globular {
namespace {

SettingValue at(SettingValue::Data data, int line = 3, int column = 7) {
    return SettingValue{std::move(data), SourcePlace{"scene.toml", line, column}};
}

/// The message of the SceneError @p f throws; fails the test when it throws nothing.
template <typename F>
std::string sceneError(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a SceneError";
    return "";
}

struct Fields {
    double speed = 2.5;
    int64_t count = 10;
    bool enabled = true;
    std::string file = "a.ply";
    std::string mode = "surface";
    Vec3 center{1, 2, 3};
    Vec3 scale{1, 1, 1};
};

SettingsSection bind(Fields& f) {
    SettingsSection s("thing");
    s.number("speed", f.speed, NumberRange::positive(), "units / s")
        .integer("count", f.count, 0, 100, "globules")
        .flag("enabled", f.enabled, "on or off")
        .text("file", f.file, "a path")
        .choice("mode", f.mode, {"spheres", "surface"}, "how to draw")
        .vec3("center", f.center, NumberRange::any(), "world units")
        .vec3("scale", f.scale, NumberRange::positive(), "factors");
    return s;
}

TEST(SourcePlace, DescribesFileLineColumnOrOverride) {
    EXPECT_EQ((SourcePlace{"scene.toml", 12, 5}.describe()), "scene.toml:12:5");
    EXPECT_EQ((SourcePlace{"--set material.b1=3", 0, 0}.describe()), "--set material.b1=3");
}

TEST(NumberRange, ContainsAndDescribes) {
    EXPECT_FALSE(NumberRange::positive().contains(0.0));
    EXPECT_TRUE(NumberRange::positive().contains(1e-300));
    EXPECT_EQ(NumberRange::positive().describe(), "> 0");
    EXPECT_TRUE(NumberRange::nonNegative().contains(0.0));
    EXPECT_FALSE(NumberRange::nonNegative().contains(-1e-9));
    EXPECT_EQ(NumberRange::nonNegative().describe(), ">= 0");
    EXPECT_TRUE(NumberRange::between(1, 3).contains(3.0));
    EXPECT_FALSE(NumberRange::between(1, 3).contains(3.0001));
    EXPECT_EQ(NumberRange::between(1, 3).describe(), "in [1, 3]");
    EXPECT_EQ(NumberRange::any().describe(), "finite");
    EXPECT_FALSE(NumberRange::any().contains(std::nan("")));
}

TEST(SettingsSection, BindsEveryType) {
    Fields f;
    SettingsSection s = bind(f);
    s.assign("speed", at(4.25));
    s.assign("count", at(int64_t(42)));
    s.assign("enabled", at(false));
    s.assign("file", at(std::string("cloud.ply")));
    s.assign("mode", at(std::string("spheres")));
    s.assign("center", at(std::vector<double>{-1, 0.5, 8}));
    EXPECT_EQ(f.speed, 4.25);
    EXPECT_EQ(f.count, 42);
    EXPECT_FALSE(f.enabled);
    EXPECT_EQ(f.file, "cloud.ply");
    EXPECT_EQ(f.mode, "spheres");
    EXPECT_EQ(f.center, (Vec3{-1, 0.5, 8}));
}

// A retired key says what replaced it, and is neither a key nor a suggestion.
TEST(SettingsSection, RetiredKeySaysWhatReplacedIt) {
    Fields f;
    SettingsSection s = bind(f);
    s.retired("spead", "use speed");
    const std::string message = sceneError([&] { s.assign("spead", at(1.0)); });
    EXPECT_NE(message.find("[thing] key 'spead'"), std::string::npos) << message;
    EXPECT_NE(message.find("no longer exists; use speed"), std::string::npos) << message;
    for (const std::string& key : s.keys()) EXPECT_NE(key, "spead");
    EXPECT_EQ(f.speed, 2.5);
}

TEST(SettingsSection, NumberAcceptsAnInteger) {
    Fields f;
    SettingsSection s = bind(f);
    s.assign("speed", at(int64_t(7)));
    EXPECT_EQ(f.speed, 7.0);
}

TEST(SettingsSection, RangeErrorNamesPlaceSectionKeyAndValue) {
    Fields f;
    SettingsSection s = bind(f);
    const std::string message = sceneError([&] { s.assign("speed", at(-1.5, 12, 9)); });
    EXPECT_EQ(message, "scene.toml:12:9: [thing] key 'speed' = -1.5: must be > 0");
    EXPECT_EQ(f.speed, 2.5) << "a rejected value must leave the field alone";
    EXPECT_EQ(s.placeOf("speed"), nullptr) << "a rejected value was not set";
}

TEST(SettingsSection, IntegerRangeError) {
    Fields f;
    SettingsSection s = bind(f);
    const std::string message = sceneError([&] { s.assign("count", at(int64_t(101), 4, 1)); });
    EXPECT_EQ(message, "scene.toml:4:1: [thing] key 'count' = 101: must be in [0, 100]");
    EXPECT_EQ(f.count, 10);
    s.assign("count", at(int64_t(100)));
    EXPECT_EQ(f.count, 100);
    s.assign("count", at(int64_t(0)));
    EXPECT_EQ(f.count, 0);
}

TEST(SettingsSection, Vec3ComponentRangeError) {
    Fields f;
    SettingsSection s = bind(f);
    const std::string message = sceneError([&] {
        s.assign("scale", at(std::vector<double>{1, 0, 2}));
    });
    EXPECT_NE(message.find("scene.toml:3:7: [thing] key 'scale' = [1, 0, 2]"), std::string::npos)
        << message;
    EXPECT_NE(message.find("components must be > 0"), std::string::npos) << message;
    EXPECT_EQ(f.scale, (Vec3{1, 1, 1}));
}

TEST(SettingsSection, WrongTypeNamesExpectedAndGot) {
    Fields f;
    SettingsSection s = bind(f);
    EXPECT_EQ(sceneError([&] { s.assign("speed", at(std::string("fast"))); }),
              "scene.toml:3:7: [thing] key 'speed' = \"fast\": expected a number, got a string");
    EXPECT_EQ(sceneError([&] { s.assign("count", at(2.5)); }),
              "scene.toml:3:7: [thing] key 'count' = 2.5: expected an integer, got a number");
    EXPECT_EQ(sceneError([&] { s.assign("enabled", at(int64_t(1))); }),
              "scene.toml:3:7: [thing] key 'enabled' = 1: expected true or false, got an integer");
    EXPECT_EQ(sceneError([&] { s.assign("file", at(true)); }),
              "scene.toml:3:7: [thing] key 'file' = true: expected a string, got a boolean");
    EXPECT_EQ(sceneError([&] { s.assign("mode", at(std::vector<double>{1})); }),
              "scene.toml:3:7: [thing] key 'mode' = [1]: expected a string, got an array");
    const std::string wrongLength = sceneError([&] {
        s.assign("center", at(std::vector<double>{1, 2}));
    });
    EXPECT_NE(wrongLength.find("expected an array of 3 numbers"), std::string::npos) << wrongLength;
    const std::string notArray = sceneError([&] { s.assign("center", at(1.0)); });
    EXPECT_NE(notArray.find("expected an array of 3 numbers"), std::string::npos) << notArray;
    EXPECT_EQ(f.center, (Vec3{1, 2, 3}));
}

TEST(SettingsSection, RejectsNonFinite) {
    Fields f;
    SettingsSection s = bind(f);
    const double inf = std::numeric_limits<double>::infinity();
    const std::string nanMessage = sceneError([&] { s.assign("speed", at(std::nan(""))); });
    EXPECT_NE(nanMessage.find("[thing] key 'speed'"), std::string::npos) << nanMessage;
    EXPECT_NE(nanMessage.find("must be a finite number"), std::string::npos) << nanMessage;
    EXPECT_EQ(sceneError([&] { s.assign("speed", at(inf)); }),
              "scene.toml:3:7: [thing] key 'speed' = inf: must be a finite number");
    const std::string vecMessage = sceneError([&] {
        s.assign("center", at(std::vector<double>{0, -inf, 0}));
    });
    EXPECT_NE(vecMessage.find("components must be finite numbers"), std::string::npos)
        << vecMessage;
    EXPECT_EQ(f.speed, 2.5);
    EXPECT_EQ(f.center, (Vec3{1, 2, 3}));
}

TEST(SettingsSection, BadChoiceListsChoicesAndSuggests) {
    Fields f;
    SettingsSection s = bind(f);
    EXPECT_EQ(sceneError([&] { s.assign("mode", at(std::string("spheers"))); }),
              "scene.toml:3:7: [thing] key 'mode' = \"spheers\": must be one of spheres, "
              "surface (did you mean spheres?)");
    EXPECT_EQ(sceneError([&] { s.assign("mode", at(std::string("wireframe"))); }),
              "scene.toml:3:7: [thing] key 'mode' = \"wireframe\": must be one of spheres, "
              "surface");
    EXPECT_EQ(f.mode, "surface");
}

TEST(SettingsSection, UnknownKeySuggestsClosest) {
    Fields f;
    SettingsSection s = bind(f);
    EXPECT_EQ(sceneError([&] { s.assign("cuont", at(int64_t(3), 5, 1)); }),
              "scene.toml:5:1: [thing] key 'cuont': unknown key (did you mean 'count'?)");
    EXPECT_EQ(sceneError([&] { s.assign("velocity", at(int64_t(3), 5, 1)); }),
              "scene.toml:5:1: [thing] key 'velocity': unknown key");
}

TEST(SettingsSection, KeysInDeclarationOrder) {
    Fields f;
    SettingsSection s = bind(f);
    EXPECT_EQ(s.name(), "thing");
    EXPECT_EQ(s.keys(), (std::vector<std::string>{"speed", "count", "enabled", "file", "mode",
                                                  "center", "scale"}));
}

TEST(SettingsSection, ValuesReflectDefaultsAndAssignments) {
    Fields f;
    SettingsSection s = bind(f);
    using Data = SettingValue::Data;
    auto values = s.values();
    ASSERT_EQ(values.size(), 7u);
    EXPECT_EQ(values[0], (std::pair<std::string, Data>{"speed", 2.5}));
    EXPECT_EQ(values[1], (std::pair<std::string, Data>{"count", int64_t(10)}));
    EXPECT_EQ(values[2], (std::pair<std::string, Data>{"enabled", true}));
    EXPECT_EQ(values[3], (std::pair<std::string, Data>{"file", std::string("a.ply")}));
    EXPECT_EQ(values[4], (std::pair<std::string, Data>{"mode", std::string("surface")}));
    EXPECT_EQ(values[5], (std::pair<std::string, Data>{"center", std::vector<double>{1, 2, 3}}));

    s.assign("speed", at(9.0));
    s.assign("center", at(std::vector<double>{4, 5, 6}));
    f.count = 77;  // the section reads the bound fields, not a copy
    values = s.values();
    EXPECT_EQ(values[0].second, Data(9.0));
    EXPECT_EQ(values[1].second, Data(int64_t(77)));
    EXPECT_EQ(values[5].second, Data(std::vector<double>{4, 5, 6}));
}

TEST(SettingsSection, PlaceOfAndDescribeKey) {
    Fields f;
    SettingsSection s = bind(f);
    EXPECT_EQ(s.placeOf("speed"), nullptr);
    EXPECT_EQ(s.describeKey("speed"), "[thing] key 'speed'");
    s.assign("speed", at(3.0, 8, 2));
    ASSERT_NE(s.placeOf("speed"), nullptr);
    EXPECT_EQ(s.placeOf("speed")->describe(), "scene.toml:8:2");
    EXPECT_EQ(s.describeKey("speed"), "scene.toml:8:2: [thing] key 'speed'");
    s.assign("speed", SettingValue{4.0, SourcePlace{"--set thing.speed=4"}});
    EXPECT_EQ(s.describeKey("speed"), "--set thing.speed=4: [thing] key 'speed'");
}

TEST(ClosestMatch, PicksNearestWithinDistance) {
    const std::vector<std::string> sections = {"simulation", "material", "ground", "output",
                                               "emitter"};
    EXPECT_EQ(closestMatch("materail", sections), "material");
    EXPECT_EQ(closestMatch("emiter", sections), "emitter");
    EXPECT_EQ(closestMatch("simulaton", sections), "simulation");
    EXPECT_EQ(closestMatch("material", sections), "material");
    EXPECT_EQ(closestMatch("camera", sections), "");
    EXPECT_EQ(closestMatch("anything", {}), "");
}

TEST(ClosestMatch, ThresholdGrowsWithLength) {
    // Short words accept up to 2 edits; a 9-letter word accepts 3; never 4 for it.
    EXPECT_EQ(closestMatch("dx", {"dt"}), "dt");
    EXPECT_EQ(closestMatch("ab", {"xyz"}), "");
    EXPECT_EQ(closestMatch("abcdefghi", {"abcdefxyz"}), "abcdefxyz");
    EXPECT_EQ(closestMatch("abcdefghi", {"abcdewxyz"}), "");
}

TEST(ClosestMatch, PrefersSmallestDistanceThenFirst) {
    EXPECT_EQ(closestMatch("count", {"counts", "count"}), "count");
    EXPECT_EQ(closestMatch("mm", {"m", "n"}), "m");
    EXPECT_EQ(closestMatch("cd", {"cr", "cd"}), "cd");
    EXPECT_EQ(closestMatch("cx", {"cr", "cd"}), "cr");
}

}  // namespace
}  // namespace globular
