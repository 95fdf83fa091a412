#include "scene_extent.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace globular {

namespace {

// Percentiles of more than this many values are estimated from an even subsample: the
// estimate is within a fraction of a percent, and a million-globule frame stays cheap.
constexpr std::size_t kMaxSamples = 200000;

/// The range of the finite values without their outliers: the extremes among the values
/// within kOutlierMargin of a span beyond the kOutlierFraction and 1 - kOutlierFraction
/// quantiles. The genuine extremes of a smooth distribution stay in; strays far away go.
bool robustRange(std::vector<float>& values, double& lo, double& hi) {
    std::erase_if(values, [](float v) { return !std::isfinite(v); });
    if (values.empty()) return false;
    const std::size_t n = values.size();
    const auto low = std::size_t(std::floor(kOutlierFraction * double(n - 1)));
    const auto high = n - 1 - low;
    std::nth_element(values.begin(), values.begin() + low, values.end());
    const double qLow = values[low];
    std::nth_element(values.begin(), values.begin() + high, values.end());
    const double qHigh = values[high];
    const double margin = kOutlierMargin * (qHigh - qLow);
    lo = qLow;
    hi = qHigh;
    for (float v : values) {
        if (v >= qLow - margin) lo = std::min(lo, double(v));
        if (v <= qHigh + margin) hi = std::max(hi, double(v));
    }
    return true;
}

std::vector<float> sampled(std::size_t n, const auto& valueAt) {
    const std::size_t stride = std::max<std::size_t>(1, (n + kMaxSamples - 1) / kMaxSamples);
    std::vector<float> out;
    out.reserve(n / stride + 1);
    for (std::size_t i = 0; i < n; i += stride) out.push_back(valueAt(i));
    return out;
}

bool inside(const Bounds3& box, Vec3 p) {
    return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x &&
           p.y <= box.max.y && p.z <= box.max.z;
}

/// Adds the points inside @p box that are extreme along x, y or z, and up to
/// kSamplesPerFrame more evenly spaced by index. When the samples outgrow
/// kMaxFramingSamples, every other one of the evenly spaced kind is dropped
/// (deterministic); the extremes stay, so the framing always reaches them.
void addSamples(std::vector<Vec3>& extremes, std::vector<Vec3>& spaced, std::size_t n,
                const Bounds3& box, const auto& pointAt) {
    std::array<std::size_t, 6> extreme;
    extreme.fill(n);
    std::array<double, 6> best{1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 p = pointAt(i);
        if (!inside(box, p)) continue;
        const double v[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
            if (v[a] < best[2 * a]) best[2 * a] = v[a], extreme[2 * a] = i;
            if (v[a] > best[2 * a + 1]) best[2 * a + 1] = v[a], extreme[2 * a + 1] = i;
        }
    }
    for (std::size_t i : extreme) {
        if (i < n) extremes.push_back(pointAt(i));
    }
    const std::size_t stride = std::max<std::size_t>(1, n / kSamplesPerFrame);
    for (std::size_t i = 0; i < n; i += stride) {
        const Vec3 p = pointAt(i);
        if (inside(box, p)) spaced.push_back(p);
    }
    while (spaced.size() > kMaxFramingSamples) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < spaced.size(); i += 2) spaced[kept++] = spaced[i];
        spaced.resize(kept);
    }
}

}  // namespace

void Bounds3::add(Vec3 p) {
    if (empty) {
        min = max = p;
        empty = false;
        return;
    }
    min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
}

void Bounds3::add(const Bounds3& other) {
    if (other.empty) return;
    add(other.min);
    add(other.max);
}

void ValueRange::add(double lo, double hi) {
    min = empty ? lo : std::min(min, lo);
    max = empty ? hi : std::max(max, hi);
    empty = false;
}

void SceneExtent::addFrame(const Globules& g) {
    const std::size_t n = g.size();
    if (n == 0) return;
    double lo[3], hi[3];
    const std::vector<float>* axes[3] = {&g.px, &g.py, &g.pz};
    for (int a = 0; a < 3; ++a) {
        std::vector<float> values = sampled(n, [&](std::size_t i) { return (*axes[a])[i]; });
        if (!robustRange(values, lo[a], hi[a])) return;  // no finite position at all
    }
    double radiusLo = 0, radiusHi = 0;
    if (g.radius.size() == n) {
        std::vector<float> radii = sampled(n, [&](std::size_t i) { return std::abs(g.radius[i]); });
        robustRange(radii, radiusLo, radiusHi);
    }
    const Vec3 grow{radiusHi, radiusHi, radiusHi};
    Bounds3 frameBox;
    frameBox.add(Vec3{lo[0], lo[1], lo[2]});
    frameBox.add(Vec3{hi[0], hi[1], hi[2]});
    addSamples(extremes, samples, n, frameBox, [&](std::size_t i) { return g.position(i); });
    maxRadius = std::max(maxRadius, radiusHi);
    box.add(frameBox.min - grow);
    box.add(frameBox.max + grow);
    currentFrame.add(frameBox.min - grow);
    currentFrame.add(frameBox.max + grow);
    height.add(lo[1], hi[1]);

    if (g.vx.size() != n || g.vy.size() != n || g.vz.size() != n) return;
    std::vector<float> speeds = sampled(n, [&](std::size_t i) {
        return std::sqrt(g.vx[i] * g.vx[i] + g.vy[i] * g.vy[i] + g.vz[i] * g.vz[i]);
    });
    double speedLo = 0, speedHi = 0;
    if (robustRange(speeds, speedLo, speedHi)) speed.add(speedLo, speedHi);
}

void SceneExtent::addPoints(const float* positions, std::size_t vertexCount) {
    if (vertexCount == 0) return;
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        std::vector<float> values =
            sampled(vertexCount, [&](std::size_t i) { return positions[3 * i + a]; });
        if (!robustRange(values, lo[a], hi[a])) return;
    }
    Bounds3 frameBox;
    frameBox.add(Vec3{lo[0], lo[1], lo[2]});
    frameBox.add(Vec3{hi[0], hi[1], hi[2]});
    addSamples(extremes, samples, vertexCount, frameBox, [&](std::size_t i) {
        return Vec3{positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    });
    box.add(frameBox);
    currentFrame.add(frameBox);
    height.add(lo[1], hi[1]);
}

void SceneExtent::endFrame() {
    frames.push_back(currentFrame);
    currentFrame = {};
}

}  // namespace globular
