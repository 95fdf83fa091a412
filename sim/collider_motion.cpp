#include "collider_motion.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "settings_schema.h"

namespace globular {

namespace {

/// Half the interval over which a moving collider's velocity is differenced, seconds:
/// far below a frame, far above rounding.
constexpr double kVelocityStep = 1e-4;

Vec3 catmullRom(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, double t0, double t1, double t2,
                double t3, double t) {
    // Non-uniform Catmull-Rom tangents (finite differences over the neighbours' times).
    const Vec3 m1 = (1.0 / (t2 - t0)) * (p2 - p0) * (t2 - t1);
    const Vec3 m2 = (1.0 / (t3 - t1)) * (p3 - p1) * (t2 - t1);
    const double s = (t - t1) / (t2 - t1), s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p1 + (s3 - 2 * s2 + s) * m1 + (-2 * s3 + 3 * s2) * p2 +
           (s3 - s2) * m2;
}

Pose poseOf(Vec3 position, Vec3 degrees) {
    const double toRadians = std::numbers::pi / 180;
    // x first, then y, then z: R = Rz Ry Rx.
    const Eigen::Matrix3d r =
        (Eigen::AngleAxisd(degrees.z * toRadians, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(degrees.y * toRadians, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(degrees.x * toRadians, Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    Pose pose;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.rotation[i][j] = r(i, j);
    }
    pose.translation = position;
    return pose;
}

}  // namespace

void ColliderKey::describe(SettingsSection& s) {
    s.number("time", time, NumberRange::nonNegative(), "seconds since the start");
    s.vec3("position", position, NumberRange::between(-1e6, 1e6),
           "offset of the collider at this time, world units");
    s.vec3("rotation", rotation, NumberRange::between(-1e6, 1e6),
           "degrees about x, then y, then z, at this time");
}

Vec3 Pose::rotate(Vec3 d) const {
    return {rotation[0][0] * d.x + rotation[0][1] * d.y + rotation[0][2] * d.z,
            rotation[1][0] * d.x + rotation[1][1] * d.y + rotation[1][2] * d.z,
            rotation[2][0] * d.x + rotation[2][1] * d.y + rotation[2][2] * d.z};
}

Vec3 Pose::toWorld(Vec3 local) const { return rotate(local) + translation; }

Vec3 Pose::toLocal(Vec3 world) const {
    const Vec3 d = world - translation;  // the inverse rotation is the transpose
    return {rotation[0][0] * d.x + rotation[1][0] * d.y + rotation[2][0] * d.z,
            rotation[0][1] * d.x + rotation[1][1] * d.y + rotation[2][1] * d.z,
            rotation[0][2] * d.x + rotation[1][2] * d.y + rotation[2][2] * d.z};
}

Pose poseAt(const std::vector<ColliderKey>& keys, double time) {
    if (keys.empty()) return Pose{};
    if (time <= keys.front().time) return poseOf(keys.front().position, keys.front().rotation);
    if (time >= keys.back().time) return poseOf(keys.back().position, keys.back().rotation);
    const auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                       [](double t, const ColliderKey& k) { return t < k.time; });
    const std::size_t k2 = std::size_t(next - keys.begin()), k1 = k2 - 1;
    // Beyond the ends, the neighbour is mirrored: the spline starts and ends with the
    // slope of its first and last intervals.
    const ColliderKey& a = keys[k1];
    const ColliderKey& b = keys[k2];
    const ColliderKey before = k1 > 0 ? keys[k1 - 1]
                                      : ColliderKey{2 * a.time - b.time, 2.0 * a.position - b.position,
                                                    2.0 * a.rotation - b.rotation};
    const ColliderKey after = k2 + 1 < keys.size()
                                  ? keys[k2 + 1]
                                  : ColliderKey{2 * b.time - a.time, 2.0 * b.position - a.position,
                                                2.0 * b.rotation - a.rotation};
    const auto spline = [&](Vec3 ColliderKey::*field) {
        return catmullRom(before.*field, a.*field, b.*field, after.*field, before.time, a.time,
                          b.time, after.time, time);
    };
    return poseOf(spline(&ColliderKey::position), spline(&ColliderKey::rotation));
}

ColliderMotion motionAt(const std::vector<ColliderKey>& keys, double time) {
    ColliderMotion m;
    m.now = poseAt(keys, time);
    m.pivot = m.now.translation;
    if (keys.size() < 2) return m;
    const Pose before = poseAt(keys, time - kVelocityStep), after = poseAt(keys, time + kVelocityStep);
    const double span = 2 * kVelocityStep;
    m.linear = (1.0 / span) * (after.translation - before.translation);
    // The rotation over the span, after * before^-1, as an axis times an angle.
    Eigen::Matrix3d a, b;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a(i, j) = after.rotation[i][j];
            b(i, j) = before.rotation[i][j];
        }
    }
    const Eigen::AngleAxisd turn(a * b.transpose());
    const Eigen::Vector3d w = (turn.angle() / span) * turn.axis();
    m.angular = {w.x(), w.y(), w.z()};
    return m;
}

}  // namespace globular
