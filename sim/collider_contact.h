#pragma once
// The force of a collider on one globule: eq. (9)'s penalty generalised to the collider's
// signed distance, and Coulomb friction.
//
// Friction opposes the tangential velocity the globule would have after the step (its
// velocity plus what the other forces on it would add over dt) with at most mu times the
// normal force. When that is enough to stop it, it stops it exactly (static friction:
// a globule at rest on a slope with tan(theta) <= mu stays, without jitter); otherwise it
// slides against mu times the normal force (kinetic friction).

#include "collider_set.h"
#include "vec3.h"

namespace globular {

/// Damping and friction act on the velocity relative to the collider's surface, so a
/// moving collider pushes and drags.
/// @param motion the collider's pose and motion at this step (collider_motion.h).
/// @param otherForce the force already on the globule (pairs, gravity, ground, other
///        colliders), for the static-friction limit.
/// @param dt the step about to be taken, seconds.
Vec3 colliderForce(const Collider& collider, const ColliderMotion& motion,
                   Vec3 position, Vec3 velocity, double radius, double mass, Vec3 otherForce,
                   double dt);

}  // namespace globular
