// Reading scenes from TOML (toml++) and writing the resolved scene back.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <toml++/toml.h>

#include "errors.h"
#include "reporter.h"
#include "scene.h"
#include "settings_schema.h"

namespace globular {

namespace {

/// Scene files larger than this are refused (the biggest real scene is a few KB).
constexpr std::size_t kMaxSceneBytes = std::size_t(4) << 20;

struct OverridePlaces {
    std::vector<std::pair<std::string, std::string>> byPath;  ///< "material.b1" -> "--set ..."
    /// The override that set @p path last (the one whose value the scene holds).
    const std::string* find(const std::string& path) const {
        for (auto it = byPath.rbegin(); it != byPath.rend(); ++it) {
            if (it->first == path) return &it->second;
        }
        return nullptr;
    }
    /// The first override below @p path ("materail" -> "--set materail.b1=3").
    const std::string* findUnder(const std::string& path) const {
        for (const auto& [p, text] : byPath) {
            if (p.compare(0, path.size() + 1, path + ".") == 0) return &text;
        }
        return nullptr;
    }
};

SourcePlace placeOf(const toml::node& node, const std::string& sourceName,
                    const std::string& path, const OverridePlaces& overrides) {
    if (const std::string* text = overrides.find(path)) return SourcePlace{*text, 0, 0};
    const auto& src = node.source();
    // A section that only an override created has no place in the file: name the override.
    if (src.begin.line == 0) {
        if (const std::string* text = overrides.findUnder(path)) return SourcePlace{*text, 0, 0};
    }
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

/// @param nested keys holding nested tables ([[collider.key]], [material.solid]), bound
///        by the caller.
void bindTable(const toml::table& table, SettingsSection& section, const std::string& pathPrefix,
               const std::string& sourceName, const OverridePlaces& overrides,
               const std::vector<std::string>& nested = {}) {
    for (const auto& [key, node] : table) {
        const std::string k(key.str());
        if (std::find(nested.begin(), nested.end(), k) != nested.end()) continue;
        const std::string path = pathPrefix + "." + k;
        const SourcePlace place = placeOf(node, sourceName, path, overrides);
        if (node.is_table() || node.is_array_of_tables()) {
            failAt(place, "[" + section.name() + "] key '" + k +
                              "': nested tables are not part of any section");
        }
        section.assign(k, toValue(node, place, k));
    }
}

/// Whether @p text is well-formed UTF-8, as TOML requires: toml++ checks what it parses,
/// but a bare --set word becomes a string unparsed and must not make the resolved scene
/// unreadable.
bool isUtf8(const std::string& text) {
    static constexpr char32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};  // no overlong forms
    std::size_t i = 0;
    while (i < text.size()) {
        const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
        const unsigned char lead = byte(i);
        const std::size_t n = lead < 0x80                    ? 1
                              : lead >= 0xC2 && lead <= 0xDF ? 2
                              : lead >= 0xE0 && lead <= 0xEF ? 3
                              : lead >= 0xF0 && lead <= 0xF4 ? 4
                                                             : 0;
        if (n == 0 || text.size() - i < n) return false;
        char32_t code = n == 1 ? lead : lead & (0x3Fu >> (n - 1));
        for (std::size_t k = 1; k < n; ++k) {
            if ((byte(i + k) & 0xC0) != 0x80) return false;
            code = (code << 6) | (byte(i + k) & 0x3F);
        }
        if (code < kLeast[n] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
            return false;
        }
        i += n;
    }
    return true;
}

/// Parses "a.b.c=value" and writes value at that path of @p root.
void applyOverride(toml::table& root, const std::string& text, OverridePlaces& places) {
    const std::string where = "--set " + quoteForMessage(text);
    // A newline would let the value carry more TOML (a second key, a section) that the
    // override then drops without a word.
    if (std::any_of(text.begin(), text.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 && c != '\t'; })) {
        throw SceneError(where + ": an override must be one line without control characters");
    }
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
    toml::table holder;
    try {
        holder = toml::parse("v = " + valueText);
    } catch (const toml::parse_error&) {
        if (!isUtf8(valueText)) throw SceneError(where + ": the value is not valid UTF-8");
        holder = toml::table{{"v", valueText}};
    }
    toml::table* table = &root;
    std::size_t i = 0;
    for (; i + 1 < parts.size(); ++i) {
        const std::string& part = parts[i];
        toml::node* next = table->get(part);
        const std::string& indexText = parts[i + 1];
        if (i + 2 < parts.size() && !indexText.empty() &&
            std::all_of(indexText.begin(), indexText.end(),
                        [](unsigned char c) { return std::isdigit(c) != 0; })) {
            // section.N.key: element N of an array of tables; N == size appends one.
            if (!next) next = &table->insert_or_assign(part, toml::array{}).first->second;
            toml::array* array = next->as_array();
            if (!array) throw SceneError(where + ": '" + part + "' is not an array of tables");
            // Compared as text first: stoul would throw on an index past its range.
            const std::size_t index =
                indexText.size() > 9 ? std::size_t(-1) : std::stoul(indexText);
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

/// The [[collider.key]] tables of one [[collider]] (at @p path, "collider.0"), in time
/// order.
void bindColliderKeys(const toml::table& element, ColliderSettings& collider,
                      const std::string& path, const std::string& sourceName,
                      const OverridePlaces& places) {
    const toml::node* node = element.get("key");
    if (!node) return;
    const toml::array* keys = node->as_array();
    const SourcePlace place = placeOf(*node, sourceName, path + ".key", places);
    if (!keys || !keys->is_array_of_tables()) {
        failAt(place, "'key' of a collider must be written as [[collider.key]] sections");
    }
    collider.keys.resize(keys->size());
    const std::string sectionName = "collider[" + path.substr(path.find('.') + 1) + "].key";
    for (std::size_t k = 0; k < keys->size(); ++k) {
        SettingsSection section(sectionName + "[" + std::to_string(k) + "]");
        collider.keys[k].describe(section);
        bindTable(*keys->get(k)->as_table(), section, path + ".key." + std::to_string(k),
                  sourceName, places);
        if (k > 0 && !(collider.keys[k].time > collider.keys[k - 1].time)) {
            throw SceneError(section.describeKey("time") + ": keys go in time order; " +
                             std::to_string(collider.keys[k].time) +
                             " s is not later than the key before it");
        }
    }
}

/// The [material.solid] and [material.liquid] tables of one material section (at @p path,
/// "material" or "material.1"; named @p sectionName in messages), into @p sections.
void bindPhases(const toml::table& table, MaterialSettings& material, const std::string& path,
                const std::string& sectionName, const std::string& sourceName,
                const OverridePlaces& places, std::vector<SettingsSection>& sections) {
    for (const auto& [which, constants] :
         {std::pair{"solid", &material.solid}, std::pair{"liquid", &material.liquid}}) {
        const toml::node* node = table.get(which);
        if (!node) continue;
        const std::string phasePath = path + "." + which;
        const toml::table* phase = node->as_table();
        if (!phase) {
            std::ostringstream message;  // (GCC 12 warns falsely on a chain of +)
            message << "'" << which << "' of a material must be a table: [" << sectionName << "."
                    << which << "]";
            failAt(placeOf(*node, sourceName, phasePath, places), message.str());
        }
        // A phase starts from the material's own constants: it names what differs.
        *constants = static_cast<const ForceConstants&>(material);
        SettingsSection section(sectionName + "." + which);
        MaterialSettings::describePhase(section, *constants);
        bindTable(*phase, section, phasePath, sourceName, places);
        material.phases = true;
        sections.push_back(std::move(section));
    }
}

/// A value as TOML text. Floats use the shortest form that reads back to the same double
/// (9.8, not 9.8000000000000007), so the resolved scene reproduces the run exactly.
std::string tomlText(const SettingValue::Data& data) {
    const auto number = [](double v) {
        char buffer[64];
        const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
        std::string text(buffer, end);
        if (text.find_first_of(".en") == std::string::npos) text += ".0";  // stay a float
        return text;
    };
    if (auto* b = std::get_if<bool>(&data)) return *b ? "true" : "false";
    if (auto* i = std::get_if<int64_t>(&data)) return std::to_string(*i);
    if (auto* d = std::get_if<double>(&data)) return number(*d);
    if (auto* a = std::get_if<std::vector<double>>(&data)) {
        std::string text = "[";
        for (std::size_t k = 0; k < a->size(); ++k) text += (k ? ", " : "") + number((*a)[k]);
        return text + "]";
    }
    std::string quoted = "\"";
    for (char c : std::get<std::string>(data)) {
        if (c == '"' || c == '\\') {
            quoted += '\\';
            quoted += c;
        } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {  // TOML forbids raw DEL
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\u%04x", c);
            quoted += escape;
        } else {
            quoted += c;
        }
    }
    return quoted + "\"";
}

std::string sectionText(const SettingsSection& section,
                        const std::function<bool(const std::string&)>& keep) {
    std::string text;
    for (const auto& [key, data] : section.values()) {
        if (keep(key)) text += key + " = " + tomlText(data) + "\n";
    }
    return text;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides, Reporter& reporter,
                 const std::filesystem::path& file) {
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
    scene.file = file;
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
            const bool material = name == "material";
            bindTable(*table, *section, name, sourceName, places,
                      material ? std::vector<std::string>{"solid", "liquid"} : std::vector<std::string>{});
            if (material) bindPhases(*table, scene.material, name, name, sourceName, places, sections.phases);
        } else if (auto* elements = sections.array(name)) {
            const toml::array* array = node.as_array();
            if (!array || !array->is_array_of_tables()) {
                failAt(place, "'" + name + "' must be written as [[" + name + "]] sections");
            }
            for (std::size_t i = 0; i < array->size(); ++i) {
                const toml::table& element = *array->get(i)->as_table();
                const bool collider = name == "collider", material = name == "material";
                bindTable(element, (*elements)[i], arrayIndexPath(name, i), sourceName, places,
                          collider   ? std::vector<std::string>{"key"}
                          : material ? std::vector<std::string>{"solid", "liquid"}
                                     : std::vector<std::string>{});
                if (collider) {
                    bindColliderKeys(element, scene.colliders[i], arrayIndexPath(name, i),
                                     sourceName, places);
                }
                if (material) {
                    bindPhases(element, i == 0 ? scene.material : scene.otherMaterials[i - 1],
                               arrayIndexPath(name, i), "material[" + std::to_string(i) + "]",
                               sourceName, places, sections.phases);
                }
            }
        } else {
            const std::string hint = closestMatch(name, sections.names());
            failAt(place, "unknown section '" + name + "'" +
                              (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
        }
    }
    try {
        validateScene(scene, sections, reporter);
    } catch (const SceneError& e) {
        // A key that kept its default has no line ("[emitter[0]] key 'file'"): name the file.
        const std::string message = e.what();
        if (message.starts_with("[")) throw SceneError(sourceName + ": " + message);
        throw;
    }
    return scene;
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                Reporter& reporter) {
    // Reading a scene is part of the command line: what goes wrong is bad usage (exit 2).
    const std::string name = quoteForMessage(file.string(), 300);
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw SceneError("no scene file " + name);
    if (std::filesystem::is_directory(file, ec)) {
        throw SceneError("scene " + name + " is a directory, not a scene file");
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) throw SceneError("cannot open scene file " + name + ": " + std::strerror(errno));
    // Bounded, and read in pieces: /dev/zero or a pipe is not a scene either.
    std::string text;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, std::size_t(in.gcount()));
        if (text.size() > kMaxSceneBytes) {
            throw SceneError("scene " + name + " is larger than " +
                             std::to_string(kMaxSceneBytes >> 20) + " MiB; not a scene file");
        }
    }
    if (in.bad()) throw SceneError("cannot read scene file " + name);
    return parseScene(text, file.string(), overrides, reporter, std::filesystem::absolute(file));
}

std::string resolvedSceneToml(const Scene& constScene) {
    Scene scene = constScene;  // sections bind mutable fields; write from a copy
    // Relative paths resolve against the scene file's folder; the resolved scene lives
    // elsewhere (DIR/scene.toml), so it names them absolutely.
    for (EmitterSettings& emitter : scene.emitters) {
        if (!emitter.file.empty() && std::filesystem::path(emitter.file).is_relative()) {
            emitter.file = (scene.directory() / emitter.file).lexically_normal().string();
        }
    }
    for (ColliderSettings& collider : scene.colliders) {
        if (!collider.file.empty() && std::filesystem::path(collider.file).is_relative()) {
            collider.file = (scene.directory() / collider.file).lexically_normal().string();
        }
    }
    std::string& environment = scene.render.environment;
    if (!environment.empty() && std::filesystem::path(environment).is_relative()) {
        environment = (scene.directory() / environment).lexically_normal().string();
    }
    std::vector<std::pair<std::string, std::size_t>> sizes;
    SceneSections sections = bindSections(scene, sizes);
    std::ostringstream out;
    out << "# The resolved scene: every key with the value the run used.\n"
        << "# Source: "
        << (scene.file.empty() ? "<default scene>"
                               : quoteForMessage(scene.file.string(), std::string::npos))
        << "\n";
    const auto everyKey = [](const std::string&) { return true; };
    // Keys that only mean something with temperature are left out of a scene without it
    // (reading them back would be an error), and a melting range without phases.
    const bool thermal = scene.thermal.enabled;
    const auto thermalKeys = [&](const std::string& section, const std::string& key,
                                 const MaterialSettings* material = nullptr) {
        static const std::vector<std::pair<std::string, std::string>> kThermalOnly = {
            {"material", "heat_capacity"}, {"material", "conductivity"}, {"material", "expansion"},
            {"material", "t_solid"},       {"material", "t_liquid"},     {"emitter", "temperature"},
            {"collider", "temperature"},   {"collider", "heat_transfer"}};
        if (section == "thermal") return thermal || key == "enabled";
        if (material && !material->phases && (key == "t_solid" || key == "t_liquid")) return false;
        return thermal || std::find(kThermalOnly.begin(), kThermalOnly.end(),
                                    std::pair{section, key}) == kThermalOnly.end();
    };
    const auto phasesText = [&](MaterialSettings& material, const std::string& table) {
        if (!material.phases) return;
        for (const auto& [which, constants] :
             {std::pair{"solid", &material.solid}, std::pair{"liquid", &material.liquid}}) {
            SettingsSection section(table + "." + which);
            MaterialSettings::describePhase(section, *constants);
            out << "\n[" << table << "." << which << "]\n" << sectionText(section, everyKey);
        }
    };
    for (const auto& section : sections.singles) {
        const std::string& name = section.name();
        const MaterialSettings* material = name == "material" ? &scene.material : nullptr;
        out << "\n[" << name << "]\n" << sectionText(section, [&](const std::string& key) {
            return thermalKeys(name, key, material);
        });
        if (material) phasesText(scene.material, "material");
    }
    for (const auto& array : sections.arrays) {
        // Named, not a structured binding: lambdas below capture it (clang 14 cannot).
        const std::string& name = array.first;
        const std::vector<SettingsSection>& elements = array.second;
        for (std::size_t i = 0; i < elements.size(); ++i) {
            out << "\n[[" << name << "]]\n";
            if (name == "emitter") {
                const EmitterSettings& emitter = scene.emitters[i];
                out << sectionText(elements[i], [&](const std::string& key) {
                    return emitterKeyApplies(emitter.type, key) && thermalKeys(name, key);
                });
            } else if (name == "collider") {
                ColliderSettings& collider = scene.colliders[i];
                out << sectionText(elements[i], [&](const std::string& key) {
                    return colliderKeyApplies(collider.shape, key, collider.dynamic) &&
                           thermalKeys(name, key);
                });
                for (ColliderKey& key : collider.keys) {
                    SettingsSection section("collider.key");
                    key.describe(section);
                    out << "\n[[collider.key]]\n" << sectionText(section, everyKey);
                }
            } else if (name == "material") {
                MaterialSettings& material = i == 0 ? scene.material : scene.otherMaterials[i - 1];
                out << sectionText(elements[i], [&](const std::string& key) {
                    return thermalKeys(name, key, &material);
                });
                phasesText(material, "material");
            } else {
                out << sectionText(elements[i], everyKey);
            }
        }
    }
    return out.str();
}


std::string sceneKeysMarkdown() {
    Scene scene;
    SceneSections sections = bindSections(scene, {});
    std::ostringstream out;
    const auto table = [&](const std::string& heading, const SettingsSection& section,
                           const std::function<bool(const std::string&)>& applies) {
        out << "\n#### `" << heading << "`\n\n| key | default | meaning |\n|---|---|---|\n";
        for (const auto& [key, data] : section.values()) {
            if (!applies(key)) continue;
            out << "| `" << key << "` | `" << tomlText(data) << "` | " << section.docOf(key)
                << " |\n";
        }
    };
    const auto everyKey = [](const std::string&) { return true; };
    for (const auto& section : sections.singles) table("[" + section.name() + "]", section, everyKey);
    const SettingsSection& emitter = sections.array("emitter")->front();
    for (const std::string type : {"helix", "box", "spout", "points"}) {
        table("[[emitter]] type = \"" + type + "\"", emitter,
              [&](const std::string& key) { return emitterKeyApplies(type, key); });
    }
    table("[[light]]", sections.array("light")->front(), everyKey);
    HeaterSettings heater;  // a scene has none by default
    SettingsSection heaterSection("heater[0]");
    heater.describe(heaterSection);
    table("[[heater]] (thermal)", heaterSection, everyKey);
    // A scene has no collider by default: describe one to list its keys.
    ColliderSettings collider;
    SettingsSection colliderSection("collider[0]");
    collider.describe(colliderSection);
    for (const std::string shape : {"plane", "box", "sphere", "cylinder", "cup", "mesh"}) {
        table("[[collider]] shape = \"" + shape + "\"", colliderSection,
              [&](const std::string& key) { return colliderKeyApplies(shape, key); });
    }
    table("[[collider]] dynamic = true (any shape but a plane; not with keys or inside)",
          colliderSection, [&](const std::string& key) {
              return !colliderKeyApplies("box", key) && colliderKeyApplies("box", key, true);
          });
    ColliderKey key;
    SettingsSection keySection("collider.key");
    key.describe(keySection);
    table("[[collider.key]]", keySection, everyKey);
    // Several materials: [[material]] sections take the keys of [material] above.
    MaterialPairSettings pair;
    SettingsSection pairSection("material_pair[0]");
    pair.describe(pairSection);
    table("[[material_pair]]", pairSection, everyKey);
    // Phases: [material.solid] and [material.liquid] (after [material] or a [[material]]).
    ForceConstants phase;
    SettingsSection phaseSection("material.solid");
    MaterialSettings::describePhase(phaseSection, phase);
    table("[material.solid] and [material.liquid] (thermal: each defaults to the material's own)",
          phaseSection, everyKey);
    return out.str();
}

}  // namespace globular
