#include "leaf_masks.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace globular {

namespace {

using openvdb::Coord;

constexpr uint64_t kZ0 = 0x0101010101010101ull;  // the bits with z = 0 in every word
constexpr uint64_t kZ7 = kZ0 << 7;               // and with z = 7

}  // namespace

LeafBits neighbourBits(const LeafBits& m, const LeafBits* beyond, int axis, int dir) {
    static const LeafBits none;
    const LeafBits& b = beyond ? *beyond : none;
    LeafBits out;
    for (std::size_t x = 0; x < 8; ++x) {
        const uint64_t w = m.word[x];
        switch (axis * 2 + (dir > 0)) {
            case 0:
                out.word[x] = x > 0 ? m.word[x - 1] : b.word[7];
                break;
            case 1:
                out.word[x] = x < 7 ? m.word[x + 1] : b.word[0];
                break;
            case 2:
                out.word[x] = (w << 8) | (b.word[x] >> 56);
                break;
            case 3:
                out.word[x] = (w >> 8) | (b.word[x] << 56);
                break;
            case 4:
                out.word[x] = ((w << 1) & ~kZ0) | ((b.word[x] >> 7) & kZ0);
                break;
            default:
                out.word[x] = ((w >> 1) & ~kZ7) | ((b.word[x] << 7) & kZ7);
                break;
        }
    }
    return out;
}

namespace {

/// The neighbour leaf of @p masks on face @p f (LeafSet::Faces order), or null.
const LeafBits* onFace(const std::vector<LeafBits>& masks, const std::array<int32_t, 6>& faces,
                       int f) {
    return faces[std::size_t(f)] >= 0 ? &masks[std::size_t(faces[std::size_t(f)])] : nullptr;
}

template <typename Body>
void forEachLeaf(std::size_t n, Body&& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) body(i);
    });
}

/// @p mask grown by one voxel both ways along @p axis.
std::vector<LeafBits> dilateAlong(const std::vector<LeafBits>& mask, const LeafSet::Faces& faces,
                                  int axis) {
    std::vector<LeafBits> out(mask.size());
    forEachLeaf(mask.size(), [&](std::size_t i) {
        const LeafBits below = neighbourBits(mask[i], onFace(mask, faces[i], 2 * axis), axis, -1);
        const LeafBits above =
            neighbourBits(mask[i], onFace(mask, faces[i], 2 * axis + 1), axis, +1);
        for (std::size_t x = 0; x < 8; ++x)
            out[i].word[x] = mask[i].word[x] | below.word[x] | above.word[x];
    });
    return out;
}

}  // namespace

LeafSet::LeafSet(std::vector<Coord> origins) : origins_(std::move(origins)) {
    std::sort(origins_.begin(), origins_.end());
    origins_.erase(std::unique(origins_.begin(), origins_.end()), origins_.end());
}

int32_t LeafSet::find(const Coord& origin) const {
    const auto it = std::lower_bound(origins_.begin(), origins_.end(), origin);
    return it != origins_.end() && *it == origin ? int32_t(it - origins_.begin()) : -1;
}

LeafSet::Faces LeafSet::faces() const {
    Faces faces(origins_.size());
    forEachLeaf(origins_.size(), [&](std::size_t i) {
        const Coord& o = origins_[i];
        // Sorted by x, then y, then z: the z neighbours, if there, are next to it.
        faces[i][4] = i > 0 && origins_[i - 1] == o.offsetBy(0, 0, -kDim) ? int32_t(i - 1) : -1;
        faces[i][5] = i + 1 < origins_.size() && origins_[i + 1] == o.offsetBy(0, 0, kDim)
                          ? int32_t(i + 1)
                          : -1;
        faces[i][0] = find(o.offsetBy(-kDim, 0, 0));
        faces[i][1] = find(o.offsetBy(kDim, 0, 0));
        faces[i][2] = find(o.offsetBy(0, -kDim, 0));
        faces[i][3] = find(o.offsetBy(0, kDim, 0));
    });
    return faces;
}

std::vector<LeafBits> interfaceOf(const std::vector<LeafBits>& inside,
                                  const LeafSet::Faces& faces) {
    std::vector<LeafBits> out(inside.size());
    forEachLeaf(inside.size(), [&](std::size_t i) {
        // Grown by the face neighbours, less shrunk by them: a voxel that differs from one.
        LeafBits grown = inside[i], shrunk = inside[i];
        for (int f = 0; f < 6; ++f) {
            const LeafBits seen =
                neighbourBits(inside[i], onFace(inside, faces[i], f), f / 2, f % 2 ? +1 : -1);
            for (std::size_t x = 0; x < 8; ++x) {
                grown.word[x] |= seen.word[x];
                shrunk.word[x] &= seen.word[x];
            }
        }
        for (std::size_t x = 0; x < 8; ++x) out[i].word[x] = grown.word[x] & ~shrunk.word[x];
    });
    return out;
}

std::vector<LeafBits> dilateByOneVoxel(const std::vector<LeafBits>& mask,
                                       const LeafSet::Faces& faces) {
    // The 3x3x3 neighbourhood is the product of three 1-D ones: three passes, each over
    // the previous one's result (its neighbours' included).
    return dilateAlong(dilateAlong(dilateAlong(mask, faces, 2), faces, 1), faces, 0);
}

}  // namespace globular
