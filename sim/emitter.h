#pragma once
// Where globules come from. Each `[[emitter]]` of a scene is one of:
//   helix  - the paper's Fig. 3: N globules in 4 phase-shifted helices, x/z jittered
//   box    - a jittered lattice filling a box
//   spout  - a continuous pour from a nozzle: layers of globules at a rate and speed
//   points - positions (and optional velocities, radii) from a PLY file

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "globules.h"
#include "vec3.h"

namespace globular {

class SettingsSection;
class Reporter;

/// The most globules one emitter may produce (memory is checked separately).
inline constexpr int64_t kMaxEmitterGlobules = 100'000'000;

struct EmitterSettings {
    std::string type = "helix";  ///< helix | box | spout | points
    int64_t count = 400;         ///< globules (box: 0 = fill the box; points: from the file)
    double radius = 1.0;         ///< globule radius, world units
    std::string material;        ///< the [[material]] it emits ("": the first)
    double mass = 1.0;           ///< per globule
    double temperature = 20;     ///< initial temperature of its globules (thermal scenes)
    Vec3 velocity{0, 0, 0};      ///< initial velocity, units / s (helix, box, points)
    double jitter = 0.05;        ///< random offset amplitude, world units (seeded)
    // helix
    Vec3 center{0, 5, 0};        ///< helix: bottom centre; spout: nozzle position
    double helixRadius = 1.0;    ///< helix circle radius, world units
    double spacing = 1.1;        ///< helix: vertical step; box and spout: lattice step
    double turn = 0.5;           ///< helix: angle per globule of a group, radians
    // box
    Vec3 min{-4, 1, -4}, max{4, 9, 4};  ///< box corners, world units
    // spout
    Vec3 direction{0, -1, 0};    ///< pour direction (normalised)
    double speed = 5.0;          ///< exit speed, units / s
    double rate = 0.0;           ///< globules per second; 0 = a layer every spacing/speed
    double nozzleRadius = 1.5;   ///< world units
    double start = 0.0;          ///< seconds after the start of the simulation
    // points
    std::string file;            ///< PLY path, relative to the scene file
    Vec3 offset{0, 0, 0};        ///< added to every point, world units

    void describe(SettingsSection& section);
    /// Rejects keys that do not apply to the type and inconsistent values.
    void validate(const SettingsSection& section, Reporter& reporter) const;
};

/// Whether an [[emitter]] of @p type reads @p key (the common keys apply to all types).
bool emitterKeyApplies(const std::string& type, const std::string& key);

class Emitter {
public:
    virtual ~Emitter() = default;
    /// Appends every globule due by @p time that was not emitted yet, with ids from
    /// @p nextId (incremented).
    virtual void emit(double time, Globules& globules, int32_t& nextId) = 0;
    /// Globules this emitter produces over the whole run (for memory estimates).
    virtual std::size_t total() const = 0;
    /// Globules emitted so far.
    virtual std::size_t emitted() const = 0;
    /// Puts the emitter in the state it had after emitting @p count globules (resume).
    virtual void skipTo(std::size_t count) = 0;
};

/// @param seed the scene seed, mixed with @p index so emitters differ.
/// @param sceneDir directory that relative paths (points.file) resolve against.
/// @throw SceneError / IoError for unusable settings or an unreadable file.
std::unique_ptr<Emitter> makeEmitter(const EmitterSettings& settings, uint64_t seed,
                                     std::size_t index, const std::filesystem::path& sceneDir);

/// Globules an emitter of these settings will make over the run, known before any is
/// placed (for the memory estimate of all emitters together). A box that is filled
/// counts its lattice; a points emitter counts 0 (its file bounds it). Saturates at
/// SIZE_MAX instead of overflowing.
std::size_t plannedGlobules(const EmitterSettings& settings);

/// Deterministic uniform numbers in [-1, 1) (splitmix64): identical on every platform.
class Jitter {
public:
    explicit Jitter(uint64_t seed) : mState(seed) {}
    double next();
    /// Skips @p draws numbers (the generator is a counter: this is O(1)).
    void skip(uint64_t draws) { mState += draws * kStep; }
    static constexpr uint64_t kStep = 0x9e3779b97f4a7c15ull;

private:
    uint64_t mState;
};

}  // namespace globular
