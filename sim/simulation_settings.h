#pragma once
// The `[simulation]`, `[ground]` and `[output]` sections of a scene.

#include <cstdint>
#include <string>

#include "vec3.h"

namespace globular {

class SettingsSection;
class Reporter;

struct SimulationSettings {
    static constexpr int64_t kMaxStepsPerFrame = 1000000;
    static constexpr double kMinFrameSeconds = 1e-6, kMaxFrameSeconds = 3600;

    double dt = 0.001;                 ///< time step, seconds (paper: 0.001); adaptive: the longest
    /// Steps as long as stability allows, up to dt (stable_step.h); frames still end on
    /// their instants. Off: the paper's fixed dt.
    bool adaptive = false;
    double fps = 25;                   ///< frames per second of the output
    int64_t frames = 150;              ///< frames written, the first being the initial state
    std::string integrator = "forward_euler";  ///< forward_euler | semi_implicit_euler | velocity_verlet
    std::string neighbors = "grid";    ///< grid (cell lists, O(N)) | all_pairs (the paper's O(N^2))
    Vec3 gravity{0, -9.8, 0};          ///< world units / s^2
    int64_t seed = 1;                  ///< seeds every random choice (emitter jitter)
    double maxSpeed = 1000;            ///< a globule faster than this counts as an explosion, units/s
    std::string onExplosion = "stop";  ///< stop | substep (retry the frame with smaller steps)

    void describe(SettingsSection& section);
    /// Also the derived quantities: steps per frame at most kMaxStepsPerFrame, a frame
    /// lasting between kMinFrameSeconds and kMaxFrameSeconds.
    void validate(const SettingsSection& section, Reporter& reporter) const;

    /// Steps per frame: the smallest count whose step does not exceed dt.
    int64_t substepsPerFrame() const;
    /// The step actually taken: 1 / (fps * substepsPerFrame()) <= dt.
    double stepSeconds() const;
};

/// The paper's penalty ground plane of eq. (9), normal +y.
struct GroundSettings {
    bool enabled = true;
    double height = 0;       ///< y of the plane, world units
    double ks = 5000;        ///< stiffness (paper: 5000)
    double kd = 300;         ///< damping (paper: 300)
    std::string contact = "center";  ///< center (paper: half a globule sinks) | surface

    void describe(SettingsSection& section);
};

struct OutputSettings {
    // cache/globules.NNNN.vdb (OpenVDB points, for Houdini) is always written: the
    // surface and render stages read it.
    bool ply = false;  ///< cache/globules.NNNN.ply as well (for Blender)

    void describe(SettingsSection& section);
};

}  // namespace globular
