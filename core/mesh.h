#pragma once
// A triangle mesh as plain arrays, and its files: what the surface stage writes, the
// render stage reads, and mesh colliders (sim) are made of. OpenVDB-free.
//
// PLY files are binary little endian with vertex properties x y z nx ny nz (float) and
// faces as "list uchar int vertex_indices": what Blender, Houdini and MeshLab import.
// OBJ files are text with v, vn and f a//a b//b c//c lines (indices from 1).
// Triangles wind counter-clockwise seen from outside: (b - a) x (c - a) points outward,
// along the vertex normals. Per-vertex scalars (VertexAttribute: the surface stage's
// velocity vx vy vz, temperature and material) follow nx ny nz as PLY vertex properties
// of their names; OBJ files carry none.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace globular {

/// One scalar per vertex, written as a PLY vertex property named @c name. A vector
/// quantity is several of them (the velocity is vx, vy, vz).
struct VertexAttribute {
    enum class Type { Float32, Int32 };
    std::string name;
    Type type = Type::Float32;
    std::vector<float> values;  ///< one per vertex; whole numbers when type is Int32
};

/// The vertex properties readMeshPly keeps as attributes (others are skipped), with the
/// type each is written as.
const std::vector<VertexAttribute>& knownVertexAttributes();

struct TriangleMesh {
    std::vector<float> positions;     ///< x y z per vertex, world units
    std::vector<float> normals;       ///< unit x y z per vertex (same count as positions)
    std::vector<uint32_t> triangles;  ///< 3 vertex indices per triangle
    std::vector<VertexAttribute> attributes;  ///< per-vertex scalars, each vertexCount() long

    /// The attribute named @p name, or null.
    const VertexAttribute* attribute(std::string_view name) const;
    std::size_t vertexCount() const { return positions.size() / 3; }
    std::size_t triangleCount() const { return triangles.size() / 3; }
    bool empty() const { return triangles.empty(); }
};

/// Writes @p mesh as binary little-endian PLY, atomically.
/// @throw IoError naming @p path.
void writeMeshPly(const std::filesystem::path& path, const TriangleMesh& mesh);

/// Writes @p mesh as Wavefront OBJ text, atomically.
/// @throw IoError naming @p path.
void writeMeshObj(const std::filesystem::path& path, const TriangleMesh& mesh);

/// Reads a PLY mesh: ascii, binary little or big endian; vertex x y z required, nx ny nz
/// optional (area-weighted normals are computed when absent), the knownVertexAttributes()
/// optional (a non-finite one is an error); faces as a list property
/// "vertex_indices" (or "vertex_index"), polygons split into fans. Other elements and
/// properties are skipped.
/// @throw IoError naming @p path and what is wrong (not PLY, truncated, bad index, ...).
TriangleMesh readMeshPly(const std::filesystem::path& path);

/// Wavefront OBJ: v and vn lines, f lines of v, v//vn, v/vt or v/vt/vn (indices from 1 or
/// negative from the end), polygons split into fans. Normals are used when there is one
/// per vertex, as the surface stage writes them; otherwise computed from the faces.
/// @throw IoError naming @p path and the line at fault.
TriangleMesh readMeshObj(const std::filesystem::path& path);

/// readMeshObj or readMeshPly by @p path's extension (.obj or .ply, any case).
/// @throw IoError naming @p path, also for any other extension.
TriangleMesh readMeshFile(const std::filesystem::path& path);

/// Sets @p mesh.normals to the normalised, area-weighted sum of the face normals around
/// each vertex (a vertex on no face gets (0, 0, 0)).
void computeAreaWeightedNormals(TriangleMesh& mesh);

}  // namespace globular
