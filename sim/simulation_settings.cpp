#include "simulation_settings.h"

#include <cmath>
#include <sstream>

#include "errors.h"
#include "reporter.h"
#include "settings_schema.h"

namespace globular {

void SimulationSettings::describe(SettingsSection& s) {
    s.number("dt", dt, NumberRange::positive(),
             "time step, seconds; with adaptive = true the longest step taken");
    s.flag("adaptive", adaptive,
           "adaptive time steps: each step as long as the contact and speed stability bounds "
           "allow (at most dt), each frame still ending on its instant; the run's summary "
           "says how many steps it saved. false: the paper's fixed dt");
    s.number("fps", fps, NumberRange::positive(), "frames per second");
    s.integer("frames", frames, 1, 1000000, "frames written; frame 1 is the initial state");
    s.choice("integrator", integrator,
             {"forward_euler", "semi_implicit_euler", "velocity_verlet"},
             "time integration scheme");
    s.choice("neighbors", neighbors, {"grid", "all_pairs"}, "neighbour search");
    s.vec3("gravity", gravity, NumberRange::any(), "acceleration, world units / s^2");
    s.integer("seed", seed, 0, INT64_MAX, "random seed for emitter jitter");
    s.number("max_speed", maxSpeed, NumberRange::positive(),
             "speed above which the simulation counts as exploded, units / s");
    s.choice("on_explosion", onExplosion, {"stop", "substep"},
             "stop with an error, or retry the frame with smaller steps");
}

int64_t SimulationSettings::substepsPerFrame() const {
    // In floating point first: dt = 1e-22 must not overflow the integer.
    const double steps = std::ceil(1.0 / (fps * dt) - 1e-9);
    if (!(steps < 9e18)) return INT64_MAX;
    return std::max<int64_t>(1, int64_t(steps));
}

double SimulationSettings::stepSeconds() const {
    return 1.0 / (fps * double(substepsPerFrame()));
}

void SimulationSettings::validate(const SettingsSection& s, Reporter& reporter) const {
    // Limits on what dt and fps derive, checked after the derivation.
    const double frameSeconds = 1.0 / fps;
    if (!(frameSeconds >= kMinFrameSeconds && frameSeconds <= kMaxFrameSeconds)) {
        throw SceneError(s.describeKey("fps") + ": frames of " + numberForMessage(frameSeconds) +
                         " s; a frame must last between 1e-06 s and 3600 s");
    }
    const double steps = 1.0 / (fps * dt);
    if (!(steps <= double(kMaxStepsPerFrame))) {
        throw SceneError(s.describeKey("dt") + ": " + numberForMessage(steps) +
                         " steps per frame (at fps " + numberForMessage(fps) +
                         ") is more than the limit of " + std::to_string(kMaxStepsPerFrame));
    }
    if (!adaptive && std::abs(stepSeconds() - dt) > 1e-6 * dt) {
        reporter.info("dt " + std::to_string(dt) + " s does not divide a frame; using " +
                      std::to_string(stepSeconds()) + " s (" +
                      std::to_string(substepsPerFrame()) + " steps per frame)");
    }
}

void GroundSettings::describe(SettingsSection& s) {
    s.flag("enabled", enabled, "whether the ground plane exists");
    s.number("height", height, NumberRange::any(), "y of the plane, world units");
    s.number("ks", ks, NumberRange::nonNegative(), "penalty stiffness of eq. (9)");
    s.number("kd", kd, NumberRange::nonNegative(), "penalty damping of eq. (9)");
    s.choice("contact", contact, {"center", "surface"},
             "contact at the globule centre (paper) or at its surface (containers)");
}

void OutputSettings::describe(SettingsSection& s) {
    s.flag("ply", ply, "also write cache/globules.NNNN.ply (binary PLY)");
}

}  // namespace globular
