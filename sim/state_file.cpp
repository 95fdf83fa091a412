#include "state_file.h"

#include <cmath>
#include <cstring>
#include <vector>

#include "atomic_file.h"
#include "errors.h"
#include "file_bytes.h"

namespace globular {

namespace {

// Version 4 adds the globules' temperatures and their heating rates; 3 added the dynamic
// colliders and the globules' materials; 2 ended with a checksum of everything before it,
// as 3 and 4 do; 1 had none.
constexpr char kMagic[8] = {'G', 'L', 'B', 'S', 'T', 'A', 'T', '4'};
constexpr char kOldMagics[3][8] = {{'G', 'L', 'B', 'S', 'T', 'A', 'T', '1'},
                                   {'G', 'L', 'B', 'S', 'T', 'A', 'T', '2'},
                                   {'G', 'L', 'B', 'S', 'T', 'A', 'T', '3'}};
/// A rigid body's state as doubles: position, orientation, velocity, angular momentum,
/// force, torque.
constexpr std::size_t kBodyDoubles = 19;
/// Checkpoints larger than this are refused before they are read.
constexpr uint64_t kMaxCheckpointBytes = uint64_t(16) << 30;

class Writer {
public:
    template <typename T>
    void value(const T& v) {
        const char* p = reinterpret_cast<const char*>(&v);
        mBytes.insert(mBytes.end(), p, p + sizeof(T));
    }
    template <typename T>
    void array(const std::vector<T>& v) {
        value(uint64_t(v.size()));
        const char* p = reinterpret_cast<const char*>(v.data());
        mBytes.insert(mBytes.end(), p, p + v.size() * sizeof(T));
    }
    std::string bytes() const { return {mBytes.begin(), mBytes.end()}; }

private:
    std::vector<char> mBytes;
};

class Reader {
public:
    Reader(std::string bytes, std::filesystem::path path)
        : mBytes(std::move(bytes)), mPath(std::move(path)) {}
    template <typename T>
    T value() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, mBytes.data() + mOffset, sizeof(T));
        mOffset += sizeof(T);
        return v;
    }
    template <typename T>
    std::vector<T> array() {
        const uint64_t n = value<uint64_t>();
        if (n > (mBytes.size() - mOffset) / sizeof(T)) fail("array longer than the file");
        std::vector<T> v(n);
        // An empty vector's data() may be null, and memcpy from or to null is undefined.
        if (n > 0) std::memcpy(v.data(), mBytes.data() + mOffset, n * sizeof(T));
        mOffset += n * sizeof(T);
        return v;
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw IoError("checkpoint " + mPath.string() + " is unreadable: " + why);
    }
    bool atEnd() const { return mOffset == mBytes.size(); }
    /// Drops the trailing checksum after checking it.
    void checkAndDropChecksum() {
        if (mBytes.size() < sizeof(kMagic) + sizeof(uint64_t)) fail("truncated");
        uint64_t stored;
        const std::size_t payload = mBytes.size() - sizeof stored;
        std::memcpy(&stored, mBytes.data() + payload, sizeof stored);
        mBytes.resize(payload);
        if (fingerprint(mBytes) != stored) fail("checksum mismatch (the file is damaged)");
    }

private:
    void need(std::size_t n) const {
        if (mBytes.size() - mOffset < n) fail("truncated");
    }
    std::string mBytes;
    std::filesystem::path mPath;
    std::size_t mOffset = 0;
};

}  // namespace

uint64_t fingerprint(const std::string& text) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    return h;
}

void writeCheckpoint(const std::filesystem::path& path, const Checkpoint& c) {
    Writer w;
    for (char ch : kMagic) w.value(ch);
    w.value(int32_t(c.frame));
    w.value(c.sceneFingerprint);
    const SimulationState& s = c.state;
    w.value(s.time);
    w.value(s.steps);
    w.value(s.nextId);
    std::vector<uint64_t> emitted(s.emitted.begin(), s.emitted.end());
    w.array(emitted);
    const Globules& g = s.globules;
    for (const auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        w.array(*a);
    }
    w.array(g.id);
    w.array(g.material);
    w.array(g.temperature);
    w.array(s.carried.x);
    w.array(s.carried.y);
    w.array(s.carried.z);
    w.array(s.carried.heat);
    std::vector<double> bodies;
    for (const RigidBodyState& b : s.bodies) {
        const Vec3 vectors[] = {b.position, b.velocity, b.angularMomentum, b.force, b.torque};
        for (const Vec3& v : vectors) bodies.insert(bodies.end(), {v.x, v.y, v.z});
        bodies.insert(bodies.end(), b.orientation.begin(), b.orientation.end());
    }
    w.array(bodies);
    std::string bytes = w.bytes();
    const uint64_t checksum = fingerprint(bytes);
    bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    writeFileAtomically(path, bytes);
}

namespace {

/// Every field within what a run can produce: a damaged or hand-edited checkpoint is
/// refused instead of resuming into nonsense or overwriting good frames.
void validate(const Checkpoint& c, Reader& r) {
    const SimulationState& s = c.state;
    const Globules& g = s.globules;
    if (c.frame < 1) r.fail("frame " + std::to_string(c.frame) + " is not a frame number");
    if (!std::isfinite(s.time) || s.time < 0) r.fail("time is not a finite number >= 0");
    if (s.steps < 0) r.fail("negative step count");
    if (s.nextId < 0 || std::size_t(s.nextId) != g.size()) {
        r.fail("next id " + std::to_string(s.nextId) + " does not match the " +
               std::to_string(g.size()) + " globules");
    }
    uint64_t emitted = 0;
    for (std::size_t e : s.emitted) {
        if (e > g.size() - emitted) r.fail("emitter counts add up to more than the globules");
        emitted += e;
    }
    if (emitted != g.size()) r.fail("emitter counts do not add up to the globule count");
    std::vector<bool> seen(g.size(), false);
    for (std::size_t i = 0; i < g.size(); ++i) {
        const float values[] = {g.px[i], g.py[i], g.pz[i], g.vx[i], g.vy[i], g.vz[i]};
        for (float v : values) {
            if (!std::isfinite(v)) r.fail("globule " + std::to_string(i) + " is not finite");
        }
        if (!(g.radius[i] > 0) || !std::isfinite(g.radius[i]) || !(g.mass[i] > 0) ||
            !std::isfinite(g.mass[i])) {
            r.fail("globule " + std::to_string(i) + " has a bad radius or mass");
        }
        if (g.id[i] < 0 || g.id[i] >= s.nextId || seen[std::size_t(g.id[i])]) {
            r.fail("globule " + std::to_string(i) + " has id " + std::to_string(g.id[i]) +
                   " (ids are 0 to " + std::to_string(s.nextId - 1) + ", each once)");
        }
        seen[std::size_t(g.id[i])] = true;
    }
    for (const auto* a : {&s.carried.x, &s.carried.y, &s.carried.z, &s.carried.heat}) {
        if (!a->empty() && a->size() != g.size()) r.fail("integrator state of the wrong size");
    }
    for (std::size_t i = 0; i < g.temperature.size(); ++i) {
        if (!std::isfinite(g.temperature[i])) {
            r.fail("globule " + std::to_string(i) + " has a non-finite temperature");
        }
    }
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        const RigidBodyState& body = s.bodies[b];
        const Vec3 vectors[] = {body.position, body.velocity, body.angularMomentum, body.force,
                                body.torque};
        double norm = 0;
        for (double q : body.orientation) norm += q * q;
        bool finite = std::isfinite(norm);
        for (const Vec3& v : vectors) finite = finite && std::isfinite(v.x + v.y + v.z);
        if (!finite || std::abs(norm - 1) > 1e-6) {
            r.fail("dynamic collider " + std::to_string(b) + " has a non-finite state or an "
                   "orientation that is not a unit quaternion");
        }
    }
}

}  // namespace

Checkpoint readCheckpoint(const std::filesystem::path& path) {
    std::string bytes;
    try {
        bytes = readFileBytes(path, kMaxCheckpointBytes);
    } catch (const std::exception& e) {
        throw IoError("cannot read checkpoint " + path.string() + ": " + e.what());
    }
    for (const char* old : kOldMagics) {
        if (bytes.compare(0, sizeof kMagic, old, sizeof kMagic) == 0) {
            throw IoError("checkpoint " + path.string() +
                          " was written by an older globular; run without --resume to start "
                          "over");
        }
    }
    Reader r(std::move(bytes), path);
    for (char ch : kMagic) {
        if (r.value<char>() != ch) r.fail("not a globular checkpoint");
    }
    r.checkAndDropChecksum();
    Checkpoint c;
    c.frame = r.value<int32_t>();
    c.sceneFingerprint = r.value<uint64_t>();
    SimulationState& s = c.state;
    s.time = r.value<double>();
    s.steps = r.value<int64_t>();
    s.nextId = r.value<int32_t>();
    for (uint64_t e : r.array<uint64_t>()) s.emitted.push_back(std::size_t(e));
    Globules& g = s.globules;
    for (auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        *a = r.array<float>();
    }
    g.id = r.array<int32_t>();
    g.material = r.array<uint8_t>();
    g.temperature = r.array<float>();
    s.carried.x = r.array<float>();
    s.carried.y = r.array<float>();
    s.carried.z = r.array<float>();
    s.carried.heat = r.array<float>();
    const std::vector<double> bodies = r.array<double>();
    if (bodies.size() % kBodyDoubles != 0) r.fail("a dynamic collider's state is cut short");
    for (std::size_t at = 0; at < bodies.size(); at += kBodyDoubles) {
        RigidBodyState b;
        const double* d = &bodies[at];
        for (Vec3* v : {&b.position, &b.velocity, &b.angularMomentum, &b.force, &b.torque}) {
            *v = {d[0], d[1], d[2]};
            d += 3;
        }
        for (double& q : b.orientation) q = *d++;
        s.bodies.push_back(b);
    }
    for (const auto* a : {&g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        if (a->size() != g.px.size()) r.fail("arrays of different lengths");
    }
    if (g.id.size() != g.px.size() || !r.atEnd() ||
        (!g.material.empty() && g.material.size() != g.px.size()) ||
        (!g.temperature.empty() && g.temperature.size() != g.px.size())) {
        r.fail("inconsistent sizes");
    }
    validate(c, r);
    return c;
}

}  // namespace globular
