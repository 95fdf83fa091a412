#include "mesh.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "atomic_file.h"
#include "ply_types.h"
#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "the PLY writer copies floats as they lie in memory");

namespace {

void writeBytes(const fs::path& temporary, const std::string& bytes) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw IoError("cannot open " + temporary.string());
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.flush();
    if (!out) throw IoError("write failed (disk full?)");
}

void checkMesh(const fs::path& path, const TriangleMesh& mesh) {
    if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0 ||
        (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())) {
        throw IoError("cannot write " + path.string() + ": malformed mesh arrays");
    }
    for (uint32_t v : mesh.triangles) {
        if (v >= mesh.vertexCount()) {
            throw IoError("cannot write " + path.string() + ": triangle index out of range");
        }
    }
}

template <typename T>
void append(std::string& out, const T& value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void appendNumber(std::string& out, float v) {
    char buffer[32];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, end);
}

void appendNumber(std::string& out, uint32_t v) {
    char buffer[16];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, end);
}

}  // namespace

void computeAreaWeightedNormals(TriangleMesh& mesh) {
    const auto& p = mesh.positions;
    std::vector<double> sum(p.size(), 0.0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t a = mesh.triangles[3 * t], b = mesh.triangles[3 * t + 1],
                       c = mesh.triangles[3 * t + 2];
        const double ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1],
                     uz = p[3 * b + 2] - p[3 * a + 2];
        const double vx = p[3 * c] - p[3 * a], vy = p[3 * c + 1] - p[3 * a + 1],
                     vz = p[3 * c + 2] - p[3 * a + 2];
        // The cross product's length is twice the area: summing it weights by area.
        const double n[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
        for (uint32_t v : {a, b, c}) {
            for (int k = 0; k < 3; ++k) sum[3 * v + k] += n[k];
        }
    }
    mesh.normals.assign(p.size(), 0.0f);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const double len = std::sqrt(sum[3 * v] * sum[3 * v] + sum[3 * v + 1] * sum[3 * v + 1] +
                                     sum[3 * v + 2] * sum[3 * v + 2]);
        if (len > 0) {
            for (int k = 0; k < 3; ++k) mesh.normals[3 * v + k] = float(sum[3 * v + k] / len);
        }
    }
}

void writeMeshPly(const fs::path& path, const TriangleMesh& mesh) {
    checkMesh(path, mesh);
    const bool hasNormals = !mesh.normals.empty();
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment globular surface\n";
    out += "element vertex " + std::to_string(mesh.vertexCount()) + "\n";
    out += "property float x\nproperty float y\nproperty float z\n";
    if (hasNormals) out += "property float nx\nproperty float ny\nproperty float nz\n";
    out += "element face " + std::to_string(mesh.triangleCount()) + "\n";
    out += "property list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + mesh.vertexCount() * 24 + mesh.triangleCount() * 13);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        out.append(reinterpret_cast<const char*>(&mesh.positions[3 * v]), 12);
        if (hasNormals) out.append(reinterpret_cast<const char*>(&mesh.normals[3 * v]), 12);
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        append(out, uint8_t(3));
        for (int k = 0; k < 3; ++k) append(out, int32_t(mesh.triangles[3 * t + k]));
    }
    writeAtomically(path, [&](const fs::path& temporary) { writeBytes(temporary, out); });
}

void writeMeshObj(const fs::path& path, const TriangleMesh& mesh) {
    checkMesh(path, mesh);
    const bool hasNormals = !mesh.normals.empty();
    std::string out = "# globular surface\n";
    out.reserve(mesh.vertexCount() * 70 + mesh.triangleCount() * 40);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        out += "v";
        for (int k = 0; k < 3; ++k) {
            out += ' ';
            appendNumber(out, mesh.positions[3 * v + k]);
        }
        out += '\n';
    }
    if (hasNormals) {
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            out += "vn";
            for (int k = 0; k < 3; ++k) {
                out += ' ';
                appendNumber(out, mesh.normals[3 * v + k]);
            }
            out += '\n';
        }
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        out += "f";
        for (int k = 0; k < 3; ++k) {
            const uint32_t index = mesh.triangles[3 * t + k] + 1;
            out += ' ';
            appendNumber(out, index);
            if (hasNormals) {
                out += "//";
                appendNumber(out, index);
            }
        }
        out += '\n';
    }
    writeAtomically(path, [&](const fs::path& temporary) { writeBytes(temporary, out); });
}

// ---------------------------------------------------------------------------------------
// PLY reading

namespace {

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::None;       ///< value type (of the items, for a list)
    PlyType countType = PlyType::None;  ///< None unless a list
};

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
};

/// Walks the body of a PLY file value by value, in ascii or binary.
class PlyCursor {
  public:
    PlyCursor(const fs::path& path, const std::string& data, std::size_t offset, bool ascii,
              bool bigEndian)
        : mPath(path), mData(data), mPos(offset), mAscii(ascii), mBigEndian(bigEndian) {}

    double read(PlyType type) {
        if (mAscii) return readAscii();
        const std::size_t size = plyTypeSize(type);
        if (mPos + size > mData.size()) fail("truncated: the file ends inside its data");
        unsigned char bytes[8];
        std::memcpy(bytes, mData.data() + mPos, size);
        mPos += size;
        if (mBigEndian) std::reverse(bytes, bytes + size);
        switch (type) {
            case PlyType::Int8:
                return double(int8_t(bytes[0]));
            case PlyType::UInt8:
                return double(bytes[0]);
            case PlyType::Int16:
                return decode<int16_t>(bytes);
            case PlyType::UInt16:
                return decode<uint16_t>(bytes);
            case PlyType::Int32:
                return decode<int32_t>(bytes);
            case PlyType::UInt32:
                return decode<uint32_t>(bytes);
            case PlyType::Float32:
                return decode<float>(bytes);
            case PlyType::Float64:
                return decode<double>(bytes);
            case PlyType::None:
                break;
        }
        fail("unknown property type");
    }

    std::size_t remaining() const { return mData.size() - mPos; }

    [[noreturn]] void fail(const std::string& problem) const {
        throw IoError("cannot read mesh " + mPath.string() + ": " + problem);
    }

  private:
    template <typename T>
    static double decode(const unsigned char* bytes) {
        T value;
        std::memcpy(&value, bytes, sizeof value);
        return double(value);
    }

    double readAscii() {
        while (mPos < mData.size() && std::isspace(static_cast<unsigned char>(mData[mPos]))) {
            ++mPos;
        }
        if (mPos >= mData.size()) fail("truncated: fewer values than the header declares");
        double value = 0;
        const char* begin = mData.data() + mPos;
        auto [end, ec] = std::from_chars(begin, mData.data() + mData.size(), value);
        if (ec != std::errc()) {
            fail("bad number '" + std::string(begin, std::min<std::size_t>(16, remaining())) + "'");
        }
        mPos += std::size_t(end - begin);
        return value;
    }

    const fs::path& mPath;
    const std::string& mData;
    std::size_t mPos;
    bool mAscii, mBigEndian;
};

int findProperty(const PlyElement& element, std::initializer_list<const char*> names) {
    for (std::size_t i = 0; i < element.properties.size(); ++i) {
        for (const char* n : names) {
            if (element.properties[i].name == n) return int(i);
        }
    }
    return -1;
}

}  // namespace

TriangleMesh readMeshPly(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read mesh " + path.string() + ": no such file or unreadable");
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto fail = [&](const std::string& problem) -> void {
        throw IoError("cannot read mesh " + path.string() + ": " + problem);
    };

    // Header: one keyword line at a time, up to end_header.
    std::size_t pos = 0;
    std::vector<PlyElement> elements;
    std::string format;
    bool ended = false, first = true;
    while (!ended) {
        const std::size_t eol = data.find('\n', pos);
        if (eol == std::string::npos) fail("not a PLY file or truncated header");
        std::string line = data.substr(pos, eol - pos);
        pos = eol + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (first) {
            if (keyword != "ply") fail("not a PLY file (no 'ply' magic)");
            first = false;
        } else if (keyword == "format") {
            words >> format;
        } else if (keyword == "element") {
            PlyElement e;
            long long count = -1;
            words >> e.name >> count;
            if (!words || count < 0) fail("bad element line '" + line + "'");
            e.count = std::size_t(count);
            elements.push_back(e);
        } else if (keyword == "property") {
            if (elements.empty()) fail("property before any element");
            std::string type;
            words >> type;
            PlyProperty p;
            if (type == "list") {
                std::string countType, itemType;
                words >> countType >> itemType >> p.name;
                p.countType = plyTypeNamed(countType);
                p.type = plyTypeNamed(itemType);
                if (p.countType == PlyType::None) fail("bad list count type '" + countType + "'");
            } else {
                words >> p.name;
                p.type = plyTypeNamed(type);
            }
            if (p.type == PlyType::None || p.name.empty()) fail("bad property '" + line + "'");
            elements.back().properties.push_back(p);
        } else if (keyword == "end_header") {
            ended = true;
        } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
            fail("unknown header line '" + line + "'");
        }
    }
    const bool ascii = format == "ascii";
    if (!ascii && format != "binary_little_endian" && format != "binary_big_endian") {
        fail("unknown format '" + format + "'");
    }
    PlyCursor cursor(path, data, pos, ascii, format == "binary_big_endian");

    TriangleMesh mesh;
    bool sawVertices = false, hasNormals = false;
    std::vector<double> record;
    for (const PlyElement& element : elements) {
        // Each record holds at least one byte (or one ascii character) per property, so a
        // count beyond that is a corrupt header, refused before anything is allocated.
        if (!element.properties.empty() &&
            element.count > cursor.remaining() / element.properties.size()) {
            fail("element '" + element.name + "' declares " + std::to_string(element.count) +
                 " records but the file is too short");
        }
        if (element.name == "vertex") {
            sawVertices = true;
            const int x = findProperty(element, {"x"}), y = findProperty(element, {"y"}),
                      z = findProperty(element, {"z"});
            const int nx = findProperty(element, {"nx"}), ny = findProperty(element, {"ny"}),
                      nz = findProperty(element, {"nz"});
            if (x < 0 || y < 0 || z < 0) fail("vertex element lacks x, y or z");
            hasNormals = nx >= 0 && ny >= 0 && nz >= 0;
            mesh.positions.reserve(3 * element.count);
            if (hasNormals) mesh.normals.reserve(3 * element.count);
            record.resize(element.properties.size());
            for (std::size_t v = 0; v < element.count; ++v) {
                for (std::size_t k = 0; k < element.properties.size(); ++k) {
                    const PlyProperty& p = element.properties[k];
                    if (p.countType != PlyType::None) {
                        const double n = cursor.read(p.countType);
                        for (double i = 0; i < n; ++i) cursor.read(p.type);
                        continue;
                    }
                    record[k] = cursor.read(p.type);
                }
                for (int k : {x, y, z}) mesh.positions.push_back(float(record[k]));
                if (hasNormals) {
                    for (int k : {nx, ny, nz}) mesh.normals.push_back(float(record[k]));
                }
            }
        } else if (element.name == "face") {
            if (!sawVertices) fail("face element before the vertex element");
            const int list = findProperty(element, {"vertex_indices", "vertex_index"});
            if (list < 0 || element.properties[list].countType == PlyType::None) {
                fail("face element lacks a vertex_indices list");
            }
            std::vector<uint32_t> polygon;
            for (std::size_t f = 0; f < element.count; ++f) {
                for (std::size_t k = 0; k < element.properties.size(); ++k) {
                    const PlyProperty& p = element.properties[k];
                    if (p.countType == PlyType::None) {
                        cursor.read(p.type);
                        continue;
                    }
                    const double n = cursor.read(p.countType);
                    if (int(k) != list) {
                        for (double i = 0; i < n; ++i) cursor.read(p.type);
                        continue;
                    }
                    if (n < 3) fail("face " + std::to_string(f) + " has fewer than 3 vertices");
                    polygon.clear();
                    for (double i = 0; i < n; ++i) {
                        const double index = cursor.read(p.type);
                        if (!(index >= 0 && index < double(mesh.vertexCount()))) {
                            fail("face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(static_cast<long long>(index)) + " of " +
                                 std::to_string(mesh.vertexCount()));
                        }
                        polygon.push_back(uint32_t(index));
                    }
                    // A fan keeps the polygon's winding and so its facing.
                    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
                        mesh.triangles.insert(mesh.triangles.end(),
                                              {polygon[0], polygon[i], polygon[i + 1]});
                    }
                }
            }
        } else {
            for (std::size_t r = 0; r < element.count; ++r) {
                for (const PlyProperty& p : element.properties) {
                    const double n = p.countType == PlyType::None ? 1 : cursor.read(p.countType);
                    for (double i = 0; i < n; ++i) cursor.read(p.type);
                }
            }
        }
    }
    if (!sawVertices) fail("no vertex element");
    if (!hasNormals) computeAreaWeightedNormals(mesh);
    return mesh;
}

}  // namespace globular
