#pragma once
// Voxel masks the size of an OpenVDB leaf (8^3 bits) over a sparse, sorted set of leaves,
// and the morphology the narrow band needs (band_distance.cpp): the voxels with a face
// neighbour on the other side of a set, and a set grown by one voxel in all 26 directions.
// Word-parallel: a leaf is eight 64-bit words, one per x, with bit (y << 3) | z (OpenVDB's
// own voxel order), so a step along z or y is a shift within the words and one along x
// is the next word; across a leaf's faces the bits come from the neighbour leaf.
// OpenVDB's MaskTree morphology did this job before at over half the band's cost, most of
// it in copying trees and allocating their internal nodes (docs/performance.md).

#include <openvdb/Types.h>

#include <array>
#include <cstdint>
#include <vector>

namespace globular {

/// One leaf's voxels as bits: voxel (x, y, z) (local, 0..7) is bit (x << 6) | (y << 3) | z.
struct LeafBits {
    std::array<uint64_t, 8> word{};

    bool any() const {
        uint64_t all = 0;
        for (uint64_t w : word) all |= w;
        return all != 0;
    }
    bool test(int voxel) const { return (word[std::size_t(voxel >> 6)] >> (voxel & 63)) & 1u; }
    void set(int voxel) { word[std::size_t(voxel >> 6)] |= uint64_t(1) << (voxel & 63); }

    /// Calls visit(voxel) for each voxel set, in increasing order.
    template <typename Visit>
    void forEach(Visit&& visit) const {
        for (int x = 0; x < 8; ++x) {
            for (uint64_t w = word[std::size_t(x)]; w != 0; w &= w - 1) {
                visit((x << 6) | __builtin_ctzll(w));
            }
        }
    }
};

/// A set of leaf origins (multiples of the leaf size), sorted, with lookups.
class LeafSet {
  public:
    static constexpr int kDim = 8;

    /// The set of @p origins, in any order, duplicates allowed.
    explicit LeafSet(std::vector<openvdb::Coord> origins);

    std::size_t size() const { return origins_.size(); }
    const openvdb::Coord& origin(std::size_t i) const { return origins_[i]; }
    const std::vector<openvdb::Coord>& origins() const { return origins_; }
    /// The index of the leaf at @p origin, or -1.
    int32_t find(const openvdb::Coord& origin) const;

    /// Each leaf's six face neighbours: index or -1, in the order -x, +x, -y, +y, -z, +z.
    using Faces = std::vector<std::array<int32_t, 6>>;
    Faces faces() const;

  private:
    std::vector<openvdb::Coord> origins_;
};

/// What each voxel of a leaf with mask @p m sees one step away along @p axis (0 = x) in
/// direction @p dir (-1 or +1): bit v of the result is bit v + dir e_axis of @p m, or of
/// @p beyond (the leaf on that side; null: none, all off) past the face.
LeafBits neighbourBits(const LeafBits& m, const LeafBits* beyond, int axis, int dir);

/// The voxels with a face neighbour on the other side of @p inside (masks of a set's
/// leaves, @p faces its face neighbours), on both sides. Voxels of leaves outside the set
/// are outside; the result's voxels in such leaves are not kept, so the set must hold
/// every leaf next to one with inside voxels.
std::vector<LeafBits> interfaceOf(const std::vector<LeafBits>& inside, const LeafSet::Faces& faces);

/// @p mask grown by one voxel in all 26 directions, kept to the set's leaves.
std::vector<LeafBits> dilateByOneVoxel(const std::vector<LeafBits>& mask,
                                       const LeafSet::Faces& faces);

}  // namespace globular
