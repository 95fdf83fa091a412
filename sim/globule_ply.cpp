// The PLY half of globule_cache.h. It lives apart from globule_cache.cpp so that this
// small parser stays out of the OpenVDB translation unit (a minute to compile, STYLE.md
// 12) and both files stay short.

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <string>
#include <string_view>

#include "atomic_file.h"
#include "errors.h"
#include "globule_cache.h"
#include "file_bytes.h"
#include "ply_reader.h"
#include "ply_writer.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

void checkArraySizes(const fs::path& path, const Globules& g) {
    if (!g.consistent()) {
        throw IoError("cannot write " + path.string() + ": globule arrays differ in size");
    }
}

static_assert(std::endian::native == std::endian::little,
              "binary PLY output assumes a little-endian host");

/// Clouds larger than this are refused before they are read.
constexpr uint64_t kMaxPlyBytes = uint64_t(16) << 30;

enum class Slot { X, Y, Z, Vx, Vy, Vz, Radius, Temperature, Mass, Id, Ignored };

Slot slotOf(const PlyProperty& p) {
    if (p.isList()) return Slot::Ignored;
    static const std::pair<std::string_view, Slot> kNames[] = {
        {"x", Slot::X},           {"y", Slot::Y},           {"z", Slot::Z},
        {"vx", Slot::Vx},         {"vy", Slot::Vy},         {"vz", Slot::Vz},
        {"radius", Slot::Radius}, {"pscale", Slot::Radius}, {"id", Slot::Id},
        {"temperature", Slot::Temperature}, {"mass", Slot::Mass}};
    for (const auto& [n, s] : kNames) {
        if (n == p.name) return s;
    }
    return Slot::Ignored;
}

/// A globule's value that no simulation can start from: a non-finite position or
/// velocity, a radius that is not a positive finite number.
void checkGlobule(const Globules& g, std::size_t i, int line) {
    const auto where = [&] {
        return "vertex " + std::to_string(i) + (line > 0 ? " (line " + std::to_string(line) + ")" : "");
    };
    if (!std::isfinite(g.px[i]) || !std::isfinite(g.py[i]) || !std::isfinite(g.pz[i])) {
        throw std::runtime_error(where() + " has a non-finite position");
    }
    if (!std::isfinite(g.vx[i]) || !std::isfinite(g.vy[i]) || !std::isfinite(g.vz[i])) {
        throw std::runtime_error(where() + " has a non-finite velocity");
    }
    if (!(g.radius[i] > 0) || !std::isfinite(g.radius[i])) {
        throw std::runtime_error(where() + " has radius " + std::to_string(g.radius[i]) +
                                 ": a radius must be a positive finite number");
    }
    if (!g.temperature.empty() && !std::isfinite(g.temperature[i])) {
        throw std::runtime_error(where() + " has a non-finite temperature");
    }
    if (!(g.mass[i] > 0) || !std::isfinite(g.mass[i])) {
        throw std::runtime_error(where() + " has mass " + std::to_string(g.mass[i]) +
                                 ": a mass must be a positive finite number");
    }
}

Globules readVertices(const PlyElement& e, PlyCursor& in, float defaultRadius, bool ascii) {
    std::vector<Slot> slots;
    for (const auto& p : e.properties) slots.push_back(slotOf(p));
    for (Slot required : {Slot::X, Slot::Y, Slot::Z}) {
        if (std::find(slots.begin(), slots.end(), required) == slots.end()) {
            throw std::runtime_error("vertex element lacks property x, y or z");
        }
    }
    // A lying header must not make us allocate: every vertex occupies some bytes.
    in.checkFits(e);
    const std::size_t n = e.count;
    Globules g;
    for (auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz}) a->assign(n, 0.0f);
    g.radius.assign(n, defaultRadius);
    g.mass.assign(n, 1.0f);
    g.id.resize(n);
    std::iota(g.id.begin(), g.id.end(), 0);
    if (std::find(slots.begin(), slots.end(), Slot::Temperature) != slots.end()) {
        g.temperature.assign(n, 0.0f);
    }
    float* const targets[] = {g.px.data(), g.py.data(), g.pz.data(),     g.vx.data(),
                              g.vy.data(), g.vz.data(), g.radius.data(), g.temperature.data(),
                              g.mass.data()};
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const PlyProperty& p = e.properties[k];
            if (p.isList()) {
                in.skip(p);
                continue;
            }
            const double v = in.read(p.type);
            if (slots[k] == Slot::Id) {
                if (!(v >= std::numeric_limits<int32_t>::min() &&
                      v <= std::numeric_limits<int32_t>::max()) ||
                    v != std::floor(v)) {
                    throw std::runtime_error("vertex " + std::to_string(i) + " has bad id " +
                                             std::to_string(v));
                }
                g.id[i] = int32_t(v);
            } else if (slots[k] != Slot::Ignored) {
                targets[int(slots[k])][i] = float(v);
            }
        }
        checkGlobule(g, i, ascii ? in.line() : 0);
    }
    return g;
}

}  // namespace

void writeGlobulePly(const fs::path& path, const Globules& globules) {
    checkArraySizes(path, globules);
    const Globules& g = globules;
    PlyElement vertex{"vertex", g.size(), {}};
    for (const char* name : {"x", "y", "z", "vx", "vy", "vz", "radius"}) {
        vertex.properties.push_back({name, PlyType::Float32});
    }
    vertex.properties.push_back({"id", PlyType::Int32});
    vertex.properties.push_back({"mass", PlyType::Float32});
    vertex.properties.push_back({"material", PlyType::Int32});
    const bool hasTemperature = !g.temperature.empty();
    if (hasTemperature) vertex.properties.push_back({"temperature", PlyType::Float32});
    const std::string header = plyHeader("globular globule cache", {vertex});
    // x y z vx vy vz radius | id | mass | material | temperature
    const std::size_t rowSize = 8 * sizeof(float) + 2 * sizeof(int32_t) +
                                 (hasTemperature ? sizeof(float) : 0);
    constexpr std::size_t kChunk = 1 << 14;  // rows per write
    writeAtomically(path, [&](const fs::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw std::runtime_error(std::strerror(errno));
        out.write(header.data(), std::streamsize(header.size()));
        std::vector<char> buffer(kChunk * rowSize);
        for (std::size_t begin = 0; begin < g.size(); begin += kChunk) {
            const std::size_t end = std::min(g.size(), begin + kChunk);
            char* p = buffer.data();
            for (std::size_t i = begin; i < end; ++i, p += rowSize) {
                const float row[7] = {g.px[i], g.py[i], g.pz[i],    g.vx[i],
                                      g.vy[i], g.vz[i], g.radius[i]};
                std::memcpy(p, row, sizeof row);
                const int32_t material = g.materialOf(i);
                if (!(g.mass[i] > 0) || !std::isfinite(g.mass[i])) {
                    throw std::runtime_error("globule " + std::to_string(g.id[i]) +
                                             " has mass " + std::to_string(g.mass[i]) +
                                             ", not a positive finite number");
                }
                char* q = p + sizeof row;
                std::memcpy(q, &g.id[i], sizeof(int32_t));
                std::memcpy(q += sizeof(int32_t), &g.mass[i], sizeof(float));
                std::memcpy(q += sizeof(float), &material, sizeof(int32_t));
                if (hasTemperature) {
                    if (!std::isfinite(g.temperature[i])) {
                        throw std::runtime_error("globule " + std::to_string(g.id[i]) +
                                                 " has a non-finite temperature");
                    }
                    std::memcpy(q + sizeof(int32_t), &g.temperature[i], sizeof(float));
                }
            }
            out.write(buffer.data(), p - buffer.data());
        }
        out.flush();
        if (!out) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
    });
}

Globules readGlobulePly(const fs::path& path, float defaultRadius) {
    try {
        const std::string data = readFileBytes(path, kMaxPlyBytes);
        const PlyHeader header = parsePlyHeader(data);
        PlyCursor in(data, header);
        for (const auto& e : header.elements) {
            if (e.name == "vertex") {
                return readVertices(e, in, defaultRadius, header.format == PlyFormat::Ascii);
            }
            in.skip(e);
        }
        throw std::runtime_error("no vertex element");
    } catch (const std::exception& e) {
        throw IoError("cannot read " + path.string() + ": " + e.what());
    }
}

}  // namespace globular
