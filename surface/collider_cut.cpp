// Cutting the colliders' solids out of the liquid's level set (collider_cut.h).
#include "collider_cut.h"

#include <openvdb/tools/Composite.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "errors.h"

namespace globular {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::FloatGrid;

namespace {

using LeafT = FloatGrid::TreeType::LeafNodeType;
constexpr int kLeafDim = int(LeafT::DIM);  // 8 voxels

/// One leaf-aligned block of a solid's grid: a leaf of values, or (null) a tile deep inside.
struct Block {
    Coord origin;
    std::unique_ptr<LeafT> leaf;
};

Vec3 worldAt(const openvdb::math::Transform& xform, const openvdb::Vec3d& index) {
    const openvdb::Vec3d w = xform.indexToWorld(index);
    return {w.x(), w.y(), w.z()};
}

bool finitePose(const Pose& pose) {
    for (const auto& row : pose.rotation) {
        for (double v : row) {
            if (!std::isfinite(v)) return false;
        }
    }
    return std::isfinite(pose.translation.x) && std::isfinite(pose.translation.y) &&
           std::isfinite(pose.translation.z);
}

/// @p region clipped to the index-space bounds of @p solid's box where it is placed, grown
/// by @p grow voxels; empty when they miss. An unbounded solid leaves @p region as it is.
CoordBBox clipToSolid(const CoordBBox& region, const PlacedSolid& solid,
                      const openvdb::math::Transform& xform, int grow) {
    if (!solid.solid->bounded()) return region;
    const Vec3 lo = solid.solid->boundsMin(), hi = solid.solid->boundsMax();
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    openvdb::Vec3d indexLo(kInfinity), indexHi(-kInfinity);
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 local{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                         corner & 4 ? hi.z : lo.z};
        const Vec3 world = solid.pose.toWorld(local);
        const openvdb::Vec3d index = xform.worldToIndex(openvdb::Vec3d(world.x, world.y, world.z));
        indexLo = openvdb::math::minComponent(indexLo, index);
        indexHi = openvdb::math::maxComponent(indexHi, index);
    }
    // Clamp in double before converting, so a solid far larger than the liquid cannot
    // overflow the coordinates.
    Coord min, max;
    for (int axis = 0; axis < 3; ++axis) {
        const double a = std::floor(indexLo[axis]) - grow, b = std::ceil(indexHi[axis]) + grow;
        if (b < region.min()[axis] || a > region.max()[axis]) return CoordBBox();  // empty
        min[axis] = std::max(region.min()[axis], openvdb::Int32(std::max(a, -2e9)));
        max[axis] = std::min(region.max()[axis], openvdb::Int32(std::min(b, 2e9)));
    }
    return CoordBBox(min, max);
}

}  // namespace

FloatGrid::Ptr solidLevelSet(const PlacedSolid& solid, const FloatGrid& like,
                             const CoordBBox& region) {
    const float background = like.background();
    FloatGrid::Ptr grid = FloatGrid::create(background);
    grid->setTransform(like.transform().copy());
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    if (region.empty()) return grid;

    const openvdb::math::Transform& xform = like.transform();
    const double voxel = like.voxelSize()[0];  // world units
    // A block's voxel centres lie within 3.5 sqrt(3) voxels of its centre; phi is
    // 1-Lipschitz, so a block whose centre is farther than this plus the band from the
    // surface holds no voxel of the band. Half a voxel more for rounding.
    const double reach = 4.0 * std::sqrt(3.0) * voxel + double(background);

    // Leaf-aligned blocks covering the region, gathered row by row (x runs along a row).
    const Coord first = region.min() & ~(kLeafDim - 1);
    const Coord last = region.max() & ~(kLeafDim - 1);
    const int nx = (last.x() - first.x()) / kLeafDim + 1;
    const int ny = (last.y() - first.y()) / kLeafDim + 1;
    const int nz = (last.z() - first.z()) / kLeafDim + 1;
    std::vector<std::vector<Block>> rows(std::size_t(ny) * std::size_t(nz));

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 1), [&](const auto& range) {
        auto liquid = like.getConstAccessor();
        for (std::size_t row = range.begin(); row != range.end(); ++row) {
            const int y = first.y() + int(row % std::size_t(ny)) * kLeafDim;
            const int z = first.z() + int(row / std::size_t(ny)) * kLeafDim;
            for (int ix = 0; ix < nx; ++ix) {
                const Coord origin(first.x() + ix * kLeafDim, y, z);
                // Where the liquid is an outside tile, liquid minus solid is that tile.
                if (!liquid.probeConstLeaf(origin) && liquid.getValue(origin) > 0) continue;

                const double half = 0.5 * (kLeafDim - 1);
                const double centrePhi =
                    solid.sample(worldAt(xform, origin.asVec3d() + openvdb::Vec3d(half))).phi;
                if (centrePhi > reach) continue;  // outside the solid and its band
                if (centrePhi < -reach) {         // inside, beyond the band: a tile
                    rows[row].push_back({origin, nullptr});
                    continue;
                }
                auto leaf = std::make_unique<LeafT>(origin, background, false);
                bool touched = false;
                for (openvdb::Index n = 0; n < LeafT::SIZE; ++n) {
                    const Coord ijk = leaf->offsetToGlobalCoord(n);
                    const double phi = solid.sample(worldAt(xform, ijk.asVec3d())).phi;
                    if (phi >= background) continue;  // the background already
                    touched = true;
                    if (phi <= -background) {
                        leaf->setValueOff(n, -background);
                    } else {
                        leaf->setValueOn(n, float(phi));
                    }
                }
                if (touched) rows[row].push_back({origin, std::move(leaf)});
            }
        }
    });

    // Blocks are disjoint, so the tree does not depend on the order they go in.
    auto& tree = grid->tree();
    for (auto& row : rows) {
        for (Block& block : row) {
            if (block.leaf) {
                tree.addLeaf(block.leaf.release());
            } else {
                tree.addTile(/*level=*/1, block.origin, -background, /*active=*/false);
            }
        }
    }
    return grid;
}

void subtractColliders(FloatGrid& levelSet, const std::vector<PlacedSolid>& solids) {
    for (const PlacedSolid& solid : solids) {
        if (!solid.solid) throw Error("subtractColliders: a placed solid without a solid");
        if (!finitePose(solid.pose)) {
            throw SimulationError("subtractColliders: a collider's pose is not finite");
        }
    }
    if (solids.empty() || levelSet.activeVoxelCount() == 0) return;

    // The narrow band surrounds the liquid's interior, so its active bounds hold all of the
    // liquid; grown by the band, they hold every voxel whose value the cut can change.
    const double voxel = levelSet.voxelSize()[0];
    const int band = int(std::ceil(double(levelSet.background()) / voxel)) + 1;
    CoordBBox liquid = levelSet.evalActiveVoxelBoundingBox();
    liquid.expand(band);

    for (const PlacedSolid& solid : solids) {
        const CoordBBox region = clipToSolid(liquid, solid, levelSet.transform(), band);
        if (region.empty()) continue;
        FloatGrid::Ptr cut = solidLevelSet(solid, levelSet, region);
        if (cut->tree().empty()) continue;
        // max(liquid, -solid) per voxel, tiles included, then pruneLevelSet: inactive
        // leaves of one sign become tiles, so the result is again a valid level set.
        openvdb::tools::csgDifference(levelSet, *cut, /*prune=*/true);
    }
}

}  // namespace globular
