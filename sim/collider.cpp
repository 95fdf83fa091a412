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
    };
    return keys;
}

const std::vector<std::string> kCommonKeys = {"name", "shape", "ks", "kd", "contact", "friction"};

/// A capped cylinder of radius @p r from y = @p y0 to @p y1 around the y axis through the
/// origin of @p local: signed distance and outward normal (the exact SDF of the solid).
SurfaceSample cylinderSample(Vec3 local, double r, double y0, double y1) {
    const double radial = std::hypot(local.x, local.z);
    const Vec3 outward = radial > 0 ? Vec3{local.x / radial, 0, local.z / radial} : Vec3{1, 0, 0};
    const double dRadial = radial - r;
    const double mid = 0.5 * (y0 + y1), half = 0.5 * (y1 - y0);
    const double dAxial = std::abs(local.y - mid) - half;
    const Vec3 axial{0, local.y >= mid ? 1.0 : -1.0, 0};
    if (dRadial > 0 && dAxial > 0) {  // beyond a rim: the nearest point is on its circle
        const double d = std::hypot(dRadial, dAxial);
        return {d, normalized(dRadial * outward + dAxial * axial)};
    }
    if (dRadial > dAxial) return {dRadial, outward};
    return {dAxial, axial};
}

SurfaceSample boxSample(Vec3 local, Vec3 half) {
    const double q[3] = {std::abs(local.x) - half.x, std::abs(local.y) - half.y,
                         std::abs(local.z) - half.z};
    const double sign[3] = {local.x >= 0 ? 1.0 : -1.0, local.y >= 0 ? 1.0 : -1.0,
                            local.z >= 0 ? 1.0 : -1.0};
    const double outside[3] = {std::max(q[0], 0.0), std::max(q[1], 0.0), std::max(q[2], 0.0)};
    const double outsideLength = std::sqrt(outside[0] * outside[0] + outside[1] * outside[1] +
                                           outside[2] * outside[2]);
    if (outsideLength > 0) {
        return {outsideLength, Vec3{outside[0] * sign[0], outside[1] * sign[1],
                                    outside[2] * sign[2]} *
                                   (1.0 / outsideLength)};
    }
    const int a = q[0] >= q[1] && q[0] >= q[2] ? 0 : (q[1] >= q[2] ? 1 : 2);
    Vec3 normal{0, 0, 0};
    (a == 0 ? normal.x : a == 1 ? normal.y : normal.z) = sign[a];
    return {q[a], normal};
}

SurfaceSample flipped(SurfaceSample s) { return {-s.phi, -1.0 * s.normal}; }

}  // namespace

bool colliderKeyApplies(const std::string& shape, const std::string& key) {
    if (std::find(kCommonKeys.begin(), kCommonKeys.end(), key) != kCommonKeys.end()) return true;
    const auto it = shapeKeys().find(shape);
    return it != shapeKeys().end() &&
           std::find(it->second.begin(), it->second.end(), key) != it->second.end();
}

void ColliderSettings::describe(SettingsSection& s) {
    s.text("name", name, "a name for messages and outputs");
    s.choice("shape", shape, {"plane", "box", "sphere", "cylinder", "cup"}, "the solid");
    s.vec3("center", center, NumberRange::between(-1e6, 1e6),
           "box, sphere: the centre; cylinder, cup: the centre of the base (axis +y)");
    s.vec3("size", size, NumberRange::between(0, 1e6), "box: edge lengths, world units");
    s.number("radius", radius, NumberRange{0, 1e6, true}, "sphere, cylinder, cup radius");
    s.number("height", height, NumberRange{0, 1e6, true}, "cylinder, cup height");
    s.vec3("normal", normal, NumberRange::any(), "plane: outward normal");
    s.number("thickness", thickness, NumberRange{0, 1e6, true}, "cup: wall and bottom thickness");
    s.flag("inside", inside, "box, sphere, cylinder: keep globules inside (a closed container)");
    s.number("ks", ks, NumberRange::nonNegative(), "penalty stiffness (eq. 9)");
    s.number("kd", kd, NumberRange::nonNegative(), "penalty damping (eq. 9)");
    s.choice("contact", contact, {"center", "surface"},
             "contact at the globule centre (as the paper's ground) or at its surface");
    s.number("friction", friction, NumberRange::nonNegative(),
             "Coulomb friction coefficient; 0 = frictionless");
}

void ColliderSettings::validate(const SettingsSection& s) const {
    for (const std::string& key : s.keys()) {
        if (s.placeOf(key) && !colliderKeyApplies(shape, key)) {
            throw SceneError(s.describeKey(key) + ": does not apply to a " + shape + " collider");
        }
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
    if (shape == "cup" && !(thickness < radius && thickness < height)) {
        throw SceneError(s.describeKey("thickness") +
                         ": a cup's wall must be thinner than its radius and its height");
    }
}

SurfaceSample sampleCollider(const ColliderSettings& c, Vec3 p) {
    const Vec3 local = p - c.center;
    SurfaceSample s;
    if (c.shape == "plane") {
        const Vec3 n = normalized(c.normal);
        return {dot(local, n), n};
    }
    if (c.shape == "sphere") {
        const double d = length(local);
        s = {d - c.radius, d > 0 ? local * (1.0 / d) : Vec3{0, 1, 0}};
    } else if (c.shape == "box") {
        s = boxSample(local, 0.5 * c.size);
    } else if (c.shape == "cylinder") {
        s = cylinderSample(local, c.radius, 0, c.height);
    } else {  // cup: the outer cylinder minus the hollow, which runs out through the top
        const SurfaceSample outer = cylinderSample(local, c.radius, 0, c.height);
        const SurfaceSample hollow =
            cylinderSample(local, c.radius - c.thickness, c.thickness, c.height + c.radius + 1);
        // The solid is outer AND NOT hollow: max(phi_outer, -phi_hollow).
        return outer.phi >= -hollow.phi ? outer : flipped(hollow);
    }
    return c.inside ? flipped(s) : s;
}

SurfaceSample sampleCollider(const ColliderSettings& c, const ColliderMotion& motion, Vec3 p) {
    const SurfaceSample local = sampleCollider(c, motion.now.toLocal(p));
    return {local.phi, motion.now.rotate(local.normal)};
}

}  // namespace globular
