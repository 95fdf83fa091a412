#include "collider.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

const std::map<std::string, std::vector<std::string>>& shapeKeys() {
    static const std::map<std::string, std::vector<std::string>> keys = {
        {"plane", {"center", "normal"}},
        {"box", {"center", "size", "inside"}},
        {"sphere", {"center", "radius", "inside"}},
        {"cylinder", {"center", "radius", "height", "inside"}},
        {"cup", {"center", "radius", "height", "thickness"}},
        {"mesh", {"center", "file", "scale", "thickness", "voxel_size", "inside"}},
    };
    return keys;
}

const std::vector<std::string> kCommonKeys = {"name",     "shape",       "ks",
                                              "kd",       "contact",     "friction",
                                              "temperature", "heat_transfer"};
/// What a rigid body reads: `dynamic` on every solid shape, the rest once it is set.
const std::vector<std::string> kDynamicKeys = {"mass", "velocity", "angular_velocity"};

bool isIn(const std::vector<std::string>& keys, const std::string& key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace

bool colliderKeyApplies(const std::string& shape, const std::string& key, bool dynamic) {
    if (isIn(kCommonKeys, key)) return true;
    if (key == "dynamic") return shape != "plane";
    if (isIn(kDynamicKeys, key)) return dynamic && shape != "plane";
    const auto it = shapeKeys().find(shape);
    return it != shapeKeys().end() && isIn(it->second, key);
}

void ColliderSettings::describe(SettingsSection& s) {
    s.text("name", name, "a name for messages and outputs");
    s.choice("shape", shape, {"plane", "box", "sphere", "cylinder", "cup", "mesh"}, "the solid");
    s.vec3("center", center, NumberRange::between(-1e6, 1e6),
           "box, sphere: the centre; cylinder, cup: the centre of the base (axis +y); mesh: "
           "where the file's origin goes");
    s.vec3("size", size, NumberRange::between(0, 1e6), "box: edge lengths, world units");
    s.number("radius", radius, NumberRange{0, 1e6, true}, "sphere, cylinder, cup radius");
    s.number("height", height, NumberRange{0, 1e6, true}, "cylinder, cup height");
    s.vec3("normal", normal, NumberRange::any(), "plane: outward normal");
    s.number("thickness", thickness, NumberRange::between(0, 1e6),
             "cup: wall and bottom thickness (> 0); mesh: a shell this thick around the "
             "surface, needed for an open mesh (0: the inside of a closed mesh)");
    s.text("file", file, "mesh: an .obj or .ply file, relative to the scene file");
    s.number("scale", scale, NumberRange{0, 1e6, true}, "mesh: scale of the file's coordinates");
    s.number("voxel_size", voxelSize, NumberRange::between(0, 1e6),
             "mesh: voxel of its signed distance field, world units (0: 1/100 of the "
             "mesh's longest extent, or 1/64 of the globules' reach if coarser, at most "
             "half the thickness)");
    s.flag("inside", inside,
           "box, sphere, cylinder, closed mesh: keep globules inside (a closed container)");
    s.number("ks", ks, NumberRange::nonNegative(), "penalty stiffness (eq. 9)");
    s.number("kd", kd, NumberRange::nonNegative(), "penalty damping (eq. 9)");
    s.choice("contact", contact, {"center", "surface"},
             "contact at the globule centre (as the paper's ground) or at its surface");
    s.number("friction", friction, NumberRange::nonNegative(),
             "Coulomb friction coefficient; 0 = frictionless");
    s.number("temperature", temperature, NumberRange::between(-1e6, 1e6),
             "thermal: temperature of its surface (a hot or cold plate)");
    s.number("heat_transfer", heatTransfer, NumberRange::nonNegative(),
             "thermal: heat transfer rate with a globule touching it, 1/s (0: insulating)");
    s.flag("dynamic", dynamic,
           "a rigid body moved by gravity and by the globules' forces (two-way coupling)");
    s.number("mass", mass, NumberRange{0, 1e12, true}, "dynamic: mass (a globule's is 1)");
    s.vec3("velocity", velocity, NumberRange::between(-1e6, 1e6),
           "dynamic: initial velocity, world units / s");
    s.vec3("angular_velocity", angularVelocity, NumberRange::between(-1e6, 1e6),
           "dynamic: initial spin about x, y, z through the centre of mass, degrees / s");
}

void ColliderSettings::validate(const SettingsSection& s) const {
    for (const std::string& key : s.keys()) {
        if (s.placeOf(key) && !colliderKeyApplies(shape, key, dynamic)) {
            throw SceneError(s.describeKey(key) + ": does not apply to a " +
                             (isIn(kDynamicKeys, key) ? "collider without dynamic = true"
                                                      : shape + " collider"));
        }
    }
    if (dynamic && inside) {
        throw SceneError(s.describeKey("dynamic") +
                         ": a container (inside = true) cannot be dynamic: its solid is "
                         "everything outside it");
    }
    if (dynamic && !keys.empty()) {
        throw SceneError(s.describeKey("dynamic") +
                         ": a collider is moved by [[collider.key]] keyframes or is dynamic, "
                         "not both");
    }
    if (shape == "mesh" && file.empty()) {
        throw SceneError(s.describeKey("shape") + ": a mesh collider needs a file (OBJ or PLY)");
    }
    if (shape == "mesh" && inside && thickness > 0) {
        throw SceneError(s.describeKey("inside") +
                         ": a container mesh must be closed, without a thickness (a shell "
                         "has no inside to keep globules in)");
    }
    if (shape == "plane" && !(length(normal) > 0)) {
        throw SceneError(s.describeKey("normal") + ": a plane needs a non-zero normal");
    }
    if (shape == "box" && !(size.x > 0 && size.y > 0 && size.z > 0)) {
        throw SceneError(s.describeKey("size") + ": every edge of a box must be positive");
    }
    for (std::size_t k = 1; k < keys.size(); ++k) {
        if (!(keys[k].time > keys[k - 1].time)) {
            throw SceneError(s.describeKey("shape") + ": [[collider.key]] " + std::to_string(k) +
                             " (time " + std::to_string(keys[k].time) +
                             " s) is not later than the key before it; keys go in time order");
        }
    }
    if (shape == "cup" && !(thickness > 0)) {
        throw SceneError(s.describeKey("shape") + ": a cup needs a thickness > 0 (its wall)");
    }
    if (shape == "cup" && !(thickness < radius && thickness < height)) {
        throw SceneError(s.describeKey("thickness") +
                         ": a cup's wall must be thinner than its radius and its height");
    }
}

}  // namespace globular
