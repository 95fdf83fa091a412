#include "camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace globular {

namespace {

// The view direction of automatic framing: from the front-right, 20 degrees above the
// horizon. High enough that the ground and shadows read, low enough that heights do.
constexpr double kAzimuthDegrees = 30;
constexpr double kElevationDegrees = 20;
constexpr double kFill = 0.9;  // the content fills at most this fraction of the image

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

}  // namespace

ViewCamera autoFrame(const SceneExtent& extent, double groundHeight, double fov, double aspect) {
    std::vector<Vec3> points = extent.samples;
    points.insert(points.end(), extent.extremes.begin(), extent.extremes.end());
    double pad = extent.maxRadius;
    if (points.empty()) {
        Bounds3 box = extent.box;
        if (box.empty) {
            box.add(Vec3{-2, groundHeight, -2});
            box.add(Vec3{2, groundHeight + 1, 2});
        }
        for (int corner = 0; corner < 8; ++corner) {
            points.push_back({(corner & 1) ? box.max.x : box.min.x,
                              (corner & 2) ? box.max.y : box.min.y,
                              (corner & 4) ? box.max.z : box.min.z});
        }
        pad = 0;
    }
    // Show where the content meets the ground (and its shadow), not only the content.
    const std::size_t count = points.size();
    for (std::size_t i = 0; i < count; ++i)
        points.push_back({points[i].x, groundHeight, points[i].z});

    const double azimuth = radians(kAzimuthDegrees), elevation = radians(kElevationDegrees);
    const Vec3 toEye{std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                     std::cos(elevation) * std::cos(azimuth)};
    const Vec3 forward = -1.0 * toEye;
    const Vec3 side = normalized(cross(forward, Vec3{0, 1, 0}));
    const Vec3 up = cross(side, forward);
    const double tanY = std::tan(radians(fov) / 2) * kFill;
    const double tanX = tanY * aspect;

    Bounds3 box;
    for (const Vec3& p : points) box.add(p);
    Vec3 target = box.center();
    // The distance at which every point fits around the current target.
    auto fit = [&] {
        double distance = pad + 1e-6;
        for (const Vec3& p : points) {
            const Vec3 o = p - target;
            const double depth = dot(o, forward);  // beyond the target: positive
            distance = std::max({distance, (std::abs(dot(o, side)) + pad) / tanX - depth,
                                 (std::abs(dot(o, up)) + pad) / tanY - depth,
                                 2 * pad - depth});  // never inside the content
        }
        return distance;
    };
    // Fit, then re-aim at the middle of what the camera sees (the view from a corner makes
    // the content's projection lopsided about the box's centre), and fit again.
    double distance = fit();
    for (int pass = 0; pass < 3; ++pass) {
        double left = 1e300, right = -1e300, bottom = 1e300, top = -1e300;
        for (const Vec3& p : points) {
            const Vec3 o = p - target;
            const double scale = 1.0 / (distance + dot(o, forward));
            left = std::min(left, (dot(o, side) - pad) * scale);
            right = std::max(right, (dot(o, side) + pad) * scale);
            bottom = std::min(bottom, (dot(o, up) - pad) * scale);
            top = std::max(top, (dot(o, up) + pad) * scale);
        }
        target = target + side * (0.5 * (left + right) * distance) +
                 up * (0.5 * (bottom + top) * distance);
        distance = fit();
    }
    return {target + toEye * distance, target, fov};
}

DepthRange depthRange(Vec3 eye, const Bounds3& content, double groundReach) {
    const Vec3 center = content.empty ? Vec3{} : content.center();
    const double radius = std::max(content.empty ? 1.0 : content.radius(), 1e-3);
    const double toCenter = length(eye - center);
    const double zFar = toCenter + std::max(radius, groundReach) * 1.5;
    // The ground can come close to the camera anywhere below it, so the near plane is a
    // small fraction of the view distance; 24-bit depth keeps 1:10^4 ratios clean.
    const double zNear = std::max(zFar * 1e-4, std::min(0.05 * toCenter, toCenter - radius));
    return {std::max(zNear, 1e-4), zFar};
}

}  // namespace globular
