#pragma once
// The colliders of a run as the force loop uses them: each one's solid, ready to sample,
// its contact constants, and what moves it (keyframes read at the set's clock, or a rigid
// body). The integrator advances the set in step with the globules (CoIntegrated): the
// clock and the bodies drift where the globules' positions move and the bodies are kicked
// where their velocities change, so a keyframed collider is sampled at the time of the
// state being evaluated and a body follows the globules' own scheme.

#include <filesystem>
#include <vector>

#include "collider.h"
#include "collider_motion.h"
#include "collider_solid.h"
#include "co_integrated.h"
#include "rigid_body.h"
#include "simulation_settings.h"

namespace globular {

struct Collider {
    ColliderSettings settings;
    ColliderSolid solid;
    bool surfaceContact = false;  ///< contact = "surface": phi is taken at the globule's surface
    int body = -1;                ///< index into ColliderSet::bodies(), or -1
};

/// A force and a torque (about a body's centre of mass).
struct Wrench {
    Vec3 force{0, 0, 0};
    Vec3 torque{0, 0, 0};
};

class ColliderSet final : public CoIntegrated {
public:
    ColliderSet() = default;
    /// @param reach how far outside a mesh collider its distance must be exact (the
    ///        largest globule radius, at least).
    /// @throw SceneError naming a collider whose solid cannot be built.
    ColliderSet(const std::vector<ColliderSettings>& settings,
                const std::filesystem::path& sceneDir, double reach, Vec3 gravity,
                const GroundSettings& ground = GroundSettings{});

    bool empty() const { return mColliders.empty(); }
    std::size_t size() const { return mColliders.size(); }
    const Collider& operator[](std::size_t k) const { return mColliders[k]; }

    double time() const { return mTime; }
    void setTime(double time) { mTime = time; }
    /// Every collider's pose and motion now.
    std::vector<ColliderMotion> motions() const;

    std::vector<RigidBody>& bodies() { return mBodies; }
    const std::vector<RigidBody>& bodies() const { return mBodies; }
    /// Sets each body's force and torque to gravity, the ground's push and @p reactions
    /// (one per body: what the globules push back with). A body meets the ground at its
    /// surface points, each with the ground's k_s and k_d per unit mass on its share of
    /// the body's mass (as a globule of mass 1 meets it); k_d damps the points' sliding
    /// too, so a body that lands comes to rest.
    void setReactions(const std::vector<Wrench>& reactions);

    void drift(double dt) override;
    void kick(double dt) override;

private:
    std::vector<Collider> mColliders;
    std::vector<RigidBody> mBodies;
    Vec3 mGravity{0, 0, 0};
    GroundSettings mGround;
    double mTime = 0;
};

}  // namespace globular
