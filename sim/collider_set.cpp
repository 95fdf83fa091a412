#include "collider_set.h"

namespace globular {

ColliderSet::ColliderSet(const std::vector<ColliderSettings>& settings,
                         const std::filesystem::path& sceneDir, double reach, Vec3 gravity,
                         const GroundSettings& ground)
    : mGravity(gravity), mGround(ground) {
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

namespace {

/// The ground's push on @p body through its surface points below it.
Wrench groundPush(const RigidBody& body, const GroundSettings& ground) {
    Wrench push;
    if (!ground.enabled) return push;
    const ColliderMotion motion = body.motion();
    const double share = body.mass() / double(body.surfacePoints().size());
    for (const Vec3& local : body.surfacePoints()) {
        const Vec3 p = motion.now.toWorld(local);
        const double depth = p.y - ground.height;
        if (depth >= 0) continue;
        const Vec3 v = motion.velocityAt(p);
        const double fy = share * (-ground.ks * depth - ground.kd * v.y);
        if (fy <= 0) continue;  // the ground pushes, never pulls
        // It damps the point's sliding as well, so a body comes to rest (a grip the
        // frictionless ground of eq. (9) does not give globules).
        const Vec3 f{-share * ground.kd * v.x, fy, -share * ground.kd * v.z};
        push.force = push.force + f;
        push.torque = push.torque + cross(p - motion.pivot, f);
    }
    return push;
}

}  // namespace

void ColliderSet::setReactions(const std::vector<Wrench>& reactions) {
    for (std::size_t b = 0; b < mBodies.size(); ++b) {
        const Wrench ground = groundPush(mBodies[b], mGround);
        mBodies[b].state.force = reactions[b].force + ground.force + mBodies[b].mass() * mGravity;
        mBodies[b].state.torque = reactions[b].torque + ground.torque;
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
