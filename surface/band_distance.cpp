// The narrow-band level set of the metaball field's iso surface, computed directly from
// the field (no polygonisation): sub-voxel distances where the field crosses the iso
// value, then closest points carried outward one voxel layer at a time.
//
//   1. inside = voxels whose field value exceeds the iso value; interface = voxels with
//      a face neighbour on the other side (masks per leaf: leaf_masks.h).
//   2. Each interface voxel gets the foot point of the iso surface's local plane: the
//      plane perpendicular to the field's gradient (central differences) through the
//      crossing on the axis most nearly along the gradient, theta = (f - iso)/(f - f_n)
//      voxels away (linear interpolation, the crossing volumeToMesh uses). Planes
//      through the axis intercepts alone (OpenVDB's fast-sweeping start,
//      1/sqrt(sum 1/theta^2)) overestimate by up to 0.4 voxel where the normal is
//      diagonal and only some axes cross within a voxel.
//   3. Layer k (voxels at Chebyshev distance k from the interface, k = 1..band)
//      takes, among the surface samples its face neighbours of layer k - 1 took (edge
//      and corner neighbours where no face neighbour has one), the one nearest to
//      itself (closest-point propagation). A sample is a small disk on the
//      tangent plane at an interface voxel's foot point: point samples a voxel apart
//      overestimate by up to 0.4 voxel between them, whole tangent planes underestimate
//      by voxels near creases. Each layer reads only finished layers, so the result does
//      not depend on the thread count.
//   4. Negative inside; voxels within the band are active, the rest are
//      +-background; signedFloodFill signs the tiles.
//
// Cost: proportional to the band (a few voxels either side of the surface), where
// levelSetRebuild meshes the iso surface and scan-converts every polygon.
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "leaf_masks.h"
#include "surface_grids.h"

namespace globular {

namespace {

using openvdb::Coord;
using openvdb::FloatGrid;
using FloatLeaf = openvdb::FloatTree::LeafNodeType;
constexpr int kDim = int(FloatLeaf::DIM);
constexpr int kVoxels = int(FloatLeaf::SIZE);
constexpr uint8_t kUnknown = 255;
static_assert(LeafSet::kDim == kDim, "masks and float leaves must align");

int voxelIndex(int x, int y, int z) { return (x << 6) | (y << 3) | z; }

/// The band's leaves in Coord order, each with its 27 neighbour leaves, its voxels of
/// each layer and its inside voxels; per voxel the layer that reached it and the
/// interface voxel whose surface sample is nearest (relative coordinates, voxels).
/// Interface voxels are their own source; their sample is the offset to their foot
/// point on the surface, along the normal there, kept only for leaves that hold
/// interface voxels.
struct Band {
    struct Voxels {
        int8_t source[3][kVoxels];
        uint8_t layer[kVoxels];
    };
    struct Samples {
        int16_t offset[3][kVoxels];  ///< voxels * kOffsetScale; |offset| <= 1 voxel
    };
    static constexpr float kOffsetScale = 16384.0f;

    std::vector<Coord> origins;
    std::vector<std::array<int32_t, 27>> neighbours;  ///< index or -1; (dx+1)*9+(dy+1)*3+dz+1
    std::vector<std::vector<LeafBits>> layers;        ///< [layer][leaf]
    std::vector<LeafBits> inside;
    std::unique_ptr<Voxels[]> voxels;
    /// The level set's leaves, one per band leaf: distances (voxels, unsigned) as the
    /// layers find them, signed and scaled at the end.
    std::vector<std::unique_ptr<FloatLeaf>> out;
    std::vector<int32_t> sampleSlot;  ///< per leaf, index into samples or -1
    std::unique_ptr<Samples[]> samples;

    int32_t find(const Coord& origin) const {
        auto it = std::lower_bound(origins.begin(), origins.end(), origin);
        return it != origins.end() && *it == origin ? int32_t(it - origins.begin()) : -1;
    }
    /// The leaf holding local coordinates (x, y, z) of leaf @p i, which may lie in a
    /// neighbour (or further, for bands wider than 6 voxels); -1 outside the band.
    /// @p v receives the voxel's index in that leaf.
    int32_t locate(std::size_t i, int x, int y, int z, int& v) const {
        v = voxelIndex(x & (kDim - 1), y & (kDim - 1), z & (kDim - 1));
        const int lx = x >> 3, ly = y >> 3, lz = z >> 3;  // floor division by 8
        if (lx >= -1 && lx <= 1 && ly >= -1 && ly <= 1 && lz >= -1 && lz <= 1) {
            return neighbours[i][std::size_t((lx + 1) * 9 + (ly + 1) * 3 + lz + 1)];
        }
        return find(origins[i] + Coord(lx * kDim, ly * kDim, lz * kDim));
    }
    /// Distance (voxels) from voxel (x, y, z) of leaf @p i to the sample of the interface
    /// voxel @p s voxels away from it.
    float distanceToSample(std::size_t i, int x, int y, int z, const int s[3]) const;
};

/// A sample is a disk of this radius (voxels) on the tangent plane at its foot point:
/// samples lie about a voxel apart, so points between them are within half a voxel of
/// one laterally. Point samples would overestimate distances by up to 0.4 voxel there;
/// whole tangent planes underestimate by voxels near creases.
constexpr float kSampleRadius = 0.5f;

inline float Band::distanceToSample(std::size_t i, int x, int y, int z,
                                   const int s[3]) const {
    int v;
    const int32_t leaf = locate(i, x + s[0], y + s[1], z + s[2], v);
    const Samples& sample = samples[std::size_t(sampleSlot[std::size_t(leaf)])];
    const float o[3] = {float(sample.offset[0][v]) / kOffsetScale,
                        float(sample.offset[1][v]) / kOffsetScale,
                        float(sample.offset[2][v]) / kOffsetScale};
    // This voxel relative to the foot point, and the unit normal there (none for a voxel
    // on the surface: then the sample is a point).
    const float w[3] = {-float(s[0]) - o[0], -float(s[1]) - o[1], -float(s[2]) - o[2]};
    const float length = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
    const float inverse = length > 0 ? 1.0f / length : 0.0f;
    const float along = (w[0] * o[0] + w[1] * o[1] + w[2] * o[2]) * inverse;
    const float length2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    const float lateral = std::sqrt(std::max(0.0f, length2 - along * along));
    if (lateral <= kSampleRadius) return std::abs(along);
    const float beyond = lateral - kSampleRadius;
    return std::sqrt(beyond * beyond + along * along);
}

/// The field's inside voxels (value above @p iso), over the leaves that hold some and
/// their face neighbours (where the interface's outer side may lie).
struct InsideVoxels {
    LeafSet leaves;
    std::vector<LeafBits> inside;
};

InsideVoxels insideVoxels(const FloatGrid& field, float iso) {
    openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(field.tree());
    std::vector<LeafBits> bits(leaves.leafCount());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount(), 64), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const float* v = leaves.leaf(i).buffer().data();
            for (int x = 0; x < 8; ++x) {
                uint64_t word = 0;
                for (int b = 0; b < 64; ++b) word |= uint64_t(v[x * 64 + b] > iso) << b;
                bits[i].word[std::size_t(x)] = word;
            }
        }
    });
    std::vector<Coord> origins;
    for (std::size_t i = 0; i < bits.size(); ++i) {
        if (!bits[i].any()) continue;
        const Coord o = leaves.leaf(i).origin();
        origins.push_back(o);
        for (int a = 0; a < 3; ++a) {
            for (int side : {-kDim, kDim}) {
                Coord n = o;
                n[a] += side;
                origins.push_back(n);
            }
        }
    }
    InsideVoxels result{LeafSet(std::move(origins)), {}};
    result.inside.resize(result.leaves.size());
    for (std::size_t i = 0; i < bits.size(); ++i) {
        if (!bits[i].any()) continue;
        result.inside[std::size_t(result.leaves.find(leaves.leaf(i).origin()))] = bits[i];
    }
    return result;
}

/// Layers 0 (the interface) to @p layerCount of the band, over the leaves within
/// @p layerCount voxels of the interface's; layer k holds the voxels at Chebyshev
/// distance k from the interface.
struct BandLayers {
    LeafSet leaves;
    std::vector<std::vector<LeafBits>> layers;  ///< [layer][leaf]
};

BandLayers bandLayers(const InsideVoxels& in, int layerCount) {
    const std::vector<LeafBits> interface = interfaceOf(in.inside, in.leaves.faces());
    const int ring = (layerCount + kDim - 1) / kDim;
    std::vector<Coord> near;
    for (std::size_t i = 0; i < interface.size(); ++i) {
        if (!interface[i].any()) continue;
        for (int dx = -ring; dx <= ring; ++dx) {
            for (int dy = -ring; dy <= ring; ++dy) {
                for (int dz = -ring; dz <= ring; ++dz) {
                    near.push_back(in.leaves.origin(i).offsetBy(dx * kDim, dy * kDim, dz * kDim));
                }
            }
        }
    }
    BandLayers band{LeafSet(std::move(near)), {}};
    const LeafSet::Faces faces = band.leaves.faces();
    auto& layers = band.layers;
    layers.emplace_back(band.leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.leaves.size(), 256), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const int32_t j = in.leaves.find(band.leaves.origin(i));
            if (j >= 0) layers[0][i] = interface[std::size_t(j)];
        }
    });
    for (int k = 1; k <= layerCount; ++k) {
        std::vector<LeafBits> next = dilateByOneVoxel(layers[std::size_t(k - 1)], faces);
        for (std::size_t i = 0; i < next.size(); ++i) {
            for (std::size_t x = 0; x < 8; ++x) {
                uint64_t& w = next[i].word[x];
                w &= ~layers[std::size_t(k - 1)][i].word[x];
                if (k >= 2) w &= ~layers[std::size_t(k - 2)][i].word[x];
            }
        }
        layers.push_back(std::move(next));
    }
    return band;
}

/// The band over the leaves of @p layers that hold band voxels; samples for those with
/// interface voxels.
Band makeBand(const BandLayers& layers, const InsideVoxels& in) {
    Band band;
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < layers.leaves.size(); ++i) {
        bool any = false;
        for (const auto& layer : layers.layers) any |= layer[i].any();
        if (any) kept.push_back(i);
    }
    const std::size_t n = kept.size();
    band.origins.resize(n);
    band.layers.assign(layers.layers.size(), std::vector<LeafBits>(n));
    band.inside.resize(n);
    band.neighbours.resize(n);
    band.sampleSlot.assign(n, -1);
    int32_t slots = 0;
    for (std::size_t i = 0; i < n; ++i) {
        band.origins[i] = layers.leaves.origin(kept[i]);
        for (std::size_t k = 0; k < layers.layers.size(); ++k) {
            band.layers[k][i] = layers.layers[k][kept[i]];
        }
        if (band.layers[0][i].any()) band.sampleSlot[i] = slots++;
    }
    // Not value-initialised: every value is written before it is read but the layers,
    // filled below.
    band.voxels.reset(new Band::Voxels[n]);
    band.out.resize(n);
    band.samples.reset(new Band::Samples[std::size_t(slots)]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            int k = 0;
            for (int dx = -1; dx <= 1; ++dx) {
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dz = -1; dz <= 1; ++dz) {
                        band.neighbours[i][std::size_t(k++)] =
                            band.find(band.origins[i] + Coord(dx * kDim, dy * kDim, dz * kDim));
                    }
                }
            }
            const int32_t j = in.leaves.find(band.origins[i]);
            if (j >= 0) band.inside[i] = in.inside[std::size_t(j)];
            std::fill(std::begin(band.voxels[i].layer), std::end(band.voxels[i].layer), kUnknown);
            band.out[i] = std::make_unique<FloatLeaf>(band.origins[i], 0.0f, false);
        }
    });
    return band;
}

/// Layer 0: the foot point of the local plane through the iso crossing of each
/// interface voxel.
void footOnInterface(const FloatGrid& field, float iso, Band& band) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.origins.size(), 16), [&](auto r) {
        auto acc = field.getConstAccessor();
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            if (band.sampleSlot[i] < 0) continue;
            Band::Voxels& voxels = band.voxels[i];
            Band::Samples& sample = band.samples[std::size_t(band.sampleSlot[i])];
            float* distance = band.out[i]->buffer().data();
            band.layers[0][i].forEach([&](int v) {
                const Coord local = FloatLeaf::offsetToLocalCoord(openvdb::Index(v));
                const Coord ijk = band.origins[i] + local;
                const float f = acc.getValue(ijk);
                const bool in = f > iso;
                float gradient[3];   // central differences, voxel units
                float theta[3];      // distance to the nearer crossing along each axis
                float direction[3];  // +-1 towards it, 0 where the axis does not cross
                bool onSurface = false;
                for (int a = 0; a < 3; ++a) {
                    float around[2];
                    theta[a] = INFINITY;
                    direction[a] = 0;
                    for (int s = 0; s < 2; ++s) {
                        Coord n = ijk;
                        n[a] += 2 * s - 1;
                        const float fn = around[s] = acc.getValue(n);
                        if ((fn > iso) == in) continue;
                        const float t = (f - iso) / (f - fn);  // in [0, 1]
                        onSurface |= !(t > 0);
                        if (t < theta[a]) theta[a] = t, direction[a] = float(2 * s - 1);
                    }
                    gradient[a] = 0.5f * (around[1] - around[0]);
                }
                const float length = std::sqrt(gradient[0] * gradient[0] +
                                               gradient[1] * gradient[1] +
                                               gradient[2] * gradient[2]);
                float offset[3] = {0, 0, 0};
                if (onSurface) {
                    // The foot point is the voxel itself.
                } else if (length > 0) {
                    // The plane through the crossing on the axis most nearly along the
                    // normal, perpendicular to the gradient; the foot lies towards larger
                    // values from outside, smaller from inside.
                    int best = -1;
                    for (int a = 0; a < 3; ++a) {
                        if (direction[a] != 0 &&
                            (best < 0 || std::abs(gradient[a]) > std::abs(gradient[best]))) {
                            best = a;
                        }
                    }
                    const float d = theta[best] * std::abs(gradient[best]) / length;
                    const float toward = in ? -d / length : d / length;
                    for (int a = 0; a < 3; ++a) offset[a] = toward * gradient[a];
                } else {
                    // A flat spot: the plane through the axis crossings instead.
                    float sum = 0;
                    for (int a = 0; a < 3; ++a) {
                        if (direction[a] != 0) sum += 1 / (theta[a] * theta[a]);
                    }
                    for (int a = 0; a < 3; ++a) {
                        if (direction[a] != 0) offset[a] = direction[a] / theta[a] / sum;
                    }
                }
                for (int a = 0; a < 3; ++a) {
                    sample.offset[a][v] = int16_t(std::lround(offset[a] * Band::kOffsetScale));
                    voxels.source[a][v] = 0;
                }
                const int zero[3] = {0, 0, 0};
                distance[v] = band.distanceToSample(i, local.x(), local.y(), local.z(), zero);
                voxels.layer[v] = 0;
            });
        }
    });
}

/// The 26 neighbour offsets, faces first, then edges, then corners.
struct NeighbourOffsets {
    int d[26][3];
    NeighbourOffsets() {
        int n = 0;
        for (int manhattan = 1; manhattan <= 3; ++manhattan) {
            for (int dx = -1; dx <= 1; ++dx) {
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dz = -1; dz <= 1; ++dz) {
                        if (std::abs(dx) + std::abs(dy) + std::abs(dz) != manhattan) continue;
                        d[n][0] = dx, d[n][1] = dy, d[n][2] = dz;
                        ++n;
                    }
                }
            }
        }
    }
};

/// Layer k: each voxel takes, among the samples its neighbours of layer k - 1 took, the
/// one nearest to itself.
void footFromNeighbours(uint8_t k, Band& band) {
    static const NeighbourOffsets offsets;
    const std::vector<LeafBits>& layer = band.layers[k];
    const std::vector<LeafBits>& previous = band.layers[std::size_t(k - 1)];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.origins.size(), 16), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            if (!layer[i].any()) continue;
            // Per face neighbour, the voxels whose neighbour there is of layer k - 1, the
            // only finished layer a face neighbour can be of (neighbours' Chebyshev
            // distances differ by one at most): bits of whole leaves, where reading each
            // neighbour's layer missed the cache and the branch predictor.
            LeafBits finishedFace[6];
            for (int nb = 0; nb < 6; ++nb) {
                const int* d = offsets.d[nb];
                const int axis = d[0] != 0 ? 0 : d[1] != 0 ? 1 : 2;
                const int32_t n =
                    band.neighbours[i][std::size_t((d[0] + 1) * 9 + (d[1] + 1) * 3 + d[2] + 1)];
                finishedFace[nb] = neighbourBits(
                    previous[i], n >= 0 ? &previous[std::size_t(n)] : nullptr, axis, d[axis]);
            }
            Band::Voxels& voxels = band.voxels[i];
            float* distance = band.out[i]->buffer().data();
            layer[i].forEach([&](int voxel) {
                const Coord p = FloatLeaf::offsetToLocalCoord(openvdb::Index(voxel));
                float best = INFINITY;
                int bestSource[3] = {0, 0, 0};
                int tried[26];  // sources already measured: neighbours often share one
                int triedCount = 0;
                for (int nb = 0; nb < 26; ++nb) {
                    // The face neighbours' samples suffice (the tests measure 0.03 voxel more
                    // error than with all 26, at a third of the time); edges and corners
                    // only where no face neighbour has one.
                    if (nb < 6 && !finishedFace[nb].test(voxel)) continue;
                    if (nb >= 6 && triedCount > 0) break;
                    const int* d = offsets.d[nb];
                    int v;
                    const int32_t n = band.locate(i, p.x() + d[0], p.y() + d[1], p.z() + d[2], v);
                    if (n < 0) continue;
                    const Band::Voxels& from = band.voxels[std::size_t(n)];
                    if (nb >= 6 && from.layer[v] >= k) continue;
                    const int s[3] = {d[0] + from.source[0][v], d[1] + from.source[1][v],
                                      d[2] + from.source[2][v]};
                    const int key = ((s[0] + 64) << 14) | ((s[1] + 64) << 7) | (s[2] + 64);
                    bool seen = false;
                    for (int t = 0; t < triedCount; ++t) seen |= tried[t] == key;
                    if (seen) continue;
                    tried[triedCount++] = key;
                    const float distance = band.distanceToSample(i, p.x(), p.y(), p.z(), s);
                    if (distance < best) {
                        best = distance;
                        for (int a = 0; a < 3; ++a) bestSource[a] = s[a];
                    }
                }
                for (int a = 0; a < 3; ++a) voxels.source[a][voxel] = int8_t(bestSource[a]);
                distance[voxel] = best;
            });
        }
    });
    // Marked only now, so that no voxel of this layer read another of the same layer.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.origins.size(), 64), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            Band::Voxels& voxels = band.voxels[i];
            layer[i].forEach([&](int voxel) { voxels.layer[voxel] = k; });
        }
    });
}

}  // namespace

FloatGrid::Ptr fieldToLevelSet(const FloatGrid& field, double isoValue, double bandWidth) {
    const float iso = float(isoValue);
    const float h = float(field.voxelSize()[0]);
    const float background = float(bandWidth) * h;

    auto levelSet = FloatGrid::create(background);
    levelSet->setTransform(field.transform().copy());
    levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
    levelSet->setName("surface");

    const InsideVoxels inside = insideVoxels(field, iso);
    // A voxel closer than bandWidth to the surface lies within Chebyshev distance
    // ceil(bandWidth) of an interface voxel: the cell holding its nearest surface point
    // has interface voxels at its corners, within 1 of that point along each axis.
    const int layerCount = int(std::ceil(bandWidth));
    Band band = makeBand(bandLayers(inside, layerCount), inside);
    if (band.origins.empty()) return levelSet;

    footOnInterface(field, iso, band);
    for (int k = 1; k <= layerCount; ++k) footFromNeighbours(uint8_t(k), band);

    // Distances, signed by the inside mask; active within the band.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.origins.size(), 64), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const LeafBits& in = band.inside[i];
            const Band::Voxels& voxels = band.voxels[i];
            FloatLeaf& leaf = *band.out[i];
            float* values = leaf.buffer().data();
            bool any = false;
            for (int v = 0; v < kVoxels; ++v) {
                const float sign = in.test(v) ? -1.0f : 1.0f;
                const float d = voxels.layer[v] != kUnknown ? values[v] : float(bandWidth);
                if (d < float(bandWidth)) {
                    values[v] = sign * d * h;
                    leaf.setValueOn(openvdb::Index(v));
                    any = true;
                } else {
                    values[v] = sign * background;
                }
            }
            if (!any) band.out[i].reset();
        }
    });
    auto& tree = levelSet->tree();
    for (auto& leaf : band.out) {
        if (leaf) tree.addLeaf(leaf.release());
    }
    openvdb::tools::signedFloodFill(tree);
    openvdb::tools::pruneLevelSet(tree);
    return levelSet;
}

}  // namespace globular
