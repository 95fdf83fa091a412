#include "camera.h"

#include <algorithm>
#include <array>
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

struct ViewAxes {
    Vec3 toEye, forward, side, up;
};

ViewAxes viewAxes() {
    const double azimuth = radians(kAzimuthDegrees), elevation = radians(kElevationDegrees);
    ViewAxes a;
    a.toEye = {std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
               std::cos(elevation) * std::cos(azimuth)};
    a.forward = -1.0 * a.toEye;
    a.side = normalized(cross(a.forward, Vec3{0, 1, 0}));
    a.up = cross(a.side, a.forward);
    return a;
}

/// The value that a fraction @p keep of @p values lie at or above (at or below for
/// @p upper): the window edge that holds the content of that many frames.
double quantileEdge(std::vector<double> values, double keep, bool upper) {
    // The smallest count of values that is at least that fraction of them.
    const std::size_t n = values.size();
    const auto held = std::clamp<std::size_t>(std::size_t(std::ceil(keep * double(n) - 1e-9)), 1, n);
    const std::size_t k = upper ? held - 1 : n - held;
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
}

/// Frames the frames' boxes (each with its foot on the ground): the window that holds
/// each edge of the content in kFramedFraction of the frames, centred and filling kFill
/// of the image in its tighter direction.
ViewCamera frameTheAction(const std::vector<Bounds3>& frames, double groundHeight, double fov,
                          double aspect) {
    const ViewAxes a = viewAxes();
    const double tanY = std::tan(radians(fov) / 2) * kFill;
    const double tanX = tanY * aspect;
    std::vector<std::array<Vec3, 8>> corners;
    for (const Bounds3& b : frames) {
        std::array<Vec3, 8> c;
        const double bottom = std::min(b.min.y, groundHeight);  // its foot, and its shadow
        for (int k = 0; k < 8; ++k) {
            c[k] = {(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : bottom,
                    (k & 4) ? b.max.z : b.min.z};
        }
        corners.push_back(c);
    }
    // Start from the typical frame (the median of the frames' centres and sizes), then
    // re-aim and re-fit to the quantiles until they hold still.
    const std::size_t n = frames.size();
    std::vector<double> xs, ys, zs, sizes;
    for (const Bounds3& b : frames) {
        xs.push_back(b.center().x);
        ys.push_back(b.center().y);
        zs.push_back(b.center().z);
        sizes.push_back(b.radius());
    }
    Vec3 target{quantileEdge(xs, 0.5, true), quantileEdge(ys, 0.5, true),
                quantileEdge(zs, 0.5, true)};
    const double size = std::max(quantileEdge(sizes, 0.5, true), 1e-6);
    double distance = size / std::min(tanX, tanY) + size;
    std::vector<double> left(n), right(n), bottom(n), top(n);
    for (int pass = 0; pass < 16; ++pass) {
        for (std::size_t f = 0; f < n; ++f) {
            left[f] = bottom[f] = 1e300;
            right[f] = top[f] = -1e300;
            for (const Vec3& p : corners[f]) {
                const Vec3 o = p - target;
                const double depth = distance + dot(o, a.forward);
                const double scale = 1.0 / std::max(depth, 1e-9 * distance);
                left[f] = std::min(left[f], dot(o, a.side) * scale);
                right[f] = std::max(right[f], dot(o, a.side) * scale);
                bottom[f] = std::min(bottom[f], dot(o, a.up) * scale);
                top[f] = std::max(top[f], dot(o, a.up) * scale);
            }
        }
        const double l = quantileEdge(left, kFramedFraction, false);
        const double r = quantileEdge(right, kFramedFraction, true);
        const double b = quantileEdge(bottom, kFramedFraction, false);
        const double t = quantileEdge(top, kFramedFraction, true);
        target = target + a.side * (0.5 * (l + r) * distance) + a.up * (0.5 * (b + t) * distance);
        distance *= std::max({0.5 * (r - l) / tanX, 0.5 * (t - b) / tanY, 1e-6});
    }
    return {target + a.toEye * distance, target, fov};
}

/// The frames that hold something (an empty frame has nothing to frame).
std::vector<Bounds3> nonEmpty(const std::vector<Bounds3>& frames) {
    std::vector<Bounds3> kept;
    for (const Bounds3& b : frames) {
        if (!b.empty) kept.push_back(b);
    }
    return kept;
}

}  // namespace

ViewCamera autoFrame(const SceneExtent& extent, double groundHeight, double fov, double aspect) {
    const std::vector<Bounds3> frames = nonEmpty(extent.frames);
    if (!frames.empty()) return frameTheAction(frames, groundHeight, fov, aspect);
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

    const ViewAxes axes = viewAxes();
    const Vec3 toEye = axes.toEye, forward = axes.forward, side = axes.side, up = axes.up;
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


std::vector<ViewCamera> followTheAction(const SceneExtent& extent, double groundHeight,
                                        double fov, double aspect, int window) {
    const std::vector<Bounds3>& frames = extent.frames;
    const int n = int(frames.size());
    const ViewCamera still = autoFrame(extent, groundHeight, fov, aspect);
    window = std::max(window, 1);
    // Each frame framed on its neighbours in time.
    std::vector<ViewCamera> framed(std::size_t(n), still);
    std::vector<char> held(std::size_t(n), 0);
    for (int f = 0; f < n; ++f) {
        std::vector<Bounds3> near;
        for (int k = std::max(0, f - window); k <= std::min(n - 1, f + window); ++k) {
            if (!frames[std::size_t(k)].empty) near.push_back(frames[std::size_t(k)]);
        }
        if (near.empty()) continue;
        framed[std::size_t(f)] = frameTheAction(near, groundHeight, fov, aspect);
        held[std::size_t(f)] = 1;
    }
    // Then smoothed: a raised-cosine average of targets and log distances.
    const ViewAxes a = viewAxes();
    std::vector<ViewCamera> path(std::size_t(n), still);
    for (int f = 0; f < n; ++f) {
        double weights = 0, logDistance = 0;
        Vec3 target{0, 0, 0};
        for (int k = std::max(0, f - window); k <= std::min(n - 1, f + window); ++k) {
            if (!held[std::size_t(k)]) continue;
            const ViewCamera& c = framed[std::size_t(k)];
            const double w = 0.5 + 0.5 * std::cos(std::numbers::pi * (k - f) / (window + 1));
            weights += w;
            target = target + c.target * w;
            logDistance += w * std::log(length(c.position - c.target));
        }
        if (!(weights > 0)) continue;
        target = target * (1 / weights);
        path[std::size_t(f)] = {target + a.toEye * std::exp(logDistance / weights), target, fov};
    }
    return path;
}

}  // namespace globular
