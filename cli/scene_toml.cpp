// Reading scenes from TOML (toml++) and writing the resolved scene back.

#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "errors.h"
#include "reporter.h"
#include "scene.h"
#include "settings_schema.h"

namespace globular {

namespace {

struct OverridePlaces {
    std::vector<std::pair<std::string, std::string>> byPath;  ///< "material.b1" -> "--set ..."
    const std::string* find(const std::string& path) const {
        for (const auto& [p, text] : byPath) {
            if (p == path) return &text;
        }
        return nullptr;
    }
};

SourcePlace placeOf(const toml::node& node, const std::string& sourceName,
                    const std::string& path, const OverridePlaces& overrides) {
    if (const std::string* text = overrides.find(path)) return SourcePlace{*text, 0, 0};
    const auto& src = node.source();
    return SourcePlace{sourceName, int(src.begin.line), int(src.begin.column)};
}

[[noreturn]] void failAt(const SourcePlace& place, const std::string& message) {
    throw SceneError(place.describe() + ": " + message);
}

SettingValue toValue(const toml::node& node, const SourcePlace& place, const std::string& key) {
    SettingValue v;
    v.place = place;
    if (auto b = node.as_boolean()) {
        v.data = b->get();
    } else if (auto i = node.as_integer()) {
        v.data = int64_t(i->get());
    } else if (auto d = node.as_floating_point()) {
        v.data = d->get();
    } else if (auto s = node.as_string()) {
        v.data = s->get();
    } else if (auto a = node.as_array()) {
        std::vector<double> numbers;
        for (const auto& element : *a) {
            if (auto ei = element.as_integer()) {
                numbers.push_back(double(ei->get()));
            } else if (auto ed = element.as_floating_point()) {
                numbers.push_back(ed->get());
            } else {
                failAt(place, "key '" + key + "': arrays may hold only numbers");
            }
        }
        v.data = numbers;
    } else {
        failAt(place, "key '" + key + "': expected a number, boolean, string or array");
    }
    return v;
}

void bindTable(const toml::table& table, SettingsSection& section, const std::string& pathPrefix,
               const std::string& sourceName, const OverridePlaces& overrides) {
    for (const auto& [key, node] : table) {
        const std::string k(key.str());
        const std::string path = pathPrefix + "." + k;
        const SourcePlace place = placeOf(node, sourceName, path, overrides);
        if (node.is_table() || node.is_array_of_tables()) {
            failAt(place, "[" + section.name() + "] key '" + k +
                              "': nested tables are not part of any section");
        }
        section.assign(k, toValue(node, place, k));
    }
}

/// Parses "a.b.c=value" and writes value at that path of @p root.
void applyOverride(toml::table& root, const std::string& text, OverridePlaces& places) {
    const std::string where = "--set " + text;
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw SceneError(where + ": expected KEY=VALUE, e.g. --set material.b1=3");
    }
    const std::string path = text.substr(0, eq), valueText = text.substr(eq + 1);
    std::vector<std::string> parts;
    std::stringstream split(path);
    for (std::string part; std::getline(split, part, '.');) parts.push_back(part);
    if (parts.size() < 2) {
        throw SceneError(where + ": the key needs a section, e.g. material.b1 or emitter.0.count");
    }
    // The value is TOML; a bare word that is not TOML is taken as a string (render.mode=surface).
    toml::node_view<toml::node> parsedValue;
    toml::table holder;
    try {
        holder = toml::parse("v = " + valueText);
    } catch (const toml::parse_error&) {
        holder = toml::table{{"v", valueText}};
    }
    toml::table* table = &root;
    std::size_t i = 0;
    for (; i + 1 < parts.size(); ++i) {
        const std::string& part = parts[i];
        toml::node* next = table->get(part);
        if (i + 2 < parts.size() && std::all_of(parts[i + 1].begin(), parts[i + 1].end(), ::isdigit)) {
            // section.N.key: element N of an array of tables; N == size appends one.
            if (!next) next = &table->insert_or_assign(part, toml::array{}).first->second;
            toml::array* array = next->as_array();
            if (!array) throw SceneError(where + ": '" + part + "' is not an array of tables");
            const std::size_t index = std::stoul(parts[i + 1]);
            if (index > array->size()) {
                throw SceneError(where + ": there are only " + std::to_string(array->size()) +
                                 " [[" + part + "]] sections (indices start at 0)");
            }
            if (index == array->size()) array->push_back(toml::table{});
            table = array->get(index)->as_table();
            if (!table) throw SceneError(where + ": [[" + part + "]] element is not a table");
            ++i;
            continue;
        }
        if (!next) next = &table->insert_or_assign(part, toml::table{}).first->second;
        table = next->as_table();
        if (!table) throw SceneError(where + ": '" + part + "' is not a section");
    }
    table->insert_or_assign(parts.back(), *holder.get("v"));
    places.byPath.emplace_back(path, where);
}

std::string arrayIndexPath(const std::string& name, std::size_t index) {
    return name + "." + std::to_string(index);
}

toml::table sectionToToml(const SettingsSection& section) {
    toml::table table;
    for (const auto& [key, data] : section.values()) {
        std::visit(
            [&](const auto& v) {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, std::vector<double>>) {
                    toml::array array;
                    for (double x : v) array.push_back(x);
                    table.insert(key, array);
                } else {
                    table.insert(key, v);
                }
            },
            data);
    }
    return table;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides, Reporter& reporter) {
    toml::table root;
    try {
        root = toml::parse(text, sourceName);
    } catch (const toml::parse_error& e) {
        const auto& src = e.source();
        throw SceneError(SourcePlace{sourceName, int(src.begin.line), int(src.begin.column)}
                             .describe() +
                         ": " + std::string(e.description()));
    }
    OverridePlaces places;
    for (const auto& o : overrides) applyOverride(root, o, places);

    Scene scene;
    std::vector<std::pair<std::string, std::size_t>> arraySizes;
    for (const auto& [key, node] : root) {
        if (auto* array = node.as_array()) arraySizes.emplace_back(std::string(key.str()), array->size());
    }
    SceneSections sections = bindSections(scene, arraySizes);
    for (const auto& [key, node] : root) {
        const std::string name(key.str());
        const SourcePlace place = placeOf(node, sourceName, name, places);
        if (SettingsSection* section = sections.single(name)) {
            const toml::table* table = node.as_table();
            if (!table) failAt(place, "'" + name + "' must be a section: [" + name + "]");
            bindTable(*table, *section, name, sourceName, places);
        } else if (auto* elements = sections.array(name)) {
            const toml::array* array = node.as_array();
            if (!array || !array->is_array_of_tables()) {
                failAt(place, "'" + name + "' must be written as [[" + name + "]] sections");
            }
            for (std::size_t i = 0; i < array->size(); ++i) {
                bindTable(*array->get(i)->as_table(), (*elements)[i], arrayIndexPath(name, i),
                          sourceName, places);
            }
        } else {
            const std::string hint = closestMatch(name, sections.names());
            failAt(place, "unknown section '" + name + "'" +
                              (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
        }
    }
    validateScene(scene, sections, reporter);
    return scene;
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                Reporter& reporter) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw IoError("cannot open scene file " + file.string());
    std::stringstream text;
    text << in.rdbuf();
    Scene scene = parseScene(text.str(), file.string(), overrides, reporter);
    scene.file = std::filesystem::absolute(file);
    return scene;
}

std::string resolvedSceneToml(const Scene& constScene) {
    Scene scene = constScene;  // sections bind mutable fields; write from a copy
    std::vector<std::pair<std::string, std::size_t>> sizes;
    SceneSections sections = bindSections(scene, sizes);
    toml::table root;
    for (const auto& section : sections.singles) root.insert(section.name(), sectionToToml(section));
    for (const auto& [name, elements] : sections.arrays) {
        toml::array array;
        for (const auto& element : elements) array.push_back(sectionToToml(element));
        root.insert(name, array);
    }
    std::ostringstream out;
    out << "# The resolved scene: every key with the value the run used.\n"
        << "# Source: " << (scene.file.empty() ? "<default scene>" : scene.file.string())
        << "\n\n"
        << root << "\n";
    return out.str();
}

}  // namespace globular
