#pragma once
// A dynamic collider (`dynamic = true`): a rigid body moved by gravity and by the
// globules' contact forces on it, the reaction of what it does to them (two-way coupling;
// linear and angular momentum are exchanged, none made or lost). Its mass is spread
// uniformly through its solid; the centre of mass and inertia tensor are integrated over
// the solid on a grid. The integrator moves it in step with the globules (drift and
// kick, integrator.h), so that it follows the same scheme. It rests on the ground through
// points on its surface (collider_set.h); it does not meet other colliders.

#include <array>
#include <vector>

#include "collider_motion.h"
#include "vec3.h"

namespace globular {

class ColliderSolid;
struct ColliderSettings;

/// What a body's future depends on: saved in the checkpoint, bit for bit.
struct RigidBodyState {
    Vec3 position{0, 0, 0};         ///< of the centre of mass, world
    std::array<double, 4> orientation{1, 0, 0, 0};  ///< unit quaternion w x y z, local -> world
    Vec3 velocity{0, 0, 0};         ///< of the centre of mass
    Vec3 angularMomentum{0, 0, 0};  ///< about the centre of mass, world axes
    Vec3 force{0, 0, 0};            ///< on it at the last force evaluation, gravity included
    Vec3 torque{0, 0, 0};           ///< about the centre of mass, at the same time
};

class RigidBody {
public:
    /// @p solid's mass properties for @p settings.mass, at rest where its geometry puts
    /// it, with the settings' velocity and spin. @throw SceneError when the solid is not
    /// bounded (a plane) or has no volume.
    RigidBody(const ColliderSettings& settings, const ColliderSolid& solid);

    /// Where the collider's frame is now: world = R (local - centre of mass) + position.
    Pose pose() const;
    /// The motion the contacts see (velocity of the material at any point).
    ColliderMotion motion() const;
    Vec3 angularVelocity() const;  ///< radians / s, world axes

    /// Moves the body on by @p dt at its current velocities (rotation: about the current
    /// angular velocity).
    void drift(double dt);
    /// Changes its momenta by @p dt times the current force and torque.
    void kick(double dt);

    /// Points on the solid's surface (its frame), each standing for an equal share of the
    /// mass where it meets the ground (ColliderSet).
    const std::vector<Vec3>& surfacePoints() const { return mSurfacePoints; }

    double mass() const { return mMass; }
    Vec3 centreOfMass() const { return mCentreOfMass; }  ///< in the collider's frame
    /// The inertia tensor about the centre of mass, in the collider's frame.
    const std::array<std::array<double, 3>, 3>& inertia() const { return mInertia; }

    RigidBodyState state;

private:
    void collectSurfacePoints(const ColliderSolid& solid);

    double mMass;
    Vec3 mCentreOfMass;
    std::array<std::array<double, 3>, 3> mInertia{}, mInverseInertia{};
    std::vector<Vec3> mSurfacePoints;
};

}  // namespace globular
