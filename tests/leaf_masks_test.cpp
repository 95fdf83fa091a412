// Leaf-sized voxel masks and their morphology (surface/leaf_masks.h) against the
// definitions, voxel by voxel, on random sparse sets that cross leaf faces, edges and
// corners at negative and positive coordinates.
#include "leaf_masks.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

namespace globular {
namespace {

using openvdb::Coord;

Coord leafOf(const Coord& voxel) { return Coord(voxel.x() & ~7, voxel.y() & ~7, voxel.z() & ~7); }

int voxelIndex(const Coord& voxel) {
    return ((voxel.x() & 7) << 6) | ((voxel.y() & 7) << 3) | (voxel.z() & 7);
}

/// Random voxels in [-12, 20)^3 (leaves -16..16 on each axis), each on with @p chance,
/// plus a solid 6x6x6 block, so that inside voxels have inside neighbours too.
std::set<Coord> randomVoxels(double chance, unsigned seed) {
    std::mt19937 random(seed);
    std::bernoulli_distribution on(chance);
    std::set<Coord> voxels;
    for (int x = -12; x < 20; ++x) {
        for (int y = -12; y < 20; ++y) {
            for (int z = -12; z < 20; ++z) {
                const bool block = x >= 5 && x < 11 && y >= -3 && y < 3 && z >= 5 && z < 11;
                if (block || on(random)) voxels.insert(Coord(x, y, z));
            }
        }
    }
    return voxels;
}

/// The leaves of @p voxels and all their neighbours within @p ring leaves.
LeafSet leavesAround(const std::set<Coord>& voxels, int ring) {
    std::vector<Coord> origins;
    for (const Coord& v : voxels) {
        for (int dx = -ring; dx <= ring; ++dx) {
            for (int dy = -ring; dy <= ring; ++dy) {
                for (int dz = -ring; dz <= ring; ++dz) {
                    origins.push_back(leafOf(v).offsetBy(8 * dx, 8 * dy, 8 * dz));
                }
            }
        }
    }
    return LeafSet(std::move(origins));
}

std::vector<LeafBits> masksOf(const std::set<Coord>& voxels, const LeafSet& leaves) {
    std::vector<LeafBits> masks(leaves.size());
    for (const Coord& v : voxels) masks[std::size_t(leaves.find(leafOf(v)))].set(voxelIndex(v));
    return masks;
}

/// How @p masks (over @p leaves) compare with @p expected(voxel) on every voxel of the
/// leaves: the voxels set, and those where the two differ.
struct Agreement {
    std::size_t on = 0, wrong = 0;
};

template <typename Expected>
Agreement compare(const LeafSet& leaves, const std::vector<LeafBits>& masks, Expected&& expected) {
    Agreement result;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        for (int x = 0; x < 8; ++x) {
            for (int y = 0; y < 8; ++y) {
                for (int z = 0; z < 8; ++z) {
                    const Coord v = leaves.origin(i).offsetBy(x, y, z);
                    const bool bit = masks[i].test(voxelIndex(v));
                    result.on += bit;
                    result.wrong += bit != expected(v);
                }
            }
        }
    }
    return result;
}

TEST(LeafMasks, SetIsSortedWithoutDuplicatesAndFindsItsLeaves) {
    const LeafSet leaves({Coord(8, 0, 0), Coord(-8, 0, 0), Coord(8, 0, 0), Coord(0, -8, 8)});
    ASSERT_EQ(leaves.size(), 3u);
    EXPECT_EQ(leaves.origin(0), Coord(-8, 0, 0));
    EXPECT_EQ(leaves.find(Coord(8, 0, 0)), 2);
    EXPECT_EQ(leaves.find(Coord(0, 0, 0)), -1);
    const LeafSet::Faces faces = leaves.faces();
    EXPECT_EQ(faces[0][1], -1);  // (0, 0, 0) is not in the set
    const LeafSet row(
        {Coord(0, 0, -8), Coord(0, 0, 0), Coord(0, 0, 8), Coord(0, 8, 0), Coord(-8, 0, 0)});
    const auto rowFaces = row.faces();
    const std::size_t middle = std::size_t(row.find(Coord(0, 0, 0)));
    EXPECT_EQ(rowFaces[middle][0], row.find(Coord(-8, 0, 0)));
    EXPECT_EQ(rowFaces[middle][1], -1);
    EXPECT_EQ(rowFaces[middle][2], -1);
    EXPECT_EQ(rowFaces[middle][3], row.find(Coord(0, 8, 0)));
    EXPECT_EQ(rowFaces[middle][4], row.find(Coord(0, 0, -8)));
    EXPECT_EQ(rowFaces[middle][5], row.find(Coord(0, 0, 8)));
}

TEST(LeafMasks, InterfaceIsTheVoxelsWithAFaceNeighbourOnTheOtherSide) {
    for (const double chance : {0.02, 0.3, 0.7}) {
        const std::set<Coord> inside = randomVoxels(chance, 11);
        const LeafSet leaves = leavesAround(inside, 1);
        const std::vector<LeafBits> interface =
            interfaceOf(masksOf(inside, leaves), leaves.faces());
        const Agreement a = compare(leaves, interface, [&](const Coord& v) {
            const bool in = inside.count(v) > 0;
            bool differs = false;
            for (int axis = 0; axis < 3; ++axis) {
                for (int side : {-1, 1}) {
                    Coord n = v;
                    n[axis] += side;
                    differs |= (inside.count(n) > 0) != in;
                }
            }
            return differs;
        });
        EXPECT_GT(a.on, 100u) << chance;
        EXPECT_EQ(a.wrong, 0u) << chance;
    }
}

TEST(LeafMasks, DilationByOneVoxelTakesAll26Neighbours) {
    for (const double chance : {0.002, 0.05}) {
        const std::set<Coord> voxels = randomVoxels(chance, 5);
        const LeafSet leaves = leavesAround(voxels, 1);
        const std::vector<LeafBits> grown =
            dilateByOneVoxel(masksOf(voxels, leaves), leaves.faces());
        const Agreement a = compare(leaves, grown, [&](const Coord& v) {
            bool near = false;
            for (int dx = -1; dx <= 1; ++dx) {
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dz = -1; dz <= 1; ++dz)
                        near |= voxels.count(v.offsetBy(dx, dy, dz)) > 0;
                }
            }
            return near;
        });
        EXPECT_GT(a.on, voxels.size()) << chance;
        EXPECT_EQ(a.wrong, 0u) << chance;
    }
}

TEST(LeafMasks, ForEachVisitsTheVoxelsSetInOrder) {
    LeafBits bits;
    for (int v : {511, 0, 63, 64, 200}) bits.set(v);
    std::vector<int> seen;
    bits.forEach([&](int v) { seen.push_back(v); });
    EXPECT_EQ(seen, (std::vector<int>{0, 63, 64, 200, 511}));
    EXPECT_TRUE(bits.any());
    EXPECT_FALSE(LeafBits{}.any());
}

}  // namespace
}  // namespace globular
