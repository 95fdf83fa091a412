#include "collider_contact.h"

#include <algorithm>

namespace globular {

Vec3 colliderForce(const Collider& collider, const ColliderMotion& motion, Vec3 position,
                   Vec3 velocity, double radius, double mass, Vec3 otherForce, double dt) {
    const SurfaceSample s = collider.solid.sample(motion.now.toLocal(position));
    const double phi = collider.surfaceContact ? s.phi - radius : s.phi;
    if (phi >= 0) return {};
    const ColliderSettings& c = collider.settings;
    const Vec3 n = motion.now.rotate(s.normal);
    const Vec3 surfaceVelocity = motion.velocityAt(position);
    // The rest is in the collider's frame of motion; the force is the same in both.
    velocity = velocity - surfaceVelocity;
    const double normalSpeed = dot(velocity, n);
    const double normalForce = -c.ks * phi - c.kd * normalSpeed;
    Vec3 force = normalForce * n;
    if (c.friction > 0 && normalForce > 0 && dt > 0) {
        const Vec3 trial = velocity + (dt / mass) * (otherForce + force);
        const Vec3 tangential = trial - dot(trial, n) * n;
        const double speed = length(tangential);
        if (speed > 0) {
            const double stop = mass * speed / dt;  // the force that ends the sliding in dt
            force = force - (std::min(c.friction * normalForce, stop) / speed) * tangential;
        }
    }
    return force;
}

}  // namespace globular
