#include "mesh_sdf.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tree/ValueAccessor.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

using FloatTree = openvdb::FloatTree;
using LeafNode = FloatTree::LeafNodeType;
using IndexTree = openvdb::Int32Tree;
using IndexLeaf = IndexTree::LeafNodeType;

void initializeVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

/// Edges of a mesh by how many triangles they lie on.
struct EdgeCounts {
    std::size_t boundary = 0;     ///< on one triangle only
    std::size_t nonManifold = 0;  ///< on three or more
};

/// Vertex ids with vertices at the same position made one (exact float equality).
std::vector<uint32_t> weldedIds(const TriangleMesh& mesh) {
    struct Key {
        uint32_t bits[3];
        bool operator==(const Key& o) const {
            return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
        }
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            uint64_t h = 1469598103934665603ull;
            for (uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
            return std::size_t(h);
        }
    };
    const std::size_t n = mesh.vertexCount();
    std::vector<uint32_t> ids(n);
    std::unordered_map<Key, uint32_t, KeyHash> first;
    first.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        Key key;
        for (int a = 0; a < 3; ++a) {
            const float c = mesh.positions[3 * v + a] + 0.0f;  // -0 and +0 alike
            std::memcpy(&key.bits[a], &c, sizeof c);
        }
        ids[v] = first.emplace(key, uint32_t(v)).first->second;
    }
    return ids;
}

/// Triangles with an index out of range are the caller's to reject; they are skipped.
EdgeCounts countEdges(const TriangleMesh& mesh) {
    const std::vector<uint32_t> ids = weldedIds(mesh);
    std::vector<uint64_t> edges;
    edges.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
        uint32_t v[3];
        bool valid = true;
        for (int k = 0; k < 3; ++k) {
            const uint32_t index = mesh.triangles[t + k];
            valid = valid && index < ids.size();
            v[k] = valid ? ids[index] : 0;
        }
        if (!valid || v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = std::min(v[k], v[(k + 1) % 3]);
            const uint32_t b = std::max(v[k], v[(k + 1) % 3]);
            edges.push_back(uint64_t(a) << 32 | b);
        }
    }
    std::sort(edges.begin(), edges.end());
    EdgeCounts counts;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) ++counts.boundary;
        if (j - i > 2) ++counts.nonManifold;
        i = j;
    }
    return counts;
}

/// Squared distance from @p p to the triangle @p a @p b @p c.
/// \see Ericson, "Real-Time Collision Detection", 2005, section 5.1.5 (ClosestPtPointTriangle).
double squaredDistanceToTriangle(const openvdb::Vec3d& p, const openvdb::Vec3d& a,
                                 const openvdb::Vec3d& b, const openvdb::Vec3d& c) {
    const openvdb::Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.lengthSqr();  // vertex a
    const openvdb::Vec3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.lengthSqr();  // vertex b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge ab
        return (ap - (d1 / (d1 - d3)) * ab).lengthSqr();
    }
    const openvdb::Vec3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.lengthSqr();  // vertex c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge ac
        return (ap - (d2 / (d2 - d6)) * ac).lengthSqr();
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge bc
        return (bp - ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)).lengthSqr();
    }
    const double denom = va + vb + vc;  // inside the face
    if (!(denom > 0)) return std::min({ap.lengthSqr(), bp.lengthSqr(), cp.lengthSqr()});
    return (ap - (vb / denom) * ab - (vc / denom) * ac).lengthSqr();
}

double triangleArea(const TriangleMesh& mesh, std::size_t t) {
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
        const float* v = &mesh.positions[3 * std::size_t(mesh.triangles[3 * t + k])];
        p[k] = {v[0], v[1], v[2]};
    }
    return 0.5 * length(cross(p[1] - p[0], p[2] - p[0]));
}

/// @brief Makes every active voxel's distance exact to the triangles near it.
/// meshToVolume finds each voxel's closest triangle by handing it on from the voxels
/// next to it, layer by layer, and can settle on one that is not the closest: on a
/// sphere up to 0.6 voxel off near the surface and a voxel deep inside, which turns the
/// gradient by tens of degrees. Each pass gives every voxel the exact distance to the
/// closest of the triangles closest to it and to its 26 neighbours (the sign kept),
/// sweeping each leaf forward, then backward on the next pass (as fast sweeping does),
/// and passes repeat on the leaves next to a change of more than 1% of a voxel (a few
/// passes, at most kMaxPasses). A leaf reads its own voxels as updated and the others'
/// from a copy taken before the pass: the result is the same for any number of threads.
/// @param points  index space (as meshToVolume had them)
/// @param scale   world units per index unit
void refineDistances(FloatTree& dist, IndexTree& index, const std::vector<openvdb::Vec3s>& points,
                     const std::vector<openvdb::Vec3I>& triangles, double scale, bool isSigned) {
    constexpr int kMaxPasses = 16;
    // A change smaller than this does not wake the neighbours: deep inside a round solid
    // many triangles are all but equally far, and chasing their last digits would take
    // passes without end.
    const float tolerance = float(0.01 * scale);
    std::vector<LeafNode*> leaves;
    dist.getNodes(leaves);
    std::vector<IndexLeaf*> indexLeaves(leaves.size());
    for (std::size_t n = 0; n < leaves.size(); ++n) {
        indexLeaves[n] = index.probeLeaf(leaves[n]->origin());
    }
    std::vector<char> dirty(leaves.size(), 1), changed(leaves.size(), 0);
    const int32_t polygons = int32_t(triangles.size());
    // Each triangle's bounding sphere (centroid, radius): a triangle whose sphere is
    // farther than the best so far is skipped without the exact distance.
    std::vector<openvdb::Vec4d> spheres(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const openvdb::Vec3d a = points[triangles[t][0]], b = points[triangles[t][1]],
                             c = points[triangles[t][2]];
        const openvdb::Vec3d centroid = (a + b + c) / 3.0;
        const double radius = std::sqrt(std::max(
            {(a - centroid).lengthSqr(), (b - centroid).lengthSqr(), (c - centroid).lengthSqr()}));
        spheres[t] = openvdb::Vec4d(centroid.x(), centroid.y(), centroid.z(), radius);
    }
    for (int pass = 0; pass < kMaxPasses; ++pass) {
        const IndexTree before(index);
        std::fill(changed.begin(), changed.end(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 8), [&](const auto& r) {
            openvdb::tree::ValueAccessor<const IndexTree, false> near(before);
            int32_t candidates[27];
            for (std::size_t n = r.begin(); n < r.end(); ++n) {
                if (!dirty[n] || !indexLeaves[n]) continue;
                LeafNode& leaf = *leaves[n];
                IndexLeaf& indexLeaf = *indexLeaves[n];
                const openvdb::Coord origin = leaf.origin();
                for (int step = 0; step < int(LeafNode::SIZE); ++step) {
                    // Forward on even passes, backward on odd ones (as in fast sweeping).
                    const openvdb::Index pos =
                        openvdb::Index(pass % 2 == 0 ? step : int(LeafNode::SIZE) - 1 - step);
                    if (!leaf.isValueOn(pos)) continue;
                    const openvdb::Coord local = LeafNode::offsetToLocalCoord(pos);
                    const openvdb::Coord ijk = origin + local;
                    int count = 0;
                    for (int dx = -1; dx <= 1; ++dx) {
                        for (int dy = -1; dy <= 1; ++dy) {
                            for (int dz = -1; dz <= 1; ++dz) {
                                const openvdb::Coord q = local.offsetBy(dx, dy, dz);
                                const bool inLeaf = (unsigned(q.x()) | unsigned(q.y()) |
                                                     unsigned(q.z())) < LeafNode::DIM;
                                // This leaf as updated so far; others as they were.
                                const int32_t k =
                                    inLeaf ? indexLeaf.getValue(LeafNode::coordToOffset(q))
                                           : near.getValue(origin + q);
                                if (k >= 0 && k < polygons &&
                                    std::find(candidates, candidates + count, k) ==
                                        candidates + count) {
                                    candidates[count++] = k;
                                }
                            }
                        }
                    }
                    if (count == 0) continue;
                    // The voxel's own triangle first: most often still the closest.
                    const int32_t own = indexLeaf.getValue(pos);
                    int32_t* ownAt = std::find(candidates, candidates + count, own);
                    if (ownAt != candidates + count) std::swap(candidates[0], *ownAt);
                    const openvdb::Vec3d p(ijk.x(), ijk.y(), ijk.z());
                    double best = std::numeric_limits<double>::max();
                    int32_t closest = -1;
                    for (int c = 0; c < count; ++c) {
                        const openvdb::Vec4d& sphere = spheres[std::size_t(candidates[c])];
                        const double beyond =
                            (p - openvdb::Vec3d(sphere.x(), sphere.y(), sphere.z())).length() -
                            sphere.w();
                        if (beyond > 0 && beyond * beyond >= best) continue;
                        const openvdb::Vec3I& t = triangles[std::size_t(candidates[c])];
                        const double d2 =
                            squaredDistanceToTriangle(p, points[t[0]], points[t[1]], points[t[2]]);
                        if (d2 < best) best = d2, closest = candidates[c];
                    }
                    const float d = float(std::sqrt(best) * scale);
                    const float old = leaf.getValue(pos);
                    if (std::abs(std::abs(old) - d) > tolerance) changed[n] = 1;
                    leaf.setValueOnly(pos, isSigned && old < 0 ? -d : d);
                    indexLeaf.setValueOnly(pos, closest);
                }
            }
        });
        // Next pass: the leaves within a voxel of a change.
        std::unordered_set<openvdb::Coord> changedOrigins;
        for (std::size_t n = 0; n < leaves.size(); ++n) {
            if (changed[n]) changedOrigins.insert(leaves[n]->origin());
        }
        if (changedOrigins.empty()) break;
        constexpr int kDim = int(LeafNode::DIM);
        for (std::size_t n = 0; n < leaves.size(); ++n) {
            dirty[n] = 0;
            const openvdb::Coord origin = leaves[n]->origin();
            for (int dx = -kDim; dx <= kDim && !dirty[n]; dx += kDim) {
                for (int dy = -kDim; dy <= kDim && !dirty[n]; dy += kDim) {
                    for (int dz = -kDim; dz <= kDim && !dirty[n]; dz += kDim) {
                        dirty[n] = changedOrigins.count(origin.offsetBy(dx, dy, dz)) > 0;
                    }
                }
            }
        }
    }
}

}  // namespace

bool isClosedMesh(const TriangleMesh& mesh) {
    const EdgeCounts counts = countEdges(mesh);
    return counts.boundary == 0 && counts.nonManifold == 0;
}

struct MeshSdf::Grid {
    double invVoxelSize = 0;  // 1 / world units
    double reach = 0;         // world units
    double offset = 0;        // subtracted from the grid's values: thickness / 2
    double background = 0;    // phi beyond the band, world units
    // Index-space box outside which every value is the background: cells wholly outside
    // it are answered without a lookup. Doubles, so that far points compare before
    // anything is cast to int. Empty: lo > hi.
    double lo[3] = {kHuge, kHuge, kHuge}, hi[3] = {-kHuge, -kHuge, -kHuge};
    // The grid as bricks, instead of the OpenVDB tree (its root map, internal nodes and
    // leaves: a lookup per corner): for each 8^3 block of voxels in the box, grown by a
    // block each way, a brick of 9^3 values, the block and the voxels one above it in x,
    // y and z, so the 8 corners of any cell whose lowest corner lies in the block are in
    // one brick. Blocks wholly of one value (the background, the inside of a large
    // solid) share one brick.
    static constexpr int kBlock = 8;           // voxels along a block's edge
    static constexpr int kBrick = kBlock + 1;  // values along a brick's edge
    static constexpr int kBrickSize = kBrick * kBrick * kBrick;
    int blockOrigin[3] = {0, 0, 0};    // index coordinate of the first block's first voxel
    int blockDims[3] = {0, 0, 0};      // blocks along x, y, z
    std::vector<const float*> bricks;  // per block: x * 81 + y * 9 + z
    std::vector<float> values;         // the bricks of varying values
    std::vector<float> constants;      // the shared bricks, one per constant value

    std::size_t slot(int bx, int by, int bz) const {
        return (std::size_t(bx) * std::size_t(blockDims[1]) + std::size_t(by)) *
                   std::size_t(blockDims[2]) +
               std::size_t(bz);
    }

    static constexpr double kHuge = 1e300;

    /// Fills the box, the table and the bricks from @p tree.
    void buildBricks(const FloatTree& tree);
};

void MeshSdf::Grid::buildBricks(const FloatTree& tree) {
    Grid& g = *this;
    static_assert(int(LeafNode::DIM) == kBlock, "blocks are the tree's leaves");
    const float background = tree.background();
    // Where anything but the background lies: every leaf, and tiles of other values.
    openvdb::CoordBBox box;
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) box.expand(leaf->getNodeBoundingBox());
    auto tile = tree.cbeginValueAll();
    tile.setMaxDepth(FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
    for (; tile; ++tile) {
        if (*tile != background) box.expand(tile.getBoundingBox());
    }
    if (box.empty()) return;
    for (int a = 0; a < 3; ++a) {
        g.lo[a] = box.min()[a];
        g.hi[a] = box.max()[a];
        // The box is whole leaves; one block more each way holds the corners of cells
        // that overlap the box only in part.
        g.blockOrigin[a] = box.min()[a] - kBlock;
        g.blockDims[a] = (box.max()[a] - box.min()[a] + 1) / kBlock + 2;
    }
    const std::size_t blockCount =
        std::size_t(g.blockDims[0]) * std::size_t(g.blockDims[1]) * std::size_t(g.blockDims[2]);
    const auto origin = [&](std::size_t slot) {
        const int bz = int(slot % std::size_t(g.blockDims[2]));
        const int by = int(slot / std::size_t(g.blockDims[2]) % std::size_t(g.blockDims[1]));
        const int bx = int(slot / (std::size_t(g.blockDims[2]) * std::size_t(g.blockDims[1])));
        return openvdb::Coord(g.blockOrigin[0] + bx * kBlock, g.blockOrigin[1] + by * kBlock,
                              g.blockOrigin[2] + bz * kBlock);
    };

    // A brick is constant where its block and the 7 blocks above it hold no leaf and
    // one and the same tile value; the rest get bricks of their own.
    std::vector<int64_t> brick(blockCount);  // >= 0: own brick number; < 0: -1 - constant
    std::vector<float> constantValues;
    std::size_t ownBricks = 0;
    {
        openvdb::tree::ValueAccessor<const FloatTree, false> accessor(tree);
        for (std::size_t slot = 0; slot < blockCount; ++slot) {
            const openvdb::Coord o = origin(slot);
            bool constant = true;
            const float value = accessor.getValue(o);
            for (int n = 0; n < 8 && constant; ++n) {
                const openvdb::Coord c =
                    o.offsetBy(kBlock * (n & 1), kBlock * (n >> 1 & 1), kBlock * (n >> 2));
                constant = !accessor.probeConstLeaf(c) && accessor.getValue(c) == value;
            }
            if (!constant) {
                brick[slot] = int64_t(ownBricks++);
                continue;
            }
            auto it = std::find(constantValues.begin(), constantValues.end(), value);
            if (it == constantValues.end()) it = constantValues.insert(it, value);
            brick[slot] = -1 - int64_t(it - constantValues.begin());
        }
    }
    g.constants.resize(constantValues.size() * kBrickSize);
    for (std::size_t c = 0; c < constantValues.size(); ++c) {
        std::fill_n(g.constants.begin() + std::ptrdiff_t(c * kBrickSize), kBrickSize,
                    constantValues[c]);
    }
    g.values.resize(ownBricks * kBrickSize);
    g.bricks.resize(blockCount);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blockCount, 64), [&](const auto& r) {
        openvdb::tree::ValueAccessor<const FloatTree, false> accessor(tree);
        for (std::size_t slot = r.begin(); slot < r.end(); ++slot) {
            if (brick[slot] < 0) {
                g.bricks[slot] = &g.constants[std::size_t(-1 - brick[slot]) * kBrickSize];
                continue;
            }
            float* out = &g.values[std::size_t(brick[slot]) * kBrickSize];
            g.bricks[slot] = out;
            const openvdb::Coord o = origin(slot);
            const LeafNode* leaf = accessor.probeConstLeaf(o);
            const float* leafValues = leaf ? leaf->buffer().data() : nullptr;
            for (int x = 0; x < kBrick; ++x) {
                for (int y = 0; y < kBrick; ++y) {
                    for (int z = 0; z < kBrick; ++z) {
                        const bool inBlock = x < kBlock && y < kBlock && z < kBlock;
                        out[(x * kBrick + y) * kBrick + z] =
                            inBlock && leafValues ? leafValues[(x * kBlock + y) * kBlock + z]
                                                  : accessor.getValue(o.offsetBy(x, y, z));
                    }
                }
            }
        }
    });
}

MeshSdf::MeshSdf(const TriangleMesh& mesh, double voxelSize, double thickness, double reach,
                 const std::string& name)
    : mVoxelSize(voxelSize) {
    const std::string who = "mesh " + quoteForMessage(name);
    const auto fail = [&](const std::string& what) { throw SceneError(who + ": " + what); };
    if (!(std::isfinite(voxelSize) && voxelSize > 0)) {
        fail("voxel_size " + numberForMessage(voxelSize) + " is not a positive number");
    }
    if (!(std::isfinite(thickness) && thickness >= 0)) {
        fail("thickness " + numberForMessage(thickness) + " is not a number >= 0");
    }
    if (!(std::isfinite(reach) && reach >= 0)) {
        fail("contact reach " + numberForMessage(reach) + " is not a number >= 0");
    }
    if (mesh.empty()) fail("has no triangles");
    if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0) {
        fail("its arrays are not whole xyz triples");
    }
    for (uint32_t index : mesh.triangles) {
        if (index >= mesh.vertexCount()) {
            fail("a triangle names vertex " + std::to_string(index) + " of " +
                 std::to_string(mesh.vertexCount()));
        }
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        if (!std::isfinite(mesh.positions[i])) {
            fail("vertex " + std::to_string(i / 3 + 1) + " is not finite");
        }
    }
    double area = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) area += triangleArea(mesh, t);
    if (!(area > 0)) fail("has no area (every triangle is degenerate)");
    if (thickness > 0 && thickness < 2 * voxelSize) {
        fail("thickness " + numberForMessage(thickness) + " is less than two voxels (voxel_size " +
             numberForMessage(voxelSize) +
             "): the shell could leak; give a smaller voxel_size or a larger thickness");
    }

    // The solid's bounds, and the grid's: the band reaches (reach + 2 voxels) beyond them.
    Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
            std::numeric_limits<double>::max()};
    Vec3 hi = -1.0 * lo;
    for (uint32_t index : mesh.triangles) {
        const float* v = &mesh.positions[3 * std::size_t(index)];
        lo = {std::min(lo.x, double(v[0])), std::min(lo.y, double(v[1])),
              std::min(lo.z, double(v[2]))};
        hi = {std::max(hi.x, double(v[0])), std::max(hi.y, double(v[1])),
              std::max(hi.z, double(v[2]))};
    }
    const double halfThickness = 0.5 * thickness;
    mBoundsMin = lo - Vec3{halfThickness, halfThickness, halfThickness};
    mBoundsMax = hi + Vec3{halfThickness, halfThickness, halfThickness};
    const double bandVoxels = std::ceil((reach + halfThickness) / voxelSize) + 2;
    double voxels = 1;
    double farthest = 0;  // index units
    for (double Vec3::*axis : {&Vec3::x, &Vec3::y, &Vec3::z}) {
        voxels *= (hi.*axis - lo.*axis) / voxelSize + 2 * bandVoxels + 1;
        farthest = std::max({farthest, std::abs(lo.*axis), std::abs(hi.*axis)});
    }
    farthest = farthest / voxelSize + bandVoxels;
    if (voxels > kMaxVoxels) {
        fail("a grid of voxel_size " + numberForMessage(voxelSize) + " would have " +
             numberForMessage(std::round(voxels)) + " voxels (at most " +
             numberForMessage(kMaxVoxels) + "): give a larger voxel_size");
    }
    constexpr double kMaxIndex = 1e9;  // voxel coordinates are 32-bit integers
    if (farthest > kMaxIndex) {
        fail("lies " + numberForMessage(std::round(farthest)) +
             " voxels from its origin at voxel_size " + numberForMessage(voxelSize) + " (at most " +
             numberForMessage(kMaxIndex) +
             "): give a larger voxel_size, or coordinates nearer the origin");
    }
    if (thickness == 0) {
        const EdgeCounts edges = countEdges(mesh);
        if (edges.boundary > 0) {
            fail("is not closed (" + std::to_string(edges.boundary) +
                 " edges lie on one triangle only): give the collider a thickness, or close "
                 "the mesh");
        }
        if (edges.nonManifold > 0) {
            fail("is not closed (" + std::to_string(edges.nonManifold) +
                 " edges lie on three or more triangles): give the collider a thickness, or "
                 "mend the mesh");
        }
    }

    // OpenVDB wants index-space points (world / voxelSize, voxel centres at integers).
    // The copy is a one-off; QuadAndTriangleDataAdapter<Vec3s, Vec3I> is the adapter
    // libopenvdb instantiates, so this file does not compile meshToVolume itself.
    initializeVdb();
    std::vector<openvdb::Vec3s> points(mesh.vertexCount());
    for (std::size_t v = 0; v < points.size(); ++v) {
        for (int a = 0; a < 3; ++a) points[v][a] = float(mesh.positions[3 * v + a] / voxelSize);
    }
    std::vector<openvdb::Vec3I> triangles(mesh.triangleCount());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        triangles[t] = openvdb::Vec3I(mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                                      mesh.triangles[3 * t + 2]);
    }
    const openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(
        points, triangles);
    const openvdb::math::Transform::Ptr transform =
        openvdb::math::Transform::createLinearTransform(voxelSize);
    openvdb::util::NullInterrupter interrupter;
    // Signed: the interior band to infinity fills the whole inside with distances.
    // Renormalisation (an eikonal smoothing against bumps from self-intersections) is
    // left out: refineDistances() then sets every distance to an exact one anyway.
    const int flags = thickness > 0 ? openvdb::tools::UNSIGNED_DISTANCE_FIELD
                                    : openvdb::tools::DISABLE_RENORMALIZATION;
    openvdb::Int32Grid polygonIndex(-1);
    openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
        interrupter, adapter, *transform, float(bandVoxels), std::numeric_limits<float>::max(),
        flags, &polygonIndex);
    refineDistances(grid->tree(), polygonIndex.tree(), points, triangles, voxelSize,
                    thickness == 0);
    polygonIndex.clear();

    mGrid = std::make_unique<Grid>();
    Grid& g = *mGrid;
    g.invVoxelSize = 1.0 / voxelSize;
    g.reach = reach;
    g.offset = halfThickness;
    g.background = double(grid->background()) - halfThickness;
    g.buildBricks(grid->constTree());
}

MeshSdf::~MeshSdf() = default;
MeshSdf::MeshSdf(MeshSdf&&) noexcept = default;
MeshSdf& MeshSdf::operator=(MeshSdf&&) noexcept = default;

double MeshSdf::background() const { return mGrid->background; }

std::size_t MeshSdf::memoryBytes() const {
    const Grid& g = *mGrid;
    return sizeof(*this) + sizeof(Grid) + g.bricks.size() * sizeof(float*) +
           (g.values.size() + g.constants.size()) * sizeof(float);
}

SurfaceSample MeshSdf::sample(Vec3 local) const {
    const Grid& g = *mGrid;
    const double p[3] = {local.x * g.invVoxelSize, local.y * g.invVoxelSize,
                         local.z * g.invVoxelSize};
    // The cell [i, i + 1]^3 around p; one wholly outside the box is background (NaN too).
    double base[3];
    for (int a = 0; a < 3; ++a) {
        base[a] = std::floor(p[a]);
        if (!(base[a] + 1 >= g.lo[a] && base[a] <= g.hi[a])) return {g.background, {0, 1, 0}};
    }
    // The cell's brick, and its lowest corner in it.
    int block[3], inBrick = 0;
    for (int a = 0; a < 3; ++a) {
        const int i = int(base[a]) - g.blockOrigin[a];  // >= 0: the table has a margin
        block[a] = i / Grid::kBlock;
        inBrick = inBrick * Grid::kBrick + i % Grid::kBlock;
    }
    const float* corner = g.bricks[g.slot(block[0], block[1], block[2])] + inBrick;
    float v[2][2][2];  // corner values v[dx][dy][dz]
    for (int dx = 0; dx < 2; ++dx) {
        for (int dy = 0; dy < 2; ++dy) {
            for (int dz = 0; dz < 2; ++dz) {
                v[dx][dy][dz] = corner[(dx * Grid::kBrick + dy) * Grid::kBrick + dz];
            }
        }
    }

    // Trilinear interpolation, and the gradient of the same trilinear function.
    const double fx = p[0] - base[0], fy = p[1] - base[1], fz = p[2] - base[2];
    double c[2][2];  // interpolated along z
    for (int dx = 0; dx < 2; ++dx) {
        for (int dy = 0; dy < 2; ++dy) {
            c[dx][dy] = v[dx][dy][0] + fz * (double(v[dx][dy][1]) - v[dx][dy][0]);
        }
    }
    const double c0 = c[0][0] + fy * (c[0][1] - c[0][0]);  // x = 0
    const double c1 = c[1][0] + fy * (c[1][1] - c[1][0]);  // x = 1
    const double phi = c0 + fx * (c1 - c0) - g.offset;     // the grid holds world units
    if (phi > g.reach) return {phi, {0, 1, 0}};

    const double gx = c1 - c0;
    const double gy = (1 - fx) * (c[0][1] - c[0][0]) + fx * (c[1][1] - c[1][0]);
    double dz[2][2];
    for (int dx = 0; dx < 2; ++dx) {
        for (int dy = 0; dy < 2; ++dy) dz[dx][dy] = double(v[dx][dy][1]) - v[dx][dy][0];
    }
    const double gz = (1 - fx) * ((1 - fy) * dz[0][0] + fy * dz[0][1]) +
                      fx * ((1 - fy) * dz[1][0] + fy * dz[1][1]);
    return {phi, normalized({gx, gy, gz})};
}

}  // namespace globular
