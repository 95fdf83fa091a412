#pragma once
// Checks that a triangle mesh is a proper closed surface: every edge shared by exactly two
// triangles that traverse it in opposite directions, normals on the side the winding says.
// Used by the tests and by the stage, which warns when a mesh is not watertight.

#include <cstddef>

#include "mesh.h"

namespace globular {

struct MeshTopology {
    std::size_t vertices = 0;               ///< vertices used by at least one triangle
    std::size_t edges = 0;                  ///< distinct undirected edges
    std::size_t boundaryEdges = 0;          ///< edges of exactly one triangle (holes)
    std::size_t nonManifoldEdges = 0;       ///< edges of three or more triangles
    std::size_t misorientedEdges = 0;       ///< two-triangle edges traversed the same way
    std::size_t degenerateTriangles = 0;    ///< triangles that repeat a vertex
    std::size_t normalsAgainstWinding = 0;  ///< triangles whose vertex normals face away
    std::size_t components = 0;             ///< pieces connected through shared vertices
    double signedVolume = 0;                ///< world units^3; > 0 when faces point outward
    double area = 0;                        ///< world units^2

    /// V - E + F over the used vertices: 2 per sphere-like piece, 0 per torus.
    long eulerCharacteristic(std::size_t triangles) const {
        return long(vertices) - long(edges) + long(triangles);
    }
    /// Closed, manifold and consistently oriented.
    bool watertight() const {
        return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0 &&
               degenerateTriangles == 0;
    }
};

MeshTopology analyzeMesh(const TriangleMesh& mesh);

}  // namespace globular
