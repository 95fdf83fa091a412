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
#include "file_bytes.h"
#include "ply_reader.h"
#include "ply_writer.h"
#include "settings_schema.h"
#include "errors.h"

namespace globular {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "the PLY writer copies floats as they lie in memory");

namespace {

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
    for (const VertexAttribute& a : mesh.attributes) {
        if (a.values.size() != mesh.vertexCount()) {
            throw IoError("cannot write " + path.string() + ": vertex attribute " + a.name +
                          " has " + std::to_string(a.values.size()) + " values for " +
                          std::to_string(mesh.vertexCount()) + " vertices");
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

const std::vector<VertexAttribute>& knownVertexAttributes() {
    static const std::vector<VertexAttribute> known = {
        {"vx", VertexAttribute::Type::Float32, {}},
        {"vy", VertexAttribute::Type::Float32, {}},
        {"vz", VertexAttribute::Type::Float32, {}},
        {"temperature", VertexAttribute::Type::Float32, {}},
        {"material", VertexAttribute::Type::Int32, {}},
    };
    return known;
}

const VertexAttribute* TriangleMesh::attribute(std::string_view name) const {
    for (const VertexAttribute& a : attributes) {
        if (a.name == name) return &a;
    }
    return nullptr;
}

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
    PlyElement vertex{"vertex", mesh.vertexCount(), {}};
    for (const char* name : {"x", "y", "z", "nx", "ny", "nz"}) {
        if (hasNormals || name[0] != 'n') vertex.properties.push_back({name, PlyType::Float32});
    }
    for (const VertexAttribute& a : mesh.attributes) {
        const bool isInt = a.type == VertexAttribute::Type::Int32;
        vertex.properties.push_back({a.name, isInt ? PlyType::Int32 : PlyType::Float32});
    }
    const PlyElement face{"face", mesh.triangleCount(),
                          {{"vertex_indices", PlyType::Int32, PlyType::UInt8}}};
    std::string out = plyHeader("globular surface", {vertex, face});
    out.reserve(out.size() + mesh.vertexCount() * (24 + 4 * mesh.attributes.size()) +
                mesh.triangleCount() * 13);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        out.append(reinterpret_cast<const char*>(&mesh.positions[3 * v]), 12);
        if (hasNormals) out.append(reinterpret_cast<const char*>(&mesh.normals[3 * v]), 12);
        for (const VertexAttribute& a : mesh.attributes) {
            if (a.type == VertexAttribute::Type::Int32) {
                append(out, int32_t(a.values[v]));
            } else {
                append(out, a.values[v]);
            }
        }
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        append(out, uint8_t(3));
        for (int k = 0; k < 3; ++k) append(out, int32_t(mesh.triangles[3 * t + k]));
    }
    writeFileAtomically(path, out);
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
    writeFileAtomically(path, out);
}

// ---------------------------------------------------------------------------------------
// PLY reading (the header and the bounded walk through the data: ply_reader.h)

namespace {

/// Meshes larger than this are refused before they are read.
constexpr uint64_t kMaxMeshBytes = uint64_t(16) << 30;

void readVertices(const PlyElement& element, PlyCursor& cursor, TriangleMesh& mesh,
                  bool& hasNormals) {
    const int x = element.find({"x"}), y = element.find({"y"}), z = element.find({"z"});
    const int nx = element.find({"nx"}), ny = element.find({"ny"}), nz = element.find({"nz"});
    if (x < 0 || y < 0 || z < 0) throw std::runtime_error("vertex element lacks x, y or z");
    hasNormals = nx >= 0 && ny >= 0 && nz >= 0;
    std::vector<int> attributeIndex;  // property of each of mesh.attributes
    for (const VertexAttribute& known : knownVertexAttributes()) {
        const int k = element.find({known.name.c_str()});
        if (k < 0 || element.properties[std::size_t(k)].isList()) continue;
        attributeIndex.push_back(k);
        mesh.attributes.push_back({known.name, known.type, {}});
        mesh.attributes.back().values.reserve(element.count);
    }
    mesh.positions.reserve(3 * element.count);
    if (hasNormals) mesh.normals.reserve(3 * element.count);
    std::vector<double> record(element.properties.size());
    // Binary rows without lists have one size: each row is taken whole, its end checked
    // once, and its values decoded in place (the render plan reads every frame's mesh).
    std::vector<std::size_t> offset;
    std::size_t rowBytes = 0;
    if (cursor.isBinary()) {
        for (const PlyProperty& p : element.properties) {
            if (p.isList()) {
                offset.clear();
                break;
            }
            offset.push_back(rowBytes);
            rowBytes += plyTypeSize(p.type);
        }
    }
    const bool wholeRows = !offset.empty();
    for (uint64_t v = 0; v < element.count; ++v) {
        if (wholeRows) {
            const unsigned char* row = cursor.take(rowBytes);
            for (std::size_t k = 0; k < offset.size(); ++k) {
                record[k] = cursor.decode(element.properties[k].type, row + offset[k]);
            }
        } else {
            for (std::size_t k = 0; k < element.properties.size(); ++k) {
                const PlyProperty& p = element.properties[k];
                if (p.isList()) {
                    cursor.skip(p);
                } else {
                    record[k] = cursor.read(p.type);
                }
            }
        }
        for (int k : {x, y, z}) {
            if (!std::isfinite(record[k])) {
                throw std::runtime_error("vertex " + std::to_string(v) + " is not finite");
            }
            mesh.positions.push_back(float(record[k]));
        }
        if (hasNormals) {
            for (int k : {nx, ny, nz}) mesh.normals.push_back(float(record[k]));
        }
        for (std::size_t a = 0; a < attributeIndex.size(); ++a) {
            const double value = record[std::size_t(attributeIndex[a])];
            if (!std::isfinite(value) || std::abs(value) > 3.4e38) {
                throw std::runtime_error("vertex " + std::to_string(v) + " has " +
                                         mesh.attributes[a].name + " " + numberForMessage(value) +
                                         ": not a finite float");
            }
            mesh.attributes[a].values.push_back(float(value));
        }
    }
}

void readFaces(const PlyElement& element, PlyCursor& cursor, TriangleMesh& mesh) {
    int list = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const auto& p = element.properties[k];
        if (p.isList() && (p.name == "vertex_indices" || p.name == "vertex_index")) list = int(k);
    }
    if (list < 0) throw std::runtime_error("face element lacks a vertex_indices list");
    std::vector<uint32_t> polygon;
    for (uint64_t f = 0; f < element.count; ++f) {
        for (std::size_t k = 0; k < element.properties.size(); ++k) {
            const PlyProperty& p = element.properties[k];
            if (int(k) != list) {
                cursor.skip(p);
                continue;
            }
            const std::size_t n = cursor.readListLength(p.countType);
            if (n < 3) {
                throw std::runtime_error("face " + std::to_string(f) + " has fewer than 3 vertices");
            }
            polygon.clear();
            // Binary: the whole list taken at once, its end checked once (n < 2^32 items
            // of at most 8 bytes: the product cannot overflow).
            const std::size_t itemBytes = plyTypeSize(p.type);
            const unsigned char* items = cursor.isBinary() ? cursor.take(n * itemBytes) : nullptr;
            for (std::size_t i = 0; i < n; ++i) {
                const double index =
                    items ? cursor.decode(p.type, items + i * itemBytes) : cursor.read(p.type);
                if (!(index >= 0 && index < double(mesh.vertexCount()))) {
                    throw std::runtime_error(
                        "face " + std::to_string(f) + " refers to vertex " +
                        numberForMessage(index) + " of " + std::to_string(mesh.vertexCount()));
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
}

}  // namespace

TriangleMesh readMeshPly(const fs::path& path) {
    try {
        const std::string data = readFileBytes(path, kMaxMeshBytes);
        const PlyHeader header = parsePlyHeader(data);
        PlyCursor cursor(data, header);
        TriangleMesh mesh;
        bool sawVertices = false, hasNormals = false;
        for (const PlyElement& element : header.elements) {
            // Refused before anything is allocated when the count cannot fit the file.
            cursor.checkFits(element);
            if (element.name == "vertex" && !sawVertices) {
                sawVertices = true;
                readVertices(element, cursor, mesh, hasNormals);
            } else if (element.name == "face") {
                if (!sawVertices) throw std::runtime_error("face element before the vertex element");
                readFaces(element, cursor, mesh);
            } else {
                cursor.skip(element);
            }
        }
        if (!sawVertices) throw std::runtime_error("no vertex element");
        if (!hasNormals) computeAreaWeightedNormals(mesh);
        return mesh;
    } catch (const std::exception& e) {
        throw IoError("cannot read mesh " + path.string() + ": " + e.what());
    }
}

}  // namespace globular
