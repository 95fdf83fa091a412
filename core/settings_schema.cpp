#include "settings_schema.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "errors.h"

namespace globular {

std::string numberForMessage(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

namespace {

std::string typeName(const SettingValue::Data& data) {
    switch (data.index()) {
        case 0: return "a boolean";
        case 1: return "an integer";
        case 2: return "a number";
        case 3: return "a string";
        default: return "an array";
    }
}

std::string valueText(const SettingValue::Data& data) {
    if (auto* b = std::get_if<bool>(&data)) return *b ? "true" : "false";
    if (auto* i = std::get_if<int64_t>(&data)) return std::to_string(*i);
    if (auto* d = std::get_if<double>(&data)) return numberForMessage(*d);
    if (auto* s = std::get_if<std::string>(&data)) return "\"" + quoteForMessage(*s) + "\"";
    std::string text = "[";
    for (double v : std::get<std::vector<double>>(data)) {
        text += (text.size() > 1 ? ", " : "") + numberForMessage(v);
    }
    return text + "]";
}

[[noreturn]] void fail(const std::string& where, const SettingValue& value,
                       const std::string& problem) {
    throw SceneError(where + " = " + valueText(value.data) + ": " + problem);
}

/// Reads a number from an integer or a float value.
double asNumber(const SettingValue& value, const std::string& where) {
    if (auto* d = std::get_if<double>(&value.data)) return *d;
    if (auto* i = std::get_if<int64_t>(&value.data)) return double(*i);
    fail(where, value, "expected a number, got " + typeName(value.data));
}

std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                               diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

std::string SourcePlace::describe() const {
    const std::string name = quoteForMessage(file, 300);
    if (line <= 0) return name;
    return name + ":" + std::to_string(line) + ":" + std::to_string(column);
}

bool NumberRange::contains(double v) const {
    if (minExclusive ? !(v > min) : !(v >= min)) return false;
    if (maxExclusive ? !(v < max) : !(v <= max)) return false;
    return true;
}

std::string NumberRange::describe() const {
    const bool hasMin = std::isfinite(min), hasMax = std::isfinite(max);
    if (hasMin && hasMax) {
        return std::string("in ") + (minExclusive ? "(" : "[") + numberForMessage(min) + ", " +
               numberForMessage(max) + (maxExclusive ? ")" : "]");
    }
    if (hasMin) return (minExclusive ? "> " : ">= ") + numberForMessage(min);
    if (hasMax) return (maxExclusive ? "< " : "<= ") + numberForMessage(max);
    return "finite";
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const auto& candidate : candidates) {
        std::size_t d = editDistance(word, candidate);
        if (d < bestDistance) {
            bestDistance = d;
            best = candidate;
        }
    }
    return best;
}

SettingsSection::Entry& SettingsSection::add(const std::string& key, std::string doc) {
    mEntries.push_back({key, std::move(doc), {}, {}});
    return mEntries.back();
}

SettingsSection& SettingsSection::number(const std::string& key, double& field,
                                         NumberRange range, std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field, range](const SettingValue& v, const std::string& where) {
        double x = asNumber(v, where);
        if (!std::isfinite(x)) fail(where, v, "must be a finite number");
        if (!range.contains(x)) fail(where, v, "must be " + range.describe());
        field = x;
    };
    e.current = [&field] { return SettingValue::Data(field); };
    return *this;
}

SettingsSection& SettingsSection::integer(const std::string& key, int64_t& field, int64_t min,
                                          int64_t max, std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field, min, max](const SettingValue& v, const std::string& where) {
        auto* i = std::get_if<int64_t>(&v.data);
        if (!i) fail(where, v, "expected an integer, got " + typeName(v.data));
        if (*i < min || *i > max) {
            fail(where, v,
                 "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
        }
        field = *i;
    };
    e.current = [&field] { return SettingValue::Data(field); };
    return *this;
}

SettingsSection& SettingsSection::flag(const std::string& key, bool& field, std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field](const SettingValue& v, const std::string& where) {
        auto* b = std::get_if<bool>(&v.data);
        if (!b) fail(where, v, "expected true or false, got " + typeName(v.data));
        field = *b;
    };
    e.current = [&field] { return SettingValue::Data(field); };
    return *this;
}

SettingsSection& SettingsSection::text(const std::string& key, std::string& field,
                                       std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field](const SettingValue& v, const std::string& where) {
        auto* s = std::get_if<std::string>(&v.data);
        if (!s) fail(where, v, "expected a string, got " + typeName(v.data));
        // A NUL would silently cut a path; other control characters have no place in
        // a name or path either.
        if (std::any_of(s->begin(), s->end(),
                        [](char c) { return static_cast<unsigned char>(c) < 0x20; })) {
            fail(where, v, "contains a control character (NUL, newline, ...)");
        }
        field = *s;
    };
    e.current = [&field] { return SettingValue::Data(field); };
    return *this;
}

SettingsSection& SettingsSection::choice(const std::string& key, std::string& field,
                                         std::vector<std::string> choices, std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field, choices](const SettingValue& v, const std::string& where) {
        auto* s = std::get_if<std::string>(&v.data);
        if (!s) fail(where, v, "expected a string, got " + typeName(v.data));
        if (std::find(choices.begin(), choices.end(), *s) == choices.end()) {
            std::string list;
            for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
            std::string hint = closestMatch(*s, choices);
            fail(where, v,
                 "must be one of " + list + (hint.empty() ? "" : " (did you mean " + hint + "?)"));
        }
        field = *s;
    };
    e.current = [&field] { return SettingValue::Data(field); };
    return *this;
}

SettingsSection& SettingsSection::vec3(const std::string& key, Vec3& field, NumberRange range,
                                       std::string doc) {
    Entry& e = add(key, std::move(doc));
    e.assign = [&field, range](const SettingValue& v, const std::string& where) {
        auto* a = std::get_if<std::vector<double>>(&v.data);
        if (!a || a->size() != 3) {
            fail(where, v, "expected an array of 3 numbers [x, y, z]");
        }
        for (double c : *a) {
            if (!std::isfinite(c)) fail(where, v, "components must be finite numbers");
            if (!range.contains(c)) fail(where, v, "components must be " + range.describe());
        }
        field = {(*a)[0], (*a)[1], (*a)[2]};
    };
    e.current = [&field] {
        return SettingValue::Data(std::vector<double>{field.x, field.y, field.z});
    };
    return *this;
}

SettingsSection& SettingsSection::retired(const std::string& key, std::string why) {
    mRetired[key] = std::move(why);
    return *this;
}

void SettingsSection::assign(const std::string& key, const SettingValue& value) {
    auto it = std::find_if(mEntries.begin(), mEntries.end(),
                           [&](const Entry& e) { return e.key == key; });
    const std::string where =
        value.place.describe() + ": [" + mName + "] key '" + quoteForMessage(key, 80) + "'";
    if (it == mEntries.end()) {
        if (auto retired = mRetired.find(key); retired != mRetired.end()) {
            throw SceneError(where + ": no longer exists; " + retired->second);
        }
        std::string hint = closestMatch(key, keys());
        throw SceneError(where + ": unknown key" +
                         (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
    }
    it->assign(value, where);
    mPlaces[key] = value.place;
}

std::vector<std::string> SettingsSection::keys() const {
    std::vector<std::string> out;
    for (const auto& e : mEntries) out.push_back(e.key);
    return out;
}

std::vector<std::pair<std::string, SettingValue::Data>> SettingsSection::values() const {
    std::vector<std::pair<std::string, SettingValue::Data>> out;
    for (const auto& e : mEntries) out.emplace_back(e.key, e.current());
    return out;
}

std::string SettingsSection::docOf(const std::string& key) const {
    for (const auto& e : mEntries) {
        if (e.key == key) return e.doc;
    }
    return "";
}

const SourcePlace* SettingsSection::placeOf(const std::string& key) const {
    auto it = mPlaces.find(key);
    return it == mPlaces.end() ? nullptr : &it->second;
}

std::string SettingsSection::describeKey(const std::string& key) const {
    const SourcePlace* place = placeOf(key);
    return (place ? place->describe() + ": " : "") + "[" + mName + "] key '" + key + "'";
}

}  // namespace globular
