#include "emitter.h"

#include <algorithm>
#include <map>
#include <vector>

#include "errors.h"
#include "reporter.h"
#include "settings_schema.h"

namespace globular {

namespace {

// The keys each type reads beyond the common ones.
const std::map<std::string, std::vector<std::string>>& typeKeys() {
    static const std::map<std::string, std::vector<std::string>> keys = {
        {"helix", {"count", "velocity", "center", "helix_radius", "spacing", "turn"}},
        {"box", {"count", "velocity", "min", "max", "spacing"}},
        {"spout",
         {"count", "center", "spacing", "direction", "speed", "rate", "nozzle_radius", "start"}},
        {"points", {"velocity", "file", "offset"}},
    };
    return keys;
}

const std::vector<std::string> kCommonKeys = {"type",   "radius",  "mass",
                                              "jitter", "material", "temperature"};

}  // namespace

double Jitter::next() {
    uint64_t z = (mState += kStep);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-52 - 1.0;
}

void EmitterSettings::describe(SettingsSection& s) {
    s.choice("type", type, {"helix", "box", "spout", "points"}, "how globules are placed");
    s.integer("count", count, 0, kMaxEmitterGlobules, "number of globules (box: 0 fills the box)");
    s.number("radius", radius, NumberRange::positive(), "globule radius, world units");
    s.text("material", material, "the [[material]] it emits, by name (empty: the first)");
    s.number("mass", mass, NumberRange::positive(), "mass per globule");
    s.number("temperature", temperature, NumberRange::between(-1e6, 1e6),
             "initial temperature of its globules ([thermal] scenes)");
    s.vec3("velocity", velocity, NumberRange::any(), "initial velocity, units / s");
    s.number("jitter", jitter, NumberRange::nonNegative(), "random offset, world units");
    s.vec3("center", center, NumberRange::any(), "helix base or spout nozzle, world units");
    s.number("helix_radius", helixRadius, NumberRange::nonNegative(),
             "helix circle radius, world units");
    s.number("spacing", spacing, NumberRange::positive(),
             "helix vertical step, box lattice or spout layer step, world units");
    s.number("turn", turn, NumberRange::any(), "helix angle per globule, radians");
    s.vec3("min", min, NumberRange::any(), "box lower corner, world units");
    s.vec3("max", max, NumberRange::any(), "box upper corner, world units");
    s.vec3("direction", direction, NumberRange::any(), "spout pour direction");
    s.number("speed", speed, NumberRange::positive(), "spout exit speed, units / s");
    s.number("rate", rate, NumberRange::nonNegative(),
             "spout globules per second (0 = as fast as the nozzle allows)");
    s.number("nozzle_radius", nozzleRadius, NumberRange::nonNegative(),
             "spout nozzle radius, world units");
    s.number("start", start, NumberRange::nonNegative(), "spout start time, seconds");
    s.text("file", file, "points: PLY file, relative to the scene file");
    s.vec3("offset", offset, NumberRange::any(), "points: offset added, world units");
}

bool emitterKeyApplies(const std::string& type, const std::string& key) {
    if (std::find(kCommonKeys.begin(), kCommonKeys.end(), key) != kCommonKeys.end()) return true;
    const auto it = typeKeys().find(type);
    return it != typeKeys().end() &&
           std::find(it->second.begin(), it->second.end(), key) != it->second.end();
}

void EmitterSettings::validate(const SettingsSection& s, Reporter& reporter) const {
    for (const auto& key : s.keys()) {
        if (s.placeOf(key) && !emitterKeyApplies(type, key)) {
            throw SceneError(s.describeKey(key) + ": does not apply to a " + type + " emitter");
        }
    }
    if (type == "box" && !(min.x < max.x && min.y < max.y && min.z < max.z)) {
        throw SceneError(s.describeKey("max") + ": every component must exceed min's");
    }
    if (type == "spout" && length(direction) == 0) {
        throw SceneError(s.describeKey("direction") + ": must not be [0, 0, 0]");
    }
    if (type == "points" && file.empty()) {
        throw SceneError(s.describeKey("file") + ": a points emitter needs a file");
    }
    if ((type == "helix" || type == "spout") && count == 0) {
        throw SceneError(s.describeKey("count") + ": must be at least 1");
    }
    if (type == "helix" && std::min(spacing, 1.41421356 * helixRadius) < radius) {
        reporter.warn(s.describeKey("spacing") +
                      ": helix globules start closer than one radius apart; expect a violent "
                      "start (widen helix_radius or spacing)");
    }
}

}  // namespace globular
