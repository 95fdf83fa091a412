#pragma once
// The seam between the integrator and what it moves besides the globules.

namespace globular {

/// What moves along with the globules under the same scheme (the colliders' clock and
/// rigid bodies, collider_set.h): the integrator calls drift where it moves positions by
/// velocities and kick where it changes velocities by the last accelerations.
class CoIntegrated {
public:
    virtual ~CoIntegrated() = default;
    virtual void drift(double dt) = 0;
    virtual void kick(double dt) = 0;
};

}  // namespace globular
