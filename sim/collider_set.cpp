#include "collider_set.h"

namespace globular {

ColliderSet::ColliderSet(const std::vector<ColliderSettings>& settings,
                         const std::filesystem::path& sceneDir, double reach, Vec3 gravity)
    : mGravity(gravity) {
    for (const ColliderSettings& s : settings) {
        Collider c{s, ColliderSolid(s, sceneDir, reach), s.contact == "surface", -1};
        if (s.dynamic) {
            c.body = int(mBodies.size());
            mBodies.emplace_back(s, c.solid);
        }
        mColliders.push_back(std::move(c));
    }
    setReactions(std::vector<Wrench>(mBodies.size()));
}

std::vector<ColliderMotion> ColliderSet::motions() const {
    std::vector<ColliderMotion> motions;
    motions.reserve(mColliders.size());
    for (const Collider& c : mColliders) {
        motions.push_back(c.body >= 0 ? mBodies[std::size_t(c.body)].motion()
                                      : motionAt(c.settings.keys, mTime));
    }
    return motions;
}

void ColliderSet::setReactions(const std::vector<Wrench>& reactions) {
    for (std::size_t b = 0; b < mBodies.size(); ++b) {
        mBodies[b].state.force = reactions[b].force + mBodies[b].mass() * mGravity;
        mBodies[b].state.torque = reactions[b].torque;
    }
}

void ColliderSet::drift(double dt) {
    mTime += dt;
    for (RigidBody& body : mBodies) body.drift(dt);
}

void ColliderSet::kick(double dt) {
    for (RigidBody& body : mBodies) body.kick(dt);
}

}  // namespace globular
