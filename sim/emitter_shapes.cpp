// The four emitter kinds of emitter.h and their factory.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "emitter.h"
#include "errors.h"
#include "globule_cache.h"

namespace globular {

namespace {

/// Emitters whose globules all exist at t = 0: a precomputed list added on first call,
/// then freed (it would double the memory of a large initial block).
class InitialEmitter : public Emitter {
public:
    InitialEmitter(const EmitterSettings& s, std::vector<Vec3> positions,
                   std::vector<Vec3> velocities = {}, std::vector<float> radii = {})
        : mSettings(s),
          mTotal(positions.size()),
          mPositions(std::move(positions)),
          mVelocities(std::move(velocities)),
          mRadii(std::move(radii)) {}

    void emit(double, Globules& g, int32_t& nextId) override {
        if (mDone) return;
        mDone = true;
        for (std::size_t k = 0; k < mPositions.size(); ++k) {
            const Vec3 v = mSettings.velocity + (mVelocities.empty() ? Vec3{} : mVelocities[k]);
            const float r = mRadii.empty() ? float(mSettings.radius) : mRadii[k];
            g.add(mPositions[k], v, r, float(mSettings.mass), nextId++);
        }
        release();
    }
    std::size_t total() const override { return mTotal; }
    std::size_t emitted() const override { return mDone ? mTotal : 0; }
    void skipTo(std::size_t count) override {
        mDone = count > 0;
        if (mDone) release();
    }

private:
    void release() {
        std::vector<Vec3>().swap(mPositions);
        std::vector<Vec3>().swap(mVelocities);
        std::vector<float>().swap(mRadii);
    }

    EmitterSettings mSettings;
    std::size_t mTotal;
    std::vector<Vec3> mPositions, mVelocities;
    std::vector<float> mRadii;
    bool mDone = false;
};

/// Fig. 3: index i belongs to group i % 4 at height step k = i / 4; the groups spiral
/// around one circle a quarter turn apart and start on the same plane.
std::vector<Vec3> helixPositions(const EmitterSettings& s, Jitter& jitter) {
    std::vector<Vec3> out;
    for (int64_t i = 0; i < s.count; ++i) {
        const int64_t group = i % 4, k = i / 4;
        const double angle = double(k) * s.turn + double(group) * std::numbers::pi / 2;
        const double jx = s.jitter * jitter.next(), jz = s.jitter * jitter.next();
        out.push_back({s.center.x + s.helixRadius * std::cos(angle) + jx,
                       s.center.y + double(k) * s.spacing,
                       s.center.z + s.helixRadius * std::sin(angle) + jz});
    }
    return out;
}

std::vector<Vec3> boxPositions(const EmitterSettings& s, Jitter& jitter) {
    const Vec3 extent = s.max - s.min;
    // Count in floating point first: a huge box at a small spacing must be refused, not
    // overflow an integer.
    const auto cells = [&](double e) { return std::floor(e / s.spacing); };
    const double lattice = cells(extent.x) * cells(extent.y) * cells(extent.z);
    if (s.count == 0 && !(lattice <= double(kMaxEmitterGlobules))) {  // NaN: inf * 0
        throw ResourceError("box emitter: filling the box at spacing " +
                            std::to_string(s.spacing) + " would make " +
                            std::to_string(lattice) + " globules, more than the limit of " +
                            std::to_string(kMaxEmitterGlobules) + "; set count or a larger spacing");
    }
    const int64_t nx = int64_t(std::min(cells(extent.x), 1e9)),
                  ny = int64_t(std::min(cells(extent.y), 1e9)),
                  nz = int64_t(std::min(cells(extent.z), 1e9));
    const double capacity = lattice;
    if (capacity == 0) throw SceneError("box emitter: the box is smaller than one spacing");
    if (double(s.count) > capacity) {
        throw SceneError("box emitter: count " + std::to_string(s.count) +
                         " exceeds the " + std::to_string(int64_t(capacity)) +
                         " lattice points the box holds at spacing " +
                         std::to_string(s.spacing));
    }
    const int64_t wanted = s.count > 0 ? s.count : int64_t(capacity);
    std::vector<Vec3> out;
    out.reserve(std::size_t(wanted));
    // Fill bottom-up so a partial box is a settled-looking layer, not a slab on one side.
    for (int64_t y = 0; y < ny && int64_t(out.size()) < wanted; ++y)
        for (int64_t z = 0; z < nz && int64_t(out.size()) < wanted; ++z)
            for (int64_t x = 0; x < nx && int64_t(out.size()) < wanted; ++x) {
                const Vec3 cell{(double(x) + 0.5) * s.spacing, (double(y) + 0.5) * s.spacing,
                                (double(z) + 0.5) * s.spacing};
                const Vec3 j{jitter.next(), jitter.next(), jitter.next()};
                out.push_back(s.min + cell + s.jitter * j);
            }
    return out;
}

/// A continuous pour: layers of globules on a hexagonal pattern across the nozzle, one
/// layer every `spacing / speed` seconds at most, so globules never start overlapping.
class SpoutEmitter final : public Emitter {
public:
    SpoutEmitter(const EmitterSettings& s, uint64_t seed) : mSettings(s), mJitter(seed) {
        mDirection = normalized(s.direction);
        const Vec3 helper = std::abs(mDirection.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
        mU = normalized(cross(mDirection, helper));
        mW = cross(mDirection, mU);
        const double row = s.spacing * std::sqrt(3.0) / 2;
        // A layer holds about 3.6 (nozzle_radius / spacing)^2 globules: refuse one no run
        // could hold before looping over it (its bounds would overflow an int).
        const double perLayer = 3.63 * (s.nozzleRadius / s.spacing) * (s.nozzleRadius / s.spacing);
        if (!(perLayer <= double(kMaxEmitterGlobules))) {
            throw SceneError("spout emitter: nozzle_radius " + std::to_string(s.nozzleRadius) +
                             " at spacing " + std::to_string(s.spacing) + " makes layers of " +
                             std::to_string(perLayer) + " globules, more than the limit of " +
                             std::to_string(kMaxEmitterGlobules));
        }
        for (int j = -int(s.nozzleRadius / row) - 1; j <= int(s.nozzleRadius / row) + 1; ++j) {
            for (int i = -int(s.nozzleRadius / s.spacing) - 2;
                 i <= int(s.nozzleRadius / s.spacing) + 2; ++i) {
                const double a = (i + 0.5 * (j & 1)) * s.spacing, b = j * row;
                if (a * a + b * b <= s.nozzleRadius * s.nozzleRadius + 1e-9) {
                    mPattern.push_back({a, b});
                }
            }
        }
        mInterval = s.rate > 0 ? double(mPattern.size()) / s.rate : s.spacing / s.speed;
        if (s.speed * mInterval < 0.9 * s.spacing) {
            throw SceneError(
                "spout emitter: rate " + std::to_string(s.rate) + " /s at speed " +
                std::to_string(s.speed) + " would start layers " +
                std::to_string(s.speed * mInterval) + " apart, closer than spacing " +
                std::to_string(s.spacing) + "; lower rate or raise speed or nozzle_radius (at most " +
                std::to_string(s.speed * double(mPattern.size()) / (0.9 * s.spacing)) + " /s)");
        }
    }

    void emit(double time, Globules& g, int32_t& nextId) override {
        while (mEmitted < std::size_t(mSettings.count)) {
            const double layerTime = mSettings.start + double(mLayer) * mInterval;
            if (layerTime > time + 1e-12) break;
            const Vec3 velocity = mSettings.speed * mDirection;
            const Vec3 base = mSettings.center + (time - layerTime) * velocity;
            for (const auto& [a, b] : mPattern) {
                if (mEmitted == std::size_t(mSettings.count)) break;
                const Vec3 j{mJitter.next(), mJitter.next(), mJitter.next()};
                g.add(base + a * mU + b * mW + mSettings.jitter * j, velocity,
                      float(mSettings.radius), float(mSettings.mass), nextId++);
                ++mEmitted;
            }
            ++mLayer;
        }
    }
    std::size_t total() const override { return std::size_t(mSettings.count); }
    std::size_t emitted() const override { return mEmitted; }
    void skipTo(std::size_t count) override {
        // Layers are emitted whole (but the last), three jitter draws per globule. The
        // generator is a counter modulo 2^64, so a backward skip wraps correctly too.
        mJitter.skip(3 * (uint64_t(count) - uint64_t(mEmitted)));
        mEmitted = count;
        mLayer = (count + mPattern.size() - 1) / mPattern.size();
    }

private:
    EmitterSettings mSettings;
    Jitter mJitter;
    Vec3 mDirection, mU, mW;
    std::vector<std::pair<double, double>> mPattern;
    double mInterval = 0;
    std::size_t mEmitted = 0, mLayer = 0;
};

std::unique_ptr<Emitter> pointsEmitter(const EmitterSettings& s,
                                       const std::filesystem::path& sceneDir) {
    const std::filesystem::path path = sceneDir / s.file;
    const Globules cloud = readGlobulePly(path, float(s.radius));
    std::vector<Vec3> positions, velocities;
    std::vector<float> radii(cloud.radius.begin(), cloud.radius.end());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        positions.push_back(cloud.position(i) + s.offset);
        velocities.push_back(cloud.velocity(i));
    }
    return std::make_unique<InitialEmitter>(s, std::move(positions), std::move(velocities),
                                            std::move(radii));
}

}  // namespace

std::size_t plannedGlobules(const EmitterSettings& s) {
    if (s.type == "points") return 0;
    if (s.type == "box" && s.count == 0) {
        const Vec3 extent = s.max - s.min;
        const auto cells = [&](double e) { return std::floor(e / s.spacing); };
        const double lattice = cells(extent.x) * cells(extent.y) * cells(extent.z);
        if (!(lattice >= 0)) return 0;  // NaN: the emitter refuses it when made
        return lattice >= double(SIZE_MAX) ? SIZE_MAX : std::size_t(lattice);
    }
    return std::size_t(std::max<int64_t>(0, s.count));
}

std::unique_ptr<Emitter> makeEmitter(const EmitterSettings& s, uint64_t seed, std::size_t index,
                                     const std::filesystem::path& sceneDir) {
    Jitter jitter(seed * 0x9e3779b97f4a7c15ull + index);
    if (s.type == "helix") {
        return std::make_unique<InitialEmitter>(s, helixPositions(s, jitter));
    }
    if (s.type == "box") return std::make_unique<InitialEmitter>(s, boxPositions(s, jitter));
    if (s.type == "spout") {
        return std::make_unique<SpoutEmitter>(s, seed * 0x9e3779b97f4a7c15ull + index);
    }
    if (s.type == "points") return pointsEmitter(s, sceneDir);
    throw SceneError("unknown emitter type '" + s.type + "'");
}

}  // namespace globular
