// Meshing a level set: volumeToMesh, quads split into triangles, gradient normals.
#include <openvdb/tools/Interpolation.h>
// volumeToMesh is instantiated here, with this project's flags, instead of called in the
// library's explicit instantiation: the pour's adaptive mesh (BM_MeshAdaptive) takes
// 1.4-1.6x less time so, and the meshes are byte-identical. The templates are OpenVDB's
// own, from the same headers; only where they are compiled changes (not in the sanitizer
// and fuzzing builds: surface/CMakeLists.txt).
#ifdef GLOBULAR_MESHER_INSTANTIATED_HERE
#undef OPENVDB_USE_EXPLICIT_INSTANTIATION
#endif
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "surface_grids.h"

namespace globular {

namespace {

using openvdb::FloatGrid;
using openvdb::Vec3s;

float distanceSquared(const Vec3s& a, const Vec3s& b) { return (a - b).lengthSqr(); }

/// Appends triangle (a, b, c) wound outward: volumeToMesh emits polygons whose right-hand
/// normal points into the level set's negative side, so the order is reversed here.
void appendOutward(std::vector<uint32_t>& out, uint32_t a, uint32_t b, uint32_t c) {
    out.insert(out.end(), {a, c, b});
}

/// Central differences of the level set's trilinear interpolant half a voxel either side
/// of index-space point @p p along each axis: the six samples of OpenVDB's BoxSampler,
/// bit for bit, from the 3x3x3 voxels they share: 27 reads, straight from the leaf when
/// the window lies in one, where the samplers make 48 through the accessor.
openvdb::Vec3d halfVoxelGradient(const FloatGrid::ConstAccessor& accessor,
                                 const openvdb::Vec3d& p) {
    using openvdb::Coord;
    using Leaf = FloatGrid::TreeType::LeafNodeType;
    const Coord base(int(std::floor(p[0] - 0.5)), int(std::floor(p[1] - 0.5)),
                     int(std::floor(p[2] - 0.5)));
    float window[3][3][3];
    const Leaf* leaf = accessor.probeConstLeaf(base);
    const int mask = int(Leaf::DIM) - 1;
    if (leaf && (base[0] & mask) <= mask - 2 && (base[1] & mask) <= mask - 2 &&
        (base[2] & mask) <= mask - 2) {
        const float* values = leaf->buffer().data();
        const openvdb::Index first = Leaf::coordToOffset(base);
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                for (int c = 0; c < 3; ++c) {
                    window[a][b][c] = values[first + openvdb::Index(a << 6 | b << 3 | c)];
                }
            }
        }
    } else {
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                for (int c = 0; c < 3; ++c) {
                    window[a][b][c] = accessor.getValue(base.offsetBy(a, b, c));
                }
            }
        }
    }
    openvdb::Vec3d gradient;
    for (int k = 0; k < 3; ++k) {
        float side[2];
        for (int s = 0; s < 2; ++s) {
            openvdb::Vec3d q = p;
            q[k] += s ? 0.5 : -0.5;
            const openvdb::Vec3i cell = openvdb::tools::local_util::floorVec3(q);
            const openvdb::Vec3d uvw = q - cell;
            const Coord o = Coord(cell) - base;  // 0 or 1 on each axis
            float corners[2][2][2];
            for (int a = 0; a < 2; ++a) {
                for (int b = 0; b < 2; ++b) {
                    for (int c = 0; c < 2; ++c) {
                        corners[a][b][c] = window[o[0] + a][o[1] + b][o[2] + c];
                    }
                }
            }
            side[s] = openvdb::tools::BoxSampler::trilinearInterpolation(corners, uvw);
        }
        gradient[k] = side[1] - side[0];
    }
    return gradient;
}

}  // namespace

TriangleMesh meshLevelSet(const FloatGrid& levelSet, double adaptivity) {
    TriangleMesh mesh;
    std::vector<Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(levelSet, points, triangles, quads, 0.0, adaptivity, true);
    if (points.empty()) return mesh;

    mesh.positions.resize(3 * points.size());
    for (std::size_t v = 0; v < points.size(); ++v) {
        for (int k = 0; k < 3; ++k) mesh.positions[3 * v + k] = points[v][k];
    }
    mesh.triangles.reserve(3 * triangles.size() + 6 * quads.size());
    for (const auto& t : triangles) appendOutward(mesh.triangles, t[0], t[1], t[2]);
    for (const auto& q : quads) {
        // The shorter diagonal gives the better-shaped pair of triangles.
        if (distanceSquared(points[q[0]], points[q[2]]) <=
            distanceSquared(points[q[1]], points[q[3]])) {
            appendOutward(mesh.triangles, q[0], q[1], q[2]);
            appendOutward(mesh.triangles, q[0], q[2], q[3]);
        } else {
            appendOutward(mesh.triangles, q[0], q[1], q[3]);
            appendOutward(mesh.triangles, q[1], q[2], q[3]);
        }
    }

    // Normals: central differences of the trilinearly interpolated level set half a voxel
    // either side of each vertex. Smooth across polygons, and outward because the level
    // set grows outward.
    mesh.normals.resize(mesh.positions.size());
    const auto& xform = levelSet.transform();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](auto range) {
        auto accessor = levelSet.getConstAccessor();
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
            const openvdb::Vec3d g =
                halfVoxelGradient(accessor, xform.worldToIndex(openvdb::Vec3d(points[v])));
            const double length = g.length();
            float* n = &mesh.normals[3 * v];
            if (length > 0) {
                for (int k = 0; k < 3; ++k) n[k] = float(g[k] / length);
            } else {
                n[0] = n[1] = n[2] = 0.0f;
            }
        }
    });
    // A flat gradient (a surface thinner than a voxel) leaves no direction: fall back to
    // the faces around such vertices.
    bool flat = false;
    for (std::size_t v = 0; v < points.size() && !flat; ++v) {
        flat = mesh.normals[3 * v] == 0 && mesh.normals[3 * v + 1] == 0 &&
               mesh.normals[3 * v + 2] == 0;
    }
    if (flat) {
        TriangleMesh faces{mesh.positions, {}, mesh.triangles, {}};
        computeAreaWeightedNormals(faces);
        for (std::size_t i = 0; i < mesh.normals.size(); i += 3) {
            if (mesh.normals[i] == 0 && mesh.normals[i + 1] == 0 && mesh.normals[i + 2] == 0) {
                for (int k = 0; k < 3; ++k) mesh.normals[i + k] = faces.normals[i + k];
            }
        }
    }
    return mesh;
}

}  // namespace globular
