#include "sub_frames.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "transform.h"

namespace globular {

std::vector<SubFrame> subFrames(const RenderSettings& r, double frameSeconds) {
    const bool moving = r.motionBlur && r.shutter > 0 && frameSeconds > 0;
    const bool lens = r.aperture > 0;
    const int count = moving || lens ? int(std::max<int64_t>(r.motionSamples, 1)) : 1;
    std::vector<SubFrame> subs(count);
    // The golden angle spreads consecutive lens points around the disc; the radius's
    // square root makes equal areas equally likely.
    const double goldenAngle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    // The sub-frame nearest the frame's instant looks through the lens's centre: the
    // passes come from it.
    const int middle = (count - 1) / 2;
    for (int k = 0; k < count; ++k) {
        SubFrame& s = subs[k];
        if (moving) s.seconds = ((k + 0.5) / count - 0.5) * r.shutter * frameSeconds;
        if (lens && count > 1) {
            // The lens points are visited in an order unrelated to time (a stride coprime
            // with the count), so a moving sphere's path is not drawn as a spiral.
            int stride = 5;
            while (std::gcd(stride, count) != 1) stride += 2;
            const int j = int(((std::int64_t(k) - middle + count) * stride) % count);
            // r^2 evenly spaced from 0 to 1: the second moment of a uniform disc, R^2 / 2.
            const double radius = r.aperture * std::sqrt(double(j) / (count - 1));
            const double angle = j * goldenAngle;
            s.lensX = radius * std::cos(angle);
            s.lensY = radius * std::sin(angle);
        }
    }
    auto offCentre = [&](const SubFrame& s) {
        return std::abs(s.seconds) / std::max(frameSeconds, 1e-30) +
               std::hypot(s.lensX, s.lensY) / std::max(r.aperture, 1e-30);
    };
    auto first = std::min_element(subs.begin(), subs.end(), [&](const SubFrame& a, const SubFrame& b) {
        return offCentre(a) < offCentre(b);
    });
    std::iter_swap(subs.begin(), first);
    return subs;
}

ViewCamera throughLens(const ViewCamera& camera, const SubFrame& sub) {
    if (sub.lensX == 0 && sub.lensY == 0) return camera;
    const Mat4 view = lookAt(camera.position, camera.target);  // rows: right, up, backwards
    const Vec3 offset = Vec3{view(0, 0), view(0, 1), view(0, 2)} * sub.lensX +
                        Vec3{view(1, 0), view(1, 1), view(1, 2)} * sub.lensY;
    return {camera.position + offset, camera.target + offset, camera.fov};
}

PixelShift lensShift(const ViewCamera& camera, const SubFrame& sub, const RenderSettings& r,
                     double focalPixelsX, double focalPixelsY) {
    const double focus =
        r.focusDistance > 0 ? r.focusDistance : length(camera.target - camera.position);
    return {sub.lensX * focalPixelsX / focus, sub.lensY * focalPixelsY / focus};
}

void addShifted(std::vector<float>& sum, const LinearFrame& frame, PixelShift shift) {
    // Output pixel (x, y) reads the frame at (x - shift.x, y + shift.y): rows run down.
    const int w = frame.width, h = frame.height;
    const double sx = -shift.x, sy = shift.y;
    const int ix = int(std::floor(sx)), iy = int(std::floor(sy));
    const float fx = float(sx - ix), fy = float(sy - iy);
    auto at = [&](int x, int y, int c) {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        return frame.rgba[(std::size_t(y) * w + x) * 4 + c];
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            float* out = &sum[(std::size_t(y) * w + x) * 4];
            for (int c = 0; c < 4; ++c) {
                const float top = (1 - fx) * at(x + ix, y + iy, c) + fx * at(x + ix + 1, y + iy, c);
                const float bottom =
                    (1 - fx) * at(x + ix, y + iy + 1, c) + fx * at(x + ix + 1, y + iy + 1, c);
                out[c] += (1 - fy) * top + fy * bottom;
            }
        }
    }
}

Globules movedBy(const Globules& globules, double seconds) {
    Globules moved = globules;
    const float t = float(seconds);
    for (std::size_t i = 0; i < moved.size(); ++i) {
        moved.px[i] += moved.vx[i] * t;
        moved.py[i] += moved.vy[i] * t;
        moved.pz[i] += moved.vz[i] * t;
    }
    return moved;
}

MeshView movedBy(const MeshView& mesh, double seconds, std::vector<float>& storage) {
    if (seconds == 0 || !mesh.vx || !mesh.vy || !mesh.vz) return mesh;
    storage.assign(mesh.positions, mesh.positions + 3 * mesh.vertexCount);
    const float t = float(seconds);
    for (std::size_t v = 0; v < mesh.vertexCount; ++v) {
        storage[3 * v] += mesh.vx[v] * t;
        storage[3 * v + 1] += mesh.vy[v] * t;
        storage[3 * v + 2] += mesh.vz[v] * t;
    }
    MeshView moved = mesh;
    moved.positions = storage.data();
    return moved;
}

}  // namespace globular
