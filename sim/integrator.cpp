#include "integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "errors.h"

namespace globular {

namespace {

template <typename Body>
void forEachGlobule(std::size_t n, Body&& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

/// T += dt dT/dt, explicit in every scheme: heat spreads far slower than globules move,
/// and the rate depends on positions and temperatures only.
void advanceTemperature(Globules& g, const Accelerations& a, float dt) {
    if (g.temperature.empty()) return;
    forEachGlobule(g.size(), [&](std::size_t i) { g.temperature[i] += dt * a.heat[i]; });
}

/// Nothing moving besides the globules.
class Nothing final : public CoIntegrated {
public:
    void drift(double) override {}
    void kick(double) override {}
};

}  // namespace

void Integrator::step(Globules& g, float dt, const AccelerationFunction& accelerate,
                      CoIntegrated* partner) {
    Nothing nothing;
    advance(g, dt, accelerate, partner ? *partner : nothing);
}

void ForwardEuler::advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                           CoIntegrated& partner) {
    accelerate(g, mA);
    advanceTemperature(g, mA, dt);
    forEachGlobule(g.size(), [&](std::size_t i) {
        g.px[i] += dt * g.vx[i];
        g.py[i] += dt * g.vy[i];
        g.pz[i] += dt * g.vz[i];
        g.vx[i] += dt * mA.x[i];
        g.vy[i] += dt * mA.y[i];
        g.vz[i] += dt * mA.z[i];
    });
    partner.drift(dt);
    partner.kick(dt);
}

void SemiImplicitEuler::advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                                CoIntegrated& partner) {
    accelerate(g, mA);
    advanceTemperature(g, mA, dt);
    forEachGlobule(g.size(), [&](std::size_t i) {
        g.vx[i] += dt * mA.x[i];
        g.vy[i] += dt * mA.y[i];
        g.vz[i] += dt * mA.z[i];
        g.px[i] += dt * g.vx[i];
        g.py[i] += dt * g.vy[i];
        g.pz[i] += dt * g.vz[i];
    });
    partner.kick(dt);
    partner.drift(dt);
}

void VelocityVerlet::advance(Globules& g, float dt, const AccelerationFunction& accelerate,
                             CoIntegrated& partner) {
    // Globules added since the last step (a spout) invalidate the carried accelerations.
    if (mA.x.size() != g.size()) accelerate(g, mA);
    const float half = 0.5f * dt;
    advanceTemperature(g, mA, dt);
    forEachGlobule(g.size(), [&](std::size_t i) {
        g.px[i] += dt * (g.vx[i] + half * mA.x[i]);
        g.py[i] += dt * (g.vy[i] + half * mA.y[i]);
        g.pz[i] += dt * (g.vz[i] + half * mA.z[i]);
        g.vx[i] += half * mA.x[i];
        g.vy[i] += half * mA.y[i];
        g.vz[i] += half * mA.z[i];
    });
    partner.kick(half);
    partner.drift(dt);
    accelerate(g, mA);
    forEachGlobule(g.size(), [&](std::size_t i) {
        g.vx[i] += half * mA.x[i];
        g.vy[i] += half * mA.y[i];
        g.vz[i] += half * mA.z[i];
    });
    partner.kick(half);
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name) {
    if (name == "forward_euler") return std::make_unique<ForwardEuler>();
    if (name == "semi_implicit_euler") return std::make_unique<SemiImplicitEuler>();
    if (name == "velocity_verlet") return std::make_unique<VelocityVerlet>();
    throw Error("unknown integrator '" + name + "'");
}

}  // namespace globular
