#include "scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "collider_solid.h"
#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

/// The force's reach max(C_r, C_d) (r_i + r_p) must stay a usable float cell size.
constexpr double kMinReach = 1e-4, kMaxReach = 1e6;

template <typename Settings>
SettingsSection describeSection(const std::string& name, Settings& settings) {
    SettingsSection section(name);
    settings.describe(section);
    return section;
}

template <typename Settings>
std::vector<SettingsSection> describeArray(const std::string& name,
                                           std::vector<Settings>& elements) {
    std::vector<SettingsSection> sections;
    for (std::size_t i = 0; i < elements.size(); ++i) {
        sections.push_back(describeSection(name + "[" + std::to_string(i) + "]", elements[i]));
    }
    return sections;
}

std::size_t sizeOr(const std::vector<std::pair<std::string, std::size_t>>& sizes,
                   const std::string& name, std::size_t fallback) {
    for (const auto& [n, size] : sizes) {
        if (n == name) return size;
    }
    return fallback;
}

/// What a material and the radii derive: the reach of the force (the neighbour grid's
/// cell) and b2 must be usable numbers, or the error would blame the grid.
void checkNeighbourReach(const ForceConstants& m, const SettingsSection& material,
                         const Scene& scene, const SceneSections& sections) {
    const double window = std::max(m.resolvedCr(), m.resolvedCd());
    const std::string windowKeys = material.describeKey("r0") + ", " +
                                   material.describeKey(m.cr > 0 ? "cr" : "alpha") + " or " +
                                   material.describeKey(m.cd > 0 ? "cd" : "preset");
    const double b2 = m.b1 * std::pow(m.r0, m.n - m.m);
    if (!std::isfinite(float(b2)) || !(std::isfinite(window) && window > 0)) {
        throw SceneError(windowKeys + ": b2 = b1 r0^(n-m) = " + numberForMessage(b2) +
                         " and the force window " + numberForMessage(window) +
                         " must be finite single-precision numbers");
    }
    const auto& emitters = *sections.array("emitter");
    for (std::size_t k = 0; k < scene.emitters.size(); ++k) {
        const double reach = window * 2.0 * scene.emitters[k].radius;
        if (!(reach >= kMinReach && reach <= kMaxReach)) {
            throw SceneError(emitters[k].describeKey("radius") + " = " +
                             numberForMessage(scene.emitters[k].radius) + " with the window " +
                             numberForMessage(window) + " (" + windowKeys +
                             ") gives globules a reach of " + numberForMessage(reach) +
                             " world units; it must lie between 1e-4 and 1e6");
        }
    }
}

/// checkNeighbourReach for every material.
void checkNeighbourReach(const Scene& scene, const SceneSections& sections) {
    const SettingsSection* place = sections.single("material");
    if (!place) place = &sections.array("material")->front();
    for (std::size_t k = 0; k < scene.otherMaterials.size(); ++k) {
        checkNeighbourReach(scene.otherMaterials[k], (*sections.array("material"))[k + 1],
                            scene, sections);
    }
    checkNeighbourReach(scene.material, *place, scene, sections);
    const std::vector<MaterialSettings> materials = scene.simulationSetup().materials();
    for (std::size_t k = 0; k < materials.size(); ++k) {
        for (const auto& [which, constants] :
             {std::pair{"solid", &materials[k].solid}, std::pair{"liquid", &materials[k].liquid}}) {
            if (const SettingsSection* phase = sections.phase(k, which)) {
                checkNeighbourReach(*constants, *phase, scene, sections);
            }
        }
    }
}

}  // namespace

std::filesystem::path Scene::directory() const {
    return file.empty() ? std::filesystem::current_path() : file.parent_path();
}

SimulationSetup Scene::simulationSetup() const {
    return SimulationSetup{simulation, material,       ground,        emitters, directory(),
                           colliders,  otherMaterials, materialPairs, thermal,  heaters};
}

ColliderScene Scene::colliderScene() const {
    return ColliderScene{colliders, directory(), Simulation::colliderReach(simulationSetup())};
}

const SettingsSection* SceneSections::single(const std::string& name) const {
    for (const auto& s : singles) {
        if (s.name() == name) return &s;
    }
    return nullptr;
}

SettingsSection* SceneSections::single(const std::string& name) {
    return const_cast<SettingsSection*>(std::as_const(*this).single(name));
}

const std::vector<SettingsSection>* SceneSections::array(const std::string& name) const {
    for (const auto& [n, sections] : arrays) {
        if (n == name) return &sections;
    }
    return nullptr;
}

std::vector<SettingsSection>* SceneSections::array(const std::string& name) {
    return const_cast<std::vector<SettingsSection>*>(std::as_const(*this).array(name));
}

const SettingsSection* SceneSections::phase(std::size_t k, const std::string& which) const {
    const std::string single = "material." + which;
    const std::string element = "material[" + std::to_string(k) + "]." + which;
    for (const SettingsSection& s : phases) {
        if (s.name() == element || (k == 0 && s.name() == single)) return &s;
    }
    return nullptr;
}

std::vector<std::string> SceneSections::names() const {
    std::vector<std::string> out;
    for (const auto& s : singles) out.push_back(s.name());
    for (const auto& [n, sections] : arrays) out.push_back(n);
    return out;
}

SceneSections bindSections(Scene& scene,
                           const std::vector<std::pair<std::string, std::size_t>>& arraySizes) {
    // An absent array keeps what the scene has: one default element when it has none.
    scene.emitters.resize(sizeOr(arraySizes, "emitter", std::max<std::size_t>(1, scene.emitters.size())));
    scene.lights.resize(sizeOr(arraySizes, "light", std::max<std::size_t>(1, scene.lights.size())));
    scene.colliders.resize(sizeOr(arraySizes, "collider", scene.colliders.size()));
    scene.materialPairs.resize(sizeOr(arraySizes, "material_pair", scene.materialPairs.size()));
    scene.heaters.resize(sizeOr(arraySizes, "heater", scene.heaters.size()));
    // [material], or [[material]] sections: the first binds to `material`, the rest to
    // `otherMaterials`.
    const std::size_t materials = sizeOr(arraySizes, "material", 0);
    if (materials > 0) scene.otherMaterials.resize(materials - 1);
    const bool materialArray = materials > 0 || scene.namedMaterials();
    SceneSections sections;
    sections.singles.push_back(describeSection("simulation", scene.simulation));
    if (!materialArray) sections.singles.push_back(describeSection("material", scene.material));
    sections.singles.push_back(describeSection("ground", scene.ground));
    sections.singles.push_back(describeSection("output", scene.output));
    sections.singles.push_back(describeSection("surface", scene.surface));
    sections.singles.push_back(describeSection("render", scene.render));
    sections.singles.push_back(describeSection("camera", scene.camera));
    sections.singles.push_back(describeSection("thermal", scene.thermal));
    sections.arrays.emplace_back("emitter", describeArray("emitter", scene.emitters));
    sections.arrays.emplace_back("light", describeArray("light", scene.lights));
    sections.arrays.emplace_back("collider", describeArray("collider", scene.colliders));
    if (materialArray) {
        std::vector<SettingsSection> all{describeSection("material[0]", scene.material)};
        for (std::size_t i = 0; i < scene.otherMaterials.size(); ++i) {
            all.push_back(describeSection("material[" + std::to_string(i + 1) + "]",
                                          scene.otherMaterials[i]));
        }
        sections.arrays.emplace_back("material", std::move(all));
    }
    sections.arrays.emplace_back("material_pair",
                                 describeArray("material_pair", scene.materialPairs));
    sections.arrays.emplace_back("heater", describeArray("heater", scene.heaters));
    return sections;
}

/// The material sections in order: [material] alone, or every [[material]].
std::vector<const SettingsSection*> materialSections(const SceneSections& sections) {
    if (const SettingsSection* single = sections.single("material")) return {single};
    std::vector<const SettingsSection*> all;
    for (const SettingsSection& s : *sections.array("material")) all.push_back(&s);
    return all;
}

/// Names of several materials: each given, once; emitters and pairs name existing ones.
void checkMaterialNames(const Scene& scene, const SceneSections& sections) {
    const std::vector<MaterialSettings> materials = scene.simulationSetup().materials();
    const std::vector<const SettingsSection*> places = materialSections(sections);
    for (std::size_t k = 0; k < materials.size() && materials.size() > 1; ++k) {
        if (materials[k].name.empty()) {
            throw SceneError(places[k]->describeKey("name") +
                             ": with several [[material]] sections each needs a name");
        }
        for (std::size_t j = 0; j < k; ++j) {
            if (materials[j].name == materials[k].name) {
                throw SceneError(places[k]->describeKey("name") + " = \"" + materials[k].name +
                                 "\": another [[material]] has this name");
            }
        }
    }
    std::string known;
    for (const MaterialSettings& m : materials) known += (known.empty() ? "" : ", ") + m.name;
    const auto check = [&](const SettingsSection& section, const std::string& key,
                           const std::string& name) {
        if (materialIndex(materials, name) < 0) {
            throw SceneError(section.describeKey(key) + " = \"" + quoteForMessage(name, 60) +
                             "\": no [[material]] has this name (there are: " + known + ")");
        }
    };
    const auto& emitterSections = *sections.array("emitter");
    for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
        check(emitterSections[i], "material", scene.emitters[i].material);
    }
    const auto& pairSections = *sections.array("material_pair");
    for (std::size_t i = 0; i < scene.materialPairs.size(); ++i) {
        const MaterialPairSettings& p = scene.materialPairs[i];
        for (const auto& [key, name] : {std::pair{"a", p.a}, std::pair{"b", p.b}}) {
            if (name.empty()) {
                throw SceneError(pairSections[i].describeKey(key) + ": a pair names two materials");
            }
            check(pairSections[i], key, name);
        }
        if (p.a == p.b) {
            throw SceneError(pairSections[i].describeKey("b") +
                             ": a pair names two different materials");
        }
        for (std::size_t j = 0; j < i; ++j) {
            const MaterialPairSettings& q = scene.materialPairs[j];
            if ((q.a == p.a && q.b == p.b) || (q.a == p.b && q.b == p.a)) {
                throw SceneError(pairSections[i].describeKey("a") + ": the pair '" + p.a +
                                 "', '" + p.b + "' is given twice");
            }
        }
    }
}

/// Keys that only mean something with temperature: set while [thermal] is off, they are
/// an error, not silently ignored.
static void checkThermalKeys(const Scene& scene, const SceneSections& sections) {
    if (scene.thermal.enabled) return;
    const auto refuse = [&](const SettingsSection& section, const std::string& key) {
        if (section.placeOf(key)) {
            throw SceneError(section.describeKey(key) +
                             ": temperature is off; set [thermal] enabled = true");
        }
    };
    for (const std::string key : {"ambient", "cooling", "reference", "ground_temperature",
                                  "ground_transfer"}) {
        refuse(*sections.single("thermal"), key);
    }
    for (const SettingsSection* m : materialSections(sections)) {
        for (const std::string key : {"heat_capacity", "conductivity", "expansion", "t_solid", "t_liquid"}) {
            refuse(*m, key);
        }
    }
    if (!sections.phases.empty()) {
        throw SceneError("[" + sections.phases.front().name() +
                         "]: phases need temperature; set [thermal] enabled = true");
    }
    for (const SettingsSection& e : *sections.array("emitter")) refuse(e, "temperature");
    for (const SettingsSection& c : *sections.array("collider")) {
        refuse(c, "temperature");
        refuse(c, "heat_transfer");
    }
    if (!scene.heaters.empty()) {
        throw SceneError("[[heater]]: heaters need temperature; set [thermal] enabled = true");
    }
}

void validateScene(const Scene& scene, const SceneSections& sections, Reporter& reporter) {
    scene.simulation.validate(*sections.single("simulation"), reporter);
    checkThermalKeys(scene, sections);
    const std::vector<const SettingsSection*> materialPlaces = materialSections(sections);
    scene.material.validate(*materialPlaces[0], reporter);
    for (std::size_t k = 0; k < scene.otherMaterials.size(); ++k) {
        scene.otherMaterials[k].validate(*materialPlaces[k + 1], reporter);
    }
    const std::vector<MaterialSettings> materials = scene.simulationSetup().materials();
    for (std::size_t k = 0; k < materials.size(); ++k) {
        if (const SettingsSection* solid = sections.phase(k, "solid")) materials[k].solid.validate(*solid, reporter);
        if (const SettingsSection* liquid = sections.phase(k, "liquid")) materials[k].liquid.validate(*liquid, reporter);
    }
    const auto& emitterSections = *sections.array("emitter");
    for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
        scene.emitters[i].validate(emitterSections[i], reporter);
    }
    checkMaterialNames(scene, sections);
    checkNeighbourReach(scene, sections);
    const auto& heaterSections = *sections.array("heater");
    for (std::size_t i = 0; i < scene.heaters.size(); ++i) scene.heaters[i].validate(heaterSections[i]);
    scene.surface.validate();
    scene.render.validate(*sections.single("render"));
    scene.camera.validate(*sections.single("camera"));
    const auto& lightSections = *sections.array("light");
    for (std::size_t i = 0; i < scene.lights.size(); ++i) scene.lights[i].validate(lightSections[i]);
    const auto& colliderSections = *sections.array("collider");
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        const ColliderSettings& collider = scene.colliders[i];
        collider.validate(colliderSections[i]);
        if (collider.shape == "mesh") {
            try {
                checkColliderMesh(collider, scene.directory());
            } catch (const SceneError& e) {
                throw SceneError(colliderSections[i].describeKey("file") + ": " + e.what());
            }
        }
    }
}

}  // namespace globular
