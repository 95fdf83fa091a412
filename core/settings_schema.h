#pragma once
// Binds the keys of one scene section to typed fields with defaults, ranges and docs.
// Each settings struct describes itself into a SettingsSection; the scene reader feeds
// values parsed from TOML (or --set) through assign(), which type- and range-checks
// them and reports errors naming file, line, column and key. Knows nothing of TOML.

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "vec3.h"

namespace globular {

/// Where a value came from: "scene.toml:12:5", or "--set material.b1=3".
struct SourcePlace {
    std::string file;
    int line = 0;  ///< 0 when the value has no line (an override)
    int column = 0;
    std::string describe() const;
};

/// A value as parsed from a scene, before it is bound to a field.
struct SettingValue {
    using Data = std::variant<bool, int64_t, double, std::string, std::vector<double>>;
    Data data;
    SourcePlace place;
};

struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minExclusive = false;
    bool maxExclusive = false;

    static NumberRange positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
    static NumberRange nonNegative() { return {0.0}; }
    static NumberRange between(double lo, double hi) { return {lo, hi}; }
    static NumberRange any() { return {}; }
    bool contains(double value) const;
    std::string describe() const;  ///< "> 0", "in [0, 1]", ...
};

class SettingsSection {
public:
    /// @param name the section's path in the scene: "material", "emitter[2]".
    explicit SettingsSection(std::string name) : mName(std::move(name)) {}

    SettingsSection& number(const std::string& key, double& field, NumberRange range,
                            std::string doc);
    SettingsSection& integer(const std::string& key, int64_t& field, int64_t min, int64_t max,
                             std::string doc);
    SettingsSection& flag(const std::string& key, bool& field, std::string doc);
    SettingsSection& text(const std::string& key, std::string& field, std::string doc);
    SettingsSection& choice(const std::string& key, std::string& field,
                            std::vector<std::string> choices, std::string doc);
    /// A 3-vector written as [x, y, z]; each component checked against @p range.
    SettingsSection& vec3(const std::string& key, Vec3& field, NumberRange range,
                          std::string doc);

    /// A key that no longer exists: assigning it is a SceneError saying @p why (what
    /// replaced it), instead of "unknown key". Not among keys().
    SettingsSection& retired(const std::string& key, std::string why);

    /// Binds @p value to @p key.
    /// @throw SceneError naming the place, section and key: unknown key (with a
    ///        suggestion), wrong type, value out of range, not finite.
    void assign(const std::string& key, const SettingValue& value);

    const std::string& name() const { return mName; }
    std::vector<std::string> keys() const;
    /// The current value of every key, in declaration order, for the resolved scene.
    std::vector<std::pair<std::string, SettingValue::Data>> values() const;
    /// The one-line documentation of @p key ("" when unknown).
    std::string docOf(const std::string& key) const;
    /// Where @p key was set, or nullptr when it kept its default.
    const SourcePlace* placeOf(const std::string& key) const;
    /// "[material] key 'b1'" plus its place when it was set: for validation messages.
    std::string describeKey(const std::string& key) const;

private:
    struct Entry {
        std::string key;
        std::string doc;
        std::function<void(const SettingValue&, const std::string& where)> assign;
        std::function<SettingValue::Data()> current;
    };
    Entry& add(const std::string& key, std::string doc);

    std::string mName;
    std::vector<Entry> mEntries;
    std::map<std::string, SourcePlace> mPlaces;
    std::map<std::string, std::string> mRetired;  // key -> what replaced it
};

/// A number as messages quote it: the shortest default form ("25", "4e+07", "0.001").
std::string numberForMessage(double value);

/// The closest of @p candidates to @p word by edit distance, or "" when none is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace globular
