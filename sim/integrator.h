#pragma once
// Time integration of positions and velocities. The paper uses forward Euler; we also
// offer semi-implicit (symplectic) Euler and velocity Verlet (PAPER_NOTES.md).

#include <functional>
#include <memory>
#include <string>

#include "co_integrated.h"
#include "forces.h"
#include "globules.h"

namespace globular {

/// Fills accelerations for the globules' current positions and velocities. It may
/// reorder the globules (ForceField sorts them into neighbour-grid order); the
/// accelerations are then in the new order.
using AccelerationFunction = std::function<void(Globules&, Accelerations&)>;

class Integrator {
public:
    virtual ~Integrator() = default;
    /// Advances @p globules, and @p partner when given, by @p dt seconds.
    void step(Globules& globules, float dt, const AccelerationFunction& accelerate,
              CoIntegrated* partner = nullptr);
    /// Accelerations kept between steps (velocity Verlet), or nullptr. Exact resumption
    /// of a run needs them.
    virtual Accelerations* carriedState() { return nullptr; }

private:
    virtual void advance(Globules& globules, float dt, const AccelerationFunction& accelerate,
                         CoIntegrated& partner) = 0;
};

/// x += dt v; v += dt a, both from the old state: the paper's scheme. First order.
class ForwardEuler final : public Integrator {
private:
    void advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                 CoIntegrated& partner) override;

    Accelerations mA;
};

/// v += dt a; x += dt v (new velocity). First order, but symplectic: stabler.
class SemiImplicitEuler final : public Integrator {
private:
    void advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                 CoIntegrated& partner) override;

    Accelerations mA;
};

/// x += dt v + dt^2/2 a; v += dt/2 (a + a_new). Second order. The drag depends on
/// velocity, so a_new is evaluated at the half-step velocity v + dt/2 a (as in DPD).
class VelocityVerlet final : public Integrator {
public:
    Accelerations* carriedState() override { return &mA; }

private:
    void advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                 CoIntegrated& partner) override;

    Accelerations mA;  ///< accelerations at the current state, valid when sized to N
};

/// @param name forward_euler | semi_implicit_euler | velocity_verlet
/// @throw Error for any other name.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name);

}  // namespace globular
