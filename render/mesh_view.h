#pragma once
// The renderer's mesh input: a view of arrays owned by the caller, so the surfacing
// stage's TriangleMesh (core/mesh.h: positions, normals, triangles, attributes) is drawn
// without a copy. @code MeshView view{m.positions.data(), m.normals.data(), m.positions.size() / 3,
//                             m.triangles.data(), m.triangles.size() / 3, true}; @endcode

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "errors.h"

namespace globular {

struct MeshView {
    const float* positions = nullptr;  ///< x y z per vertex, world units
    const float* normals = nullptr;    ///< x y z per vertex (unit), or null: faceted shading
    std::size_t vertexCount = 0;
    const uint32_t* triangles = nullptr;  ///< three vertex indices per triangle
    std::size_t triangleCount = 0;
    /// Closed and wound counter-clockwise seen from outside (as the surface stage writes
    /// its meshes): back faces are then skipped. False: every face is drawn, two-sided.
    bool closed = false;
    /// One value per vertex that color_by = material or temperature colours by (a
    /// TriangleMesh attribute), or null: 0 everywhere.
    const float* values = nullptr;
    /// Each vertex's material index (the mesh's "material" attribute, scenes of several
    /// materials), for its roughness and metallic; null: material 0 everywhere.
    const float* materials = nullptr;
    /// Each vertex's velocity, world units/s (the mesh's vx, vy, vz attributes: the surface
    /// stage's kernel-weighted mean of the globules'), for motion blur; null: still.
    const float* vx = nullptr;
    const float* vy = nullptr;
    const float* vz = nullptr;
};

/// @throw Error naming the largest triangle index when it is not below mesh.vertexCount.
inline void checkTriangleIndices(const MeshView& mesh) {
    const std::size_t indexCount = mesh.triangleCount * 3;
    if (indexCount == 0) return;
    const uint32_t largest = *std::max_element(mesh.triangles, mesh.triangles + indexCount);
    if (largest >= mesh.vertexCount) {
        throw Error("render: mesh triangle index " + std::to_string(largest) +
                    " is out of range (" + std::to_string(mesh.vertexCount) + " vertices)");
    }
}

}  // namespace globular
