#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

#include "errors.h"
#include "file_bytes.h"
#include "mesh.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// Meshes larger than this are refused before they are read.
constexpr uint64_t kMaxObjBytes = uint64_t(16) << 30;

[[noreturn]] void fail(const fs::path& path, std::size_t line, const std::string& problem) {
    throw IoError(path.string() + ":" + std::to_string(line) + ": " + problem);
}

/// The vertex index of a face corner "7", "7//7", "7/3" or "7/3/7", from 0.
uint32_t cornerIndex(const std::string& token, std::size_t vertexCount, const fs::path& path,
                     std::size_t line) {
    long long index = 0;
    const char* end = token.data() + token.size();
    const auto [stop, ec] = std::from_chars(token.data(), end, index);
    if (ec != std::errc() || (stop != end && *stop != '/')) {
        fail(path, line, "bad face corner '" + quoteForMessage(token, 40) + "'");
    }
    if (index < 0) index += (long long)vertexCount + 1;  // relative to the vertices so far
    if (index < 1 || index > (long long)vertexCount) {
        fail(path, line, "face index " + quoteForMessage(token, 40) + " is out of range");
    }
    return uint32_t(index - 1);
}

}  // namespace

TriangleMesh readMeshObj(const fs::path& path) {
    std::string bytes;
    try {
        bytes = readFileBytes(path, kMaxObjBytes);
    } catch (const std::exception& e) {
        throw IoError("cannot read mesh " + path.string() + ": " + e.what());
    }
    std::istringstream in(std::move(bytes));
    TriangleMesh mesh;
    std::vector<float> normals;
    std::string text;
    std::size_t lineNumber = 0;
    while (std::getline(in, text)) {
        ++lineNumber;
        std::istringstream line(text);
        std::string kind;
        line >> kind;
        if (kind == "v" || kind == "vn") {
            float xyz[3];
            if (!(line >> xyz[0] >> xyz[1] >> xyz[2])) fail(path, lineNumber, "expected x y z");
            if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
                fail(path, lineNumber, "a coordinate is not finite");
            }
            auto& target = kind == "v" ? mesh.positions : normals;
            target.insert(target.end(), xyz, xyz + 3);
        } else if (kind == "f") {
            std::vector<uint32_t> corners;
            std::string token;
            while (line >> token) {
                corners.push_back(cornerIndex(token, mesh.vertexCount(), path, lineNumber));
            }
            if (corners.size() < 3) fail(path, lineNumber, "a face needs three corners");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
                mesh.triangles.insert(mesh.triangles.end(),
                                      {corners[0], corners[k], corners[k + 1]});
            }
        }  // other lines (comments, vt, groups, materials) do not change the shape
    }
    if (in.bad()) throw IoError("cannot read " + path.string());
    if (normals.size() == mesh.positions.size()) {
        mesh.normals = std::move(normals);
    } else {
        computeAreaWeightedNormals(mesh);
    }
    return mesh;
}

TriangleMesh readMeshFile(const fs::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension) c = char(std::tolower((unsigned char)c));
    if (extension == ".obj") return readMeshObj(path);
    if (extension == ".ply") return readMeshPly(path);
    throw IoError("mesh " + path.string() + ": expected an .obj or .ply file, not '" +
                  quoteForMessage(path.extension().string(), 40) + "'");
}

}  // namespace globular
