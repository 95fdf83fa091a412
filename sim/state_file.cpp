#include "state_file.h"

#include <cstring>
#include <fstream>
#include <vector>

#include "atomic_file.h"
#include "errors.h"

namespace globular {

namespace {

constexpr char kMagic[8] = {'G', 'L', 'B', 'S', 'T', 'A', 'T', '1'};

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
    w.array(s.carried.x);
    w.array(s.carried.y);
    w.array(s.carried.z);
    writeFileAtomically(path, w.bytes());
}

Checkpoint readCheckpoint(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot open checkpoint " + path.string());
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Reader r(std::move(bytes), path);
    for (char ch : kMagic) {
        if (r.value<char>() != ch) r.fail("not a globular checkpoint");
    }
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
    s.carried.x = r.array<float>();
    s.carried.y = r.array<float>();
    s.carried.z = r.array<float>();
    for (const auto* a : {&g.py, &g.pz, &g.vx, &g.vy, &g.vz, &g.radius, &g.mass}) {
        if (a->size() != g.px.size()) r.fail("arrays of different lengths");
    }
    if (g.id.size() != g.px.size() || !r.atEnd()) r.fail("inconsistent sizes");
    return c;
}

}  // namespace globular
