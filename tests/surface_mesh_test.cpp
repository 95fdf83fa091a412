#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "errors.h"
#include "mesh.h"
#include "mesh_topology.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// The unit cube [0, 1]^3 with 12 triangles wound outward.
TriangleMesh unitCube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) {
        m.positions.insert(m.positions.end(), {float(i & 1), float((i >> 1) & 1), float(i >> 2)});
    }
    // Each face as a quad seen from outside, counter-clockwise.
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.insert(m.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    }
    computeAreaWeightedNormals(m);
    return m;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_surface_mesh_test";
    fs::create_directories(dir);
    return dir / name;
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

std::string ioErrorOf(const fs::path& path) {
    try {
        readMeshPly(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

TEST(MeshTopology, UnitCubeIsClosedOutwardAndOfVolumeOne) {
    const TriangleMesh cube = unitCube();
    const MeshTopology t = analyzeMesh(cube);
    EXPECT_TRUE(t.watertight());
    EXPECT_EQ(t.vertices, 8u);
    EXPECT_EQ(t.edges, 18u);
    EXPECT_EQ(t.components, 1u);
    EXPECT_EQ(t.eulerCharacteristic(cube.triangleCount()), 2);
    EXPECT_NEAR(t.signedVolume, 1.0, 1e-12);
    EXPECT_NEAR(t.area, 6.0, 1e-12);
    EXPECT_EQ(t.normalsAgainstWinding, 0u);
}

TEST(MeshTopology, DetectsHolesFlipsAndNonManifoldEdges) {
    TriangleMesh open = unitCube();
    open.triangles.resize(open.triangles.size() - 3);  // one triangle missing
    EXPECT_EQ(analyzeMesh(open).boundaryEdges, 3u);

    TriangleMesh flipped = unitCube();
    std::swap(flipped.triangles[1], flipped.triangles[2]);
    const MeshTopology f = analyzeMesh(flipped);
    EXPECT_EQ(f.misorientedEdges, 3u);
    EXPECT_EQ(f.normalsAgainstWinding, 1u);

    TriangleMesh fin = unitCube();
    fin.positions.insert(fin.positions.end(), {0.5f, 0.5f, 0.5f});
    fin.normals.insert(fin.normals.end(), {0, 0, 1});
    fin.triangles.insert(fin.triangles.end(), {0, 1, 8});  // a third face on edge 0-1
    EXPECT_EQ(analyzeMesh(fin).nonManifoldEdges, 1u);
    EXPECT_FALSE(analyzeMesh(fin).watertight());

    TriangleMesh two = unitCube();
    const TriangleMesh other = unitCube();
    for (std::size_t i = 0; i < other.positions.size(); ++i) {
        two.positions.push_back(other.positions[i] + 3.0f);
        two.normals.push_back(other.normals[i]);
    }
    for (uint32_t v : other.triangles) two.triangles.push_back(v + 8);
    EXPECT_EQ(analyzeMesh(two).components, 2u);
    EXPECT_NEAR(analyzeMesh(two).signedVolume, 2.0, 1e-9);
}

TEST(MeshFile, PlyRoundTripIsExact) {
    const TriangleMesh cube = unitCube();
    const fs::path path = scratch("cube.ply");
    writeMeshPly(path, cube);
    const TriangleMesh back = readMeshPly(path);
    EXPECT_EQ(back.positions, cube.positions);
    EXPECT_EQ(back.normals, cube.normals);
    EXPECT_EQ(back.triangles, cube.triangles);
    // Header as documented; 8 * 24 vertex bytes and 12 * 13 face bytes follow it.
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(bytes.find("property float nx\n"), std::string::npos);
    EXPECT_NE(bytes.find("property list uchar int vertex_indices\n"), std::string::npos);
    EXPECT_EQ(bytes.size() - (bytes.find("end_header\n") + 11), 8u * 24 + 12u * 13);
}

TEST(MeshFile, ObjHasVerticesNormalsAndOneBasedFaces) {
    const fs::path path = scratch("cube.obj");
    writeMeshObj(path, unitCube());
    std::ifstream in(path);
    std::string line;
    int v = 0, vn = 0, f = 0;
    std::string firstFace;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) ++v;
        if (line.rfind("vn ", 0) == 0) ++vn;
        if (line.rfind("f ", 0) == 0 && f++ == 0) firstFace = line;
    }
    EXPECT_EQ(v, 8);
    EXPECT_EQ(vn, 8);
    EXPECT_EQ(f, 12);
    EXPECT_EQ(firstFace, "f 1//1 3//3 4//4");
}

/// @p value as @p T's bytes, reversed for a big-endian file.
template <typename T>
void appendValue(std::string& out, T value, bool bigEndian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (bigEndian) std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

/// A unit square in binary PLY, each vertex's x, y, z as a double, a float and a short,
/// with a float temperature and an int material, and one quad with ushort indices.
std::string binarySquare(bool bigEndian) {
    std::string out = std::string("ply\nformat ") +
                      (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty double x\nproperty float y\n"
                      "property short z\nproperty float temperature\nproperty int material\n"
                      "element face 1\nproperty list uchar ushort vertex_indices\nend_header\n";
    const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int v = 0; v < 4; ++v) {
        appendValue(out, corners[v][0], bigEndian);
        appendValue(out, float(corners[v][1]), bigEndian);
        appendValue(out, int16_t(-2), bigEndian);
        appendValue(out, 20.5f + float(v), bigEndian);
        appendValue(out, int32_t(v % 2), bigEndian);
    }
    out += char(4);
    for (uint16_t index : {0, 1, 2, 3}) appendValue(out, index, bigEndian);
    return out;
}

TEST(MeshFile, ReadsBinaryPlyRowsOfEveryTypeInEitherByteOrder) {
    for (bool bigEndian : {false, true}) {
        const fs::path path = scratch("square.ply");
        writeText(path, binarySquare(bigEndian));
        const TriangleMesh m = readMeshPly(path);
        EXPECT_EQ(m.positions, (std::vector<float>{0, 0, -2, 1, 0, -2, 1, 1, -2, 0, 1, -2}))
            << bigEndian;
        EXPECT_EQ(m.triangles, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        ASSERT_NE(m.attribute("temperature"), nullptr);
        EXPECT_EQ(m.attribute("temperature")->values,
                  (std::vector<float>{20.5f, 21.5f, 22.5f, 23.5f}));
        ASSERT_NE(m.attribute("material"), nullptr);
        EXPECT_EQ(m.attribute("material")->values, (std::vector<float>{0, 1, 0, 1}));

        // Cut anywhere in the data, the file is refused as truncated: in a vertex row and
        // in the face's list.
        const std::string whole = binarySquare(bigEndian);
        const std::size_t data = whole.find("end_header\n") + 11;
        for (std::size_t cut : {data + 3, data + 4 * 22 - 1, whole.size() - 1}) {
            writeText(path, whole.substr(0, cut));
            EXPECT_NE(ioErrorOf(path).find("truncated"), std::string::npos)
                << "cut at " << cut - data << ": " << ioErrorOf(path);
        }
    }
}

TEST(MeshFile, ReadsAsciiPlyWithQuadsAsFans) {
    const fs::path path = scratch("quad.ply");
    writeText(path,
              "ply\nformat ascii 1.0\ncomment a unit square\nelement vertex 4\n"
              "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
              "element face 1\nproperty list uchar int vertex_index\nend_header\n"
              "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 9\n4 0 1 2 3\n");
    const TriangleMesh m = readMeshPly(path);
    EXPECT_EQ(m.vertexCount(), 4u);
    EXPECT_EQ(m.triangles, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    // No normals in the file: area-weighted ones, +z for a counter-clockwise square.
    for (std::size_t i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(m.normals[3 * i + 2], 1.0f);
}

TEST(MeshFile, BadFilesThrowIoErrorNamingTheFile) {
    EXPECT_NE(ioErrorOf(scratch("missing.ply")).find("missing.ply"), std::string::npos);

    writeText(scratch("notply.ply"), "solid cube\n");
    EXPECT_NE(ioErrorOf(scratch("notply.ply")).find("not a PLY"), std::string::npos);

    writeMeshPly(scratch("whole.ply"), unitCube());
    std::ifstream in(scratch("whole.ply"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    writeText(scratch("truncated.ply"), bytes.substr(0, bytes.size() - 20));
    const std::string truncated = ioErrorOf(scratch("truncated.ply"));
    EXPECT_NE(truncated.find("truncated.ply"), std::string::npos);
    EXPECT_NE(truncated.find("truncated"), std::string::npos);

    writeText(scratch("badindex.ply"),
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    EXPECT_NE(ioErrorOf(scratch("badindex.ply")).find("vertex 7 of 3"), std::string::npos);

    writeText(scratch("huge.ply"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 999999999999\n"
              "property float x\nproperty float y\nproperty float z\nend_header\n");
    EXPECT_NE(ioErrorOf(scratch("huge.ply")).find("too short"), std::string::npos);
}

}  // namespace
}  // namespace globular
