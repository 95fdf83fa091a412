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
#include "ply_types.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

void checkArraySizes(const fs::path& path, const Globules& g) {
    if (!g.consistent()) {
        throw IoError("cannot write " + path.string() + ": globule arrays differ in size");
    }
}

static_assert(std::endian::native == std::endian::little,
              "binary PLY input and output assume a little-endian host");

template <typename T>
double loadAs(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return double(v);
}

double loadBinary(const char* p, PlyType t) {
    switch (t) {
        case PlyType::Int8:
            return loadAs<int8_t>(p);
        case PlyType::UInt8:
            return loadAs<uint8_t>(p);
        case PlyType::Int16:
            return loadAs<int16_t>(p);
        case PlyType::UInt16:
            return loadAs<uint16_t>(p);
        case PlyType::Int32:
            return loadAs<int32_t>(p);
        case PlyType::UInt32:
            return loadAs<uint32_t>(p);
        case PlyType::Float32:
            return loadAs<float>(p);
        case PlyType::Float64:
            return loadAs<double>(p);
        case PlyType::None:
            break;
    }
    return 0;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;
    bool isList = false;
    PlyType countType = PlyType::UInt8;  ///< list properties only
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    bool ascii = false;
    std::vector<PlyElement> elements;
    std::size_t dataOffset = 0;  ///< bytes
    int lineCount = 0;           ///< lines of the header, for ascii data line numbers
};

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i) words.push_back(line.substr(i, j - i));
        i = j;
    }
    return words;
}

/// @brief Parses the header; @throw std::runtime_error naming the header line.
PlyHeader parsePlyHeader(const std::string& data) {
    PlyHeader header;
    std::size_t pos = 0;
    int lineNo = 0;
    bool hasFormat = false;
    const auto fail = [&](const std::string& what) {
        return std::runtime_error("header line " + std::to_string(lineNo) + ": " + what);
    };
    while (pos < data.size()) {
        std::size_t end = data.find('\n', pos);
        if (end == std::string::npos) end = data.size();
        std::string_view line(data.data() + pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = std::min(end + 1, data.size());
        ++lineNo;
        const auto words = splitWords(line);
        if (lineNo == 1) {
            if (line != "ply") throw std::runtime_error("not a PLY file (no 'ply' magic line)");
            continue;
        }
        if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
        if (words[0] == "end_header") {
            if (!hasFormat) throw fail("end_header before any format line");
            header.dataOffset = pos;
            header.lineCount = lineNo;
            return header;
        }
        if (words[0] == "format") {
            if (words.size() < 2) throw fail("format line without a format");
            if (words[1] == "ascii") {
                header.ascii = true;
            } else if (words[1] != "binary_little_endian") {
                throw fail("unsupported format '" + std::string(words[1]) + "'");
            }
            hasFormat = true;
        } else if (words[0] == "element") {
            uint64_t count = 0;
            const auto last = words.size() == 3 ? words[2].data() + words[2].size() : nullptr;
            if (!last || std::from_chars(words[2].data(), last, count).ptr != last) {
                throw fail("expected 'element NAME COUNT', got '" + std::string(line) + "'");
            }
            header.elements.push_back({std::string(words[1]), count, {}});
        } else if (words[0] == "property") {
            if (header.elements.empty()) throw fail("property before any element");
            PlyProperty property;
            const bool isList = words.size() == 5 && words[1] == "list";
            if (!isList && words.size() != 3) throw fail("malformed property line");
            const auto type = plyTypeNamed(words[isList ? 3 : 1]);
            const auto countType = isList ? plyTypeNamed(words[2]) : type;
            if (type == PlyType::None || countType == PlyType::None) {
                throw fail("unknown property type in '" + std::string(line) + "'");
            }
            header.elements.back().properties.push_back(
                {std::string(words.back()), type, isList, countType});
        } else {
            throw fail("unexpected '" + std::string(line.substr(0, 80)) + "'");
        }
    }
    throw std::runtime_error("header has no end_header line");
}

/// Reads values of binary little-endian PLY data, refusing to run past the end.
struct BinaryCursor {
    const std::string& data;
    std::size_t pos;

    std::size_t remaining() const { return data.size() - pos; }
    double read(PlyType t) {
        const std::size_t n = plyTypeSize(t);
        if (remaining() < n) throw std::runtime_error("data is truncated");
        const double v = loadBinary(data.data() + pos, t);
        pos += n;
        return v;
    }
    /// Fewest bytes a row of @p e occupies.
    static std::size_t minRowSize(const PlyElement& e) {
        std::size_t n = 0;
        for (const auto& p : e.properties) n += plyTypeSize(p.isList ? p.countType : p.type);
        return n;
    }
};

/// Reads whitespace-separated values of ascii PLY data, counting lines for messages.
struct AsciiCursor {
    const std::string& data;
    std::size_t pos;
    int line;

    std::size_t remaining() const { return data.size() - pos; }
    double read(PlyType) {
        while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) {
            if (data[pos++] == '\n') ++line;
        }
        if (pos == data.size()) throw std::runtime_error("data ends early (truncated file)");
        const char* begin = data.data() + pos;
        std::size_t end = pos;
        while (end < data.size() && !std::isspace(static_cast<unsigned char>(data[end]))) ++end;
        const char* last = data.data() + end;
        double v = 0;
        if (*begin == '+') ++begin;  // from_chars rejects a leading '+'
        const auto [ptr, ec] = std::from_chars(begin, last, v);
        if (ptr != last || ec != std::errc()) {  // out of range (1e999) is an error too
            throw std::runtime_error("line " + std::to_string(line) + ": bad number '" +
                                     std::string(data.data() + pos, last).substr(0, 40) + "'");
        }
        pos = end;
        return v;
    }
    /// Fewest bytes a row of @p e occupies: one character and one separator per value.
    static std::size_t minRowSize(const PlyElement& e) { return 2 * e.properties.size(); }
};

std::size_t listLength(double count) {
    // Bounded before the conversion (1e300 would overflow it): no PLY count type goes
    // past 2^32 - 1.
    if (!(count >= 0) || count != std::floor(count) || count > 4294967295.0) {
        throw std::runtime_error("bad list length " + std::to_string(count));
    }
    return std::size_t(count);
}

template <typename Cursor>
void skipElement(const PlyElement& e, Cursor& in) {
    if (e.properties.empty()) return;
    for (uint64_t row = 0; row < e.count; ++row) {
        for (const auto& p : e.properties) {
            const std::size_t n = p.isList ? listLength(in.read(p.countType)) : 1;
            for (std::size_t k = 0; k < n; ++k) in.read(p.type);
        }
    }
}

enum class Slot { X, Y, Z, Vx, Vy, Vz, Radius, Id, Ignored };

Slot slotOf(const PlyProperty& p) {
    if (p.isList) return Slot::Ignored;
    static const std::pair<std::string_view, Slot> kNames[] = {
        {"x", Slot::X},           {"y", Slot::Y},           {"z", Slot::Z},
        {"vx", Slot::Vx},         {"vy", Slot::Vy},         {"vz", Slot::Vz},
        {"radius", Slot::Radius}, {"pscale", Slot::Radius}, {"id", Slot::Id}};
    for (const auto& [n, s] : kNames) {
        if (n == p.name) return s;
    }
    return Slot::Ignored;
}

template <typename Cursor>
Globules readVertices(const PlyElement& e, Cursor& in, float defaultRadius) {
    std::vector<Slot> slots;
    for (const auto& p : e.properties) slots.push_back(slotOf(p));
    for (Slot required : {Slot::X, Slot::Y, Slot::Z}) {
        if (std::find(slots.begin(), slots.end(), required) == slots.end()) {
            throw std::runtime_error("vertex element lacks property x, y or z");
        }
    }
    // A lying header must not make us allocate: every vertex occupies some bytes.
    const std::size_t minRow = Cursor::minRowSize(e);
    if (e.count > (in.remaining() + 1) / minRow) {
        throw std::runtime_error("header declares " + std::to_string(e.count) +
                                 " vertices but only " + std::to_string(in.remaining()) +
                                 " bytes of data follow (truncated file?)");
    }
    const std::size_t n = e.count;
    Globules g;
    for (auto* a : {&g.px, &g.py, &g.pz, &g.vx, &g.vy, &g.vz}) a->assign(n, 0.0f);
    g.radius.assign(n, defaultRadius);
    g.mass.assign(n, 1.0f);
    g.id.resize(n);
    std::iota(g.id.begin(), g.id.end(), 0);
    float* const targets[] = {g.px.data(), g.py.data(), g.pz.data(),    g.vx.data(),
                              g.vy.data(), g.vz.data(), g.radius.data()};
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const PlyProperty& p = e.properties[k];
            if (p.isList) {
                const std::size_t len = listLength(in.read(p.countType));
                for (std::size_t m = 0; m < len; ++m) in.read(p.type);
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
    }
    return g;
}

template <typename Cursor>
Globules readPlyData(const PlyHeader& header, Cursor& in, float defaultRadius) {
    for (const auto& e : header.elements) {
        if (e.name == "vertex") return readVertices(e, in, defaultRadius);
        skipElement(e, in);
    }
    throw std::runtime_error("no vertex element");
}

std::string readWholeFile(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw std::runtime_error("no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(std::strerror(errno));
    std::string data(fs::file_size(path), '\0');
    in.read(data.data(), std::streamsize(data.size()));
    if (std::size_t(in.gcount()) != data.size()) throw std::runtime_error("read failed");
    return data;
}

}  // namespace

void writeGlobulePly(const fs::path& path, const Globules& globules) {
    checkArraySizes(path, globules);
    const Globules& g = globules;
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment globular globule cache\n"
        "element vertex " +
        std::to_string(g.size()) +
        "\nproperty float x\nproperty float y\nproperty float z\n"
        "property float vx\nproperty float vy\nproperty float vz\n"
        "property float radius\nproperty int id\nend_header\n";
    constexpr std::size_t kRowSize = 7 * sizeof(float) + sizeof(int32_t);
    constexpr std::size_t kChunk = 1 << 14;  // rows per write
    writeAtomically(path, [&](const fs::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw std::runtime_error(std::strerror(errno));
        out.write(header.data(), std::streamsize(header.size()));
        std::vector<char> buffer(kChunk * kRowSize);
        for (std::size_t begin = 0; begin < g.size(); begin += kChunk) {
            const std::size_t end = std::min(g.size(), begin + kChunk);
            char* p = buffer.data();
            for (std::size_t i = begin; i < end; ++i, p += kRowSize) {
                const float row[7] = {g.px[i], g.py[i], g.pz[i],    g.vx[i],
                                      g.vy[i], g.vz[i], g.radius[i]};
                std::memcpy(p, row, sizeof row);
                std::memcpy(p + sizeof row, &g.id[i], sizeof(int32_t));
            }
            out.write(buffer.data(), p - buffer.data());
        }
        out.flush();
        if (!out) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
    });
}

Globules readGlobulePly(const fs::path& path, float defaultRadius) {
    try {
        const std::string data = readWholeFile(path);
        const PlyHeader header = parsePlyHeader(data);
        if (header.ascii) {
            AsciiCursor in{data, header.dataOffset, header.lineCount + 1};
            return readPlyData(header, in, defaultRadius);
        }
        BinaryCursor in{data, header.dataOffset};
        return readPlyData(header, in, defaultRadius);
    } catch (const std::exception& e) {
        throw IoError("cannot read " + path.string() + ": " + e.what());
    }
}

}  // namespace globular
