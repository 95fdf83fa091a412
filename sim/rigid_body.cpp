#include "rigid_body.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <numbers>

#include "collider.h"
#include "collider_solid.h"
#include "errors.h"

namespace globular {

namespace {

/// Grid samples per axis over the solid's bounds for its mass properties: the centre of
/// mass and inertia come out within a fraction of a percent for the shapes here.
constexpr int kMassSamples = 64;
/// Grid samples per axis for the surface points of the ground contact: a few thousand
/// points, symmetric where the solid is (a sphere resting on its points feels no torque).
constexpr int kSurfaceSamples = 24;

Eigen::Quaterniond quaternion(const std::array<double, 4>& q) { return {q[0], q[1], q[2], q[3]}; }

Eigen::Vector3d eigen(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Eigen::Matrix3d matrix(const std::array<std::array<double, 3>, 3>& m) {
    Eigen::Matrix3d out;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) out(i, j) = m[i][j];
    }
    return out;
}

}  // namespace

RigidBody::RigidBody(const ColliderSettings& settings, const ColliderSolid& solid)
    : mMass(settings.mass) {
    if (!solid.bounded()) {
        throw SceneError("[[collider]] '" + settings.name + "': a " + settings.shape +
                         " has no finite volume and cannot be dynamic");
    }
    // Midpoint rule over the bounds: volume, first and second moments of the solid.
    const Vec3 lo = solid.boundsMin(), extent = solid.boundsMax() - solid.boundsMin();
    const Vec3 cell = (1.0 / kMassSamples) * extent;
    constexpr int n = kMassSamples;
    const auto centreOf = [&](int i, int j, int k) {
        return lo + Vec3{(i + 0.5) * cell.x, (j + 0.5) * cell.y, (k + 0.5) * cell.z};
    };
    double volume = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                const Vec3 p = centreOf(i, j, k);
                if (!(solid.sample(p).phi < 0)) continue;
                const Eigen::Vector3d e = eigen(p);
                volume += 1;
                first += e;
                second += e * e.transpose();
            }
        }
    }
    collectSurfacePoints(solid);
    if (volume == 0) {
        throw SceneError("[[collider]] '" + settings.name +
                         "': its solid has no volume to give a mass to");
    }
    const Eigen::Vector3d centre = first / volume;
    // Inertia about the centre: m (tr(C) I - C) with C the covariance of the samples.
    const Eigen::Matrix3d covariance = second / volume - centre * centre.transpose();
    const Eigen::Matrix3d inertia =
        mMass * (covariance.trace() * Eigen::Matrix3d::Identity() - covariance);
    const Eigen::Matrix3d inverse = inertia.inverse();
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            mInertia[a][b] = inertia(a, b);
            mInverseInertia[a][b] = inverse(a, b);
        }
    }
    mCentreOfMass = vec(centre);
    state.position = mCentreOfMass;
    state.velocity = settings.velocity;
    const double toRadians = std::numbers::pi / 180;
    state.angularMomentum = vec(inertia * (toRadians * eigen(settings.angularVelocity)));
}

void RigidBody::collectSurfacePoints(const ColliderSolid& solid) {
    // Cells inside with a face on the outside (or on the bounds), moved onto the surface
    // along the normal.
    constexpr int n = kSurfaceSamples;
    const Vec3 lo = solid.boundsMin(), cell = (1.0 / n) * (solid.boundsMax() - lo);
    const auto centreOf = [&](int i, int j, int k) {
        return lo + Vec3{(i + 0.5) * cell.x, (j + 0.5) * cell.y, (k + 0.5) * cell.z};
    };
    std::vector<uint8_t> inside(std::size_t(n) * n * n);
    const auto at = [&](int i, int j, int k) -> uint8_t& {
        return inside[(std::size_t(i) * n + std::size_t(j)) * n + std::size_t(k)];
    };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) at(i, j, k) = solid.sample(centreOf(i, j, k)).phi < 0;
        }
    }
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                if (!at(i, j, k)) continue;
                const bool onBounds =
                    i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
                if (onBounds || !at(i - 1, j, k) || !at(i + 1, j, k) || !at(i, j - 1, k) ||
                    !at(i, j + 1, k) || !at(i, j, k - 1) || !at(i, j, k + 1)) {
                    const Vec3 p = centreOf(i, j, k);
                    const SurfaceSample s = solid.sample(p);
                    mSurfacePoints.push_back(p - s.phi * s.normal);
                }
            }
        }
    }
}

Pose RigidBody::pose() const {
    const Eigen::Matrix3d r = quaternion(state.orientation).toRotationMatrix();
    Pose pose;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.rotation[i][j] = r(i, j);
    }
    pose.translation = state.position - pose.rotate(mCentreOfMass);
    return pose;
}

Vec3 RigidBody::angularVelocity() const {
    // omega = R I^-1 R^T L: the inverse inertia turned into world axes.
    const Eigen::Matrix3d r = quaternion(state.orientation).toRotationMatrix();
    return vec(r * matrix(mInverseInertia) * r.transpose() * eigen(state.angularMomentum));
}

ColliderMotion RigidBody::motion() const {
    ColliderMotion m;
    m.now = pose();
    m.pivot = state.position;
    m.linear = state.velocity;
    m.angular = angularVelocity();
    return m;
}

void RigidBody::drift(double dt) {
    const Vec3 omega = angularVelocity();
    state.position = state.position + dt * state.velocity;
    const double angle = length(omega) * dt;
    if (angle > 0) {
        const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle, eigen(normalized(omega))));
        const Eigen::Quaterniond q = (turn * quaternion(state.orientation)).normalized();
        state.orientation = {q.w(), q.x(), q.y(), q.z()};
    }
}

void RigidBody::kick(double dt) {
    state.velocity = state.velocity + (dt / mMass) * state.force;
    state.angularMomentum = state.angularMomentum + dt * state.torque;
}

}  // namespace globular
