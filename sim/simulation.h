#pragma once
// One running simulation: globules, emitters, forces and an integrator, advanced a
// frame at a time. Stops with a SimulationError naming the frame and step when the
// state blows up (the paper's Fig. 4), or retries the frame with smaller steps when the
// scene asks for it (on_explosion = "substep").

#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "collider_set.h"
#include "emitter.h"
#include "forces.h"
#include "globules.h"
#include "integrator.h"
#include "material.h"
#include "material_pairs.h"
#include "simulation_settings.h"
#include "stable_step.h"
#include "thermal_settings.h"

namespace globular {

class Reporter;

/// Everything a simulation needs from a scene.
struct SimulationSetup {
    SimulationSettings simulation;
    MaterialSettings material;  ///< the first (or only) material
    GroundSettings ground;
    std::vector<EmitterSettings> emitters;
    std::filesystem::path sceneDir;  ///< relative emitter paths resolve against it
    std::vector<ColliderSettings> colliders;  ///< [[collider]]
    std::vector<MaterialSettings> otherMaterials;  ///< [[material]] sections after the first
    std::vector<MaterialPairSettings> materialPairs;  ///< [[material_pair]]
    ThermalSettings thermal;               ///< [thermal]
    std::vector<HeaterSettings> heaters;   ///< [[heater]]

    /// material, then otherMaterials: globule material k is materials()[k].
    std::vector<MaterialSettings> materials() const;
};

/// Everything that determines the future of a run: saving and restoring it reproduces
/// an uninterrupted run bit for bit.
struct SimulationState {
    Globules globules;
    double time = 0;
    int64_t steps = 0;
    int32_t nextId = 0;
    std::vector<std::size_t> emitted;  ///< per emitter
    Accelerations carried;             ///< integrator state (velocity Verlet), may be empty
    std::vector<RigidBodyState> bodies;  ///< dynamic colliders, in scene order
};

class Simulation {
public:
    /// Emits the globules due at t = 0: the state of frame 1.
    explicit Simulation(const SimulationSetup& setup);

    /// Advances one frame (1/fps seconds). @param frame the frame being produced, for
    /// messages. @throw SimulationError when the state becomes non-finite or too fast.
    void advanceFrame(int frame, Reporter& reporter);

    /// One step of @p dt seconds (emission, forces, integration), no checks.
    void step(double dt);

    const Globules& globules() const { return mGlobules; }
    Globules& globules() { return mGlobules; }
    double time() const { return mTime; }
    int64_t stepCount() const { return mSteps; }
    /// The shortest adaptive step this object has taken (not kept across a resume), s;
    /// infinity before the first.
    double shortestStep() const { return mShortestStep; }
    /// Globules the emitters will have produced by the end (for memory estimates).
    std::size_t plannedCount() const;
    /// The same, from the settings alone, before any emitter places a globule (points
    /// emitters count 0). Saturates at SIZE_MAX.
    static std::size_t plannedCount(const SimulationSetup& setup);

    /// How far outside a mesh collider its distance field must be exact: beyond the
    /// largest globule radius (contact = "surface" measures from the globule's surface).
    static double colliderReach(const SimulationSetup& setup);

    SimulationState saveState() const;
    /// @throw Error when @p state does not fit this scene (emitter or body count).
    void restoreState(const SimulationState& state);

    const SimulationSetup& setup() const { return mSetup; }
    /// The colliders as they stand now (poses for the outputs).
    const ColliderSet& colliders() const { return mForces.colliders(); }
    /// The build of the force loops this run uses (simd_path.h); a run's future depends
    /// on it to rounding, so tests compare paths by setting it before the first step.
    SimdPath simdPath() const { return mForces.simdPath(); }
    void setSimdPath(SimdPath path) { mForces.setSimdPath(path); }

private:
    /// Emits what emitter @p k has due at @p time.
    /// @throw SceneError naming the emitter when a globule it placed is not finite (a
    ///        centre, spacing or jitter so large that positions overflow).
    void emitFrom(std::size_t k, double time);
    /// Index of a non-finite or too-fast globule after a step, or -1.
    long findRunaway() const;
    /// Steps to the frame's end at @p frameEnd, each of (frame length) / @p steps (fixed
    /// dt) or, with @p steps = 0, as long as StableStep allows divided by @p refine.
    /// @return -1, or a runaway globule (the state is then left as it blew up).
    long stepTo(double frameEnd, int64_t steps, int refine, int64_t& taken);

    SimulationSetup mSetup;
    Globules mGlobules;
    ForceField mForces;
    StableStep mStableStep;
    std::unique_ptr<Integrator> mIntegrator;
    std::vector<std::unique_ptr<Emitter>> mEmitters;
    std::vector<uint8_t> mEmitterMaterials;  ///< per emitter; empty with one material
    int32_t mNextId = 0;
    double mTime = 0;
    int64_t mSteps = 0;
    double mShortestStep = std::numeric_limits<double>::infinity();
};

}  // namespace globular
