#include "mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace globular {

namespace {

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

}  // namespace

MeshTopology analyzeMesh(const TriangleMesh& mesh) {
    MeshTopology topo;
    const auto& p = mesh.positions;
    const auto& tri = mesh.triangles;
    const std::size_t triangleCount = mesh.triangleCount();

    // Each directed edge as (min << 32 | max) with the direction in a separate flag, sorted
    // so the uses of one undirected edge lie together.
    struct DirectedEdge {
        uint64_t key;
        bool forward;  ///< traversed from the smaller to the larger index
        bool operator<(const DirectedEdge& o) const {
            return key < o.key || (key == o.key && forward < o.forward);
        }
    };
    std::vector<DirectedEdge> edges;
    edges.reserve(3 * triangleCount);
    std::vector<uint32_t> parent(mesh.vertexCount());
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<char> used(mesh.vertexCount(), 0);

    for (std::size_t t = 0; t < triangleCount; ++t) {
        const uint32_t v[3] = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) ++topo.degenerateTriangles;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = v[k], b = v[(k + 1) % 3];
            used[a] = 1;
            edges.push_back({(uint64_t(std::min(a, b)) << 32) | std::max(a, b), a < b});
            parent[findRoot(parent, a)] = findRoot(parent, b);
        }

        const double ax = p[3 * v[0]], ay = p[3 * v[0] + 1], az = p[3 * v[0] + 2];
        const double ux = p[3 * v[1]] - ax, uy = p[3 * v[1] + 1] - ay, uz = p[3 * v[1] + 2] - az;
        const double wx = p[3 * v[2]] - ax, wy = p[3 * v[2] + 1] - ay, wz = p[3 * v[2] + 2] - az;
        const double nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
        topo.area += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
        // Divergence theorem: each triangle adds the signed volume of its tetrahedron with
        // the origin.
        topo.signedVolume += (ax * nx + ay * ny + az * nz) / 6.0;
        if (!mesh.normals.empty()) {
            double dot = 0;
            for (int k = 0; k < 3; ++k) {
                const float* n = &mesh.normals[3 * v[k]];
                dot += n[0] * nx + n[1] * ny + n[2] * nz;
            }
            if (dot <= 0) ++topo.normalsAgainstWinding;
        }
    }

    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        int forward = 0;
        while (j < edges.size() && edges[j].key == edges[i].key) forward += edges[j++].forward;
        const std::size_t uses = j - i;
        ++topo.edges;
        if (uses == 1) ++topo.boundaryEdges;
        if (uses > 2) ++topo.nonManifoldEdges;
        if (uses == 2 && forward != 1) ++topo.misorientedEdges;
        i = j;
    }

    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        if (!used[v]) continue;
        ++topo.vertices;
        if (findRoot(parent, v) == v) ++topo.components;
    }
    return topo;
}

}  // namespace globular
