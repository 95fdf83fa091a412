#pragma once
// A closed axis-aligned box as a triangle mesh, for the render tests.

#include <cstdint>
#include <vector>

#include "mesh.h"
#include "mesh_view.h"
#include "vec3.h"

namespace globular {

/// A closed box, four vertices per face with its normal, wound counter-clockwise seen
/// from outside.
struct BoxMesh {
    std::vector<float> positions, normals;
    std::vector<uint32_t> triangles;
    BoxMesh(Vec3 lo, Vec3 hi) {
        auto face = [&](Vec3 n, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
            const auto base = uint32_t(positions.size() / 3);
            for (Vec3 v : {a, b, c, d}) {
                positions.insert(positions.end(), {float(v.x), float(v.y), float(v.z)});
                normals.insert(normals.end(), {float(n.x), float(n.y), float(n.z)});
            }
            // a b c d run counter-clockwise around n
            triangles.insert(triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        };
        const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
        face({0, 1, 0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0});
        face({0, -1, 0}, {x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1});
        face({1, 0, 0}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1});
        face({-1, 0, 0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0});
        face({0, 0, 1}, {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1});
        face({0, 0, -1}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0});
    }
    TriangleMesh mesh() const { return {positions, normals, triangles, {}}; }
    MeshView view() const {
        return {positions.data(), normals.data(), positions.size() / 3, triangles.data(),
                triangles.size() / 3, true};
    }
};

}  // namespace globular
