#pragma once
// How a collider moves: `[[collider.key]]` keyframes of position and rotation (degrees
// about x, then y, then z), interpolated by Catmull-Rom splines (C1: no jolt at a key),
// held before the first key and after the last. A collider without keys stays where its
// geometry puts it. The pose maps the collider's own frame (where its shape is defined)
// into the world.

#include <vector>

#include "vec3.h"

namespace globular {

class SettingsSection;

struct ColliderKey {
    double time = 0;          ///< seconds
    Vec3 position{0, 0, 0};   ///< world units, added to the shape's own coordinates
    Vec3 rotation{0, 0, 0};   ///< degrees about x, y, z (applied in that order)

    void describe(SettingsSection& section);
};

/// A rigid motion: world = rotation * local + translation.
struct Pose {
    double rotation[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3 translation{0, 0, 0};

    Vec3 toWorld(Vec3 local) const;
    Vec3 toLocal(Vec3 world) const;
    Vec3 rotate(Vec3 direction) const;  ///< local direction -> world
};

/// The pose at @p time of a collider with @p keys (identity without keys).
Pose poseAt(const std::vector<ColliderKey>& keys, double time);

/// A collider's pose at one instant, with what the contact needs to know of its motion:
/// the rigid velocity field v(p) = linear + angular x (p - pivot).
struct ColliderMotion {
    Pose now;
    Vec3 pivot{0, 0, 0};    ///< world point that moves at `linear`
    Vec3 linear{0, 0, 0};   ///< world units / s
    Vec3 angular{0, 0, 0};  ///< radians / s, world axes

    /// Velocity of the collider's material at world point @p p (its surface there).
    Vec3 velocityAt(Vec3 p) const { return linear + cross(angular, p - pivot); }
};

/// The motion at @p time of a collider with @p keys: the velocities are the spline's
/// central differences over a tenth of a millisecond.
ColliderMotion motionAt(const std::vector<ColliderKey>& keys, double time);

}  // namespace globular
