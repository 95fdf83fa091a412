#pragma once
// A whole scene: every section of the TOML file (DESIGN.md), typed and defaulted. An
// empty file is the paper's best liquid (Fig. 1): 400 globules in a helix, forward
// Euler, dt = 0.001 s.

#include <filesystem>
#include <string>
#include <vector>

#include "collider.h"
#include "emitter.h"
#include "material.h"
#include "render_settings.h"
#include "simulation.h"
#include "simulation_settings.h"
#include "surface_settings.h"

namespace globular {

class Reporter;
class SettingsSection;

struct Scene {
    SimulationSettings simulation;
    MaterialSettings material;  ///< [material], or the first [[material]]
    std::vector<MaterialSettings> otherMaterials;     ///< the [[material]] sections after it
    std::vector<MaterialPairSettings> materialPairs;  ///< [[material_pair]]
    GroundSettings ground;
    OutputSettings output;
    std::vector<EmitterSettings> emitters;  ///< [[emitter]]; one helix when none is given
    std::vector<ColliderSettings> colliders;  ///< [[collider]]; none by default
    SurfaceSettings surface;
    RenderSettings render;
    CameraSettings camera;
    std::vector<LightSettings> lights;  ///< [[light]]; one key light when none is given
    ThermalSettings thermal;              ///< [thermal]
    std::vector<HeaterSettings> heaters;  ///< [[heater]]

    std::filesystem::path file;  ///< the scene file; empty for the built-in default
    std::filesystem::path directory() const;  ///< relative paths resolve against it

    SimulationSetup simulationSetup() const;
    /// Whether the materials are written as [[material]] sections (several, or named).
    bool namedMaterials() const { return !otherMaterials.empty() || !material.name.empty(); }
    /// The colliders as the surface and render stages need them.
    ColliderScene colliderScene() const;
};

/// Parses a scene from TOML @p text. @p sourceName names it in messages (a path, or
/// "<default scene>"). @p overrides are --set arguments "dotted.key=value", applied
/// over the text: `material.b1=3`, `emitter.0.count=100`, `render.mode=surface`.
/// Warnings (values outside the paper's recommended ranges) go to @p reporter.
/// @p file, when given, is the scene's own path: relative paths in it (a mesh collider's
/// file, which is read to check it) resolve against its folder, else the current one.
/// @throw SceneError naming file, line, column and key for every kind of bad input.
Scene parseScene(const std::string& text, const std::string& sourceName,
                 const std::vector<std::string>& overrides, Reporter& reporter,
                 const std::filesystem::path& file = {});

/// Reads and parses a scene file. @throw SceneError / IoError naming the file.
Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                Reporter& reporter);

/// The resolved scene as TOML: every key of every section with its value, defaults
/// included, so a run can be repeated from DIR/scene.toml alone.
std::string resolvedSceneToml(const Scene& scene);

/// The scene's sections bound to its fields (settings_schema.h), in file order.
struct SceneSections {
    std::vector<SettingsSection> singles;  ///< [simulation], [material], ...
    std::vector<std::pair<std::string, std::vector<SettingsSection>>> arrays;  ///< [[emitter]]
    /// [material.solid] and [material.liquid] tables as parsed, named "material[k].solid"
    /// (or "material.solid" for a single [material]).
    std::vector<SettingsSection> phases;

    SettingsSection* single(const std::string& name);
    const SettingsSection* single(const std::string& name) const;
    std::vector<SettingsSection>* array(const std::string& name);
    const std::vector<SettingsSection>* array(const std::string& name) const;
    /// The parsed phase table @p phase ("solid" or "liquid") of material @p k, or nullptr.
    const SettingsSection* phase(std::size_t k, const std::string& phase) const;
    std::vector<std::string> names() const;  ///< every section name, for suggestions
};

/// Binds sections to @p scene's fields. Array sections get @p arraySizes[name] elements
/// (the scene's vectors are resized to match; missing names keep the defaults).
SceneSections bindSections(Scene& scene,
                           const std::vector<std::pair<std::string, std::size_t>>& arraySizes);

/// Every section and key with its default and documentation, as a Markdown table: what
/// `globular keys` prints and the README's scene reference shows.
std::string sceneKeysMarkdown();

/// Cross-field checks of every section. @throw SceneError naming file and key.
void validateScene(const Scene& scene, const SceneSections& sections, Reporter& reporter);

}  // namespace globular
