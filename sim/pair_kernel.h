#pragma once
// The force loop's inner kernels, in three passes:
//   1. collectGroupCandidates, once per grid cell: the globules of the cell's runs within
//      reach of the bounding box of the cell's members, copied into one short array (a
//      crowded cell's parts then filter their own from it: force_kernels.cpp, GroupParts);
//   2. collectNeighbors, per member: those candidates within the pair's reach, compacted
//      into a NeighborBatch of relative positions and V.P;
//   3. sumBatch, per member: eq. (2)-(5) summed over the batch, every lane useful.
// With AVX-512, integer exponents and a uniform radius, passes 2 and 3 are one
// (CandidateLanes, sumCandidatesWith): the force summed over the candidates, the lanes
// that are no neighbours masked out; there the compaction cost more than the force on
// those lanes. There each pair is also evaluated once: a member sums over the candidates
// after it in grid order and leaves the opposite forces in Reactions (each_pair_once.h).
// The grid hands about five candidates for each one within reach, so testing them cheaply
// and evaluating the force only for the rest is what makes the loop fast. With AVX-512
// the passes use 16 lanes (compress for the compaction, rsqrt14 + one Newton step for
// 1/D); with AVX2 8 lanes (a table-driven permutation for the compaction, simd_lanes.h,
// and rsqrt + one Newton step); elsewhere they are plain loops. Every build gives the
// same neighbours in the same order.
// The arithmetic is PairForce::accumulate's, to single-precision rounding.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "pair_force.h"
#include "simd_lanes.h"

namespace globular {

/// Read-only view of globule arrays (struct of arrays), in neighbour-grid order.
/// Thermal scenes also pass the temperatures, which then travel with the candidates
/// (thermal_kernel.h).
struct GlobuleArrays {
    const float *x, *y, *z, *vx, *vy, *vz, *radius;
    const float* temperature = nullptr;
    /// Each entry's globule, where the arrays are a copy (GroupCandidates); null: entry j
    /// is globule j.
    const uint32_t* index = nullptr;
};

/// One globule's neighbours within reach: P = x_i - x_j, V.P with V = v_i - v_j (all the
/// drag needs of the velocities: one array instead of three) and r_i + r_j.
struct NeighborBatch {
    static constexpr uint32_t kPadding = 16;  ///< vector stores write up to 16 past count
    std::vector<float> dx, dy, dz, vDotP, radiusSum;
    float uniformSum = 0;  ///< r_i + r_j of every neighbour, or 0: see radiusSum
    uint32_t count = 0;
    std::vector<float> temperature;  ///< thermal scenes (collectNeighbors<true>)

    /// Room for @p candidates entries.
    void reserve(std::size_t candidates) {
        for (auto* a : {&dx, &dy, &dz, &vDotP, &radiusSum, &temperature}) {
            if (a->size() < candidates + kPadding) a->resize(candidates + kPadding);
        }
    }
};

/// The candidates shared by a group of globules (the members of one grid cell): the
/// globules of the cell's runs within reach of the group's bounding box, copied
/// contiguously. Each member then tests one short array instead of the nine runs (about
/// two thirds as many candidates).
struct GroupCandidates {
    static constexpr uint32_t kPadding = 16;  ///< vector stores write up to 16 past count
    std::vector<float> x, y, z, vx, vy, vz, radius;
    bool uniformRadius = false;  ///< all globules share one radius: `radius` is not kept
    /// Each candidate's globule is kept in `index` (the loop that evaluates each pair once
    /// adds the opposite force to it, force_kernels.cpp).
    bool indexed = false;
    uint32_t count = 0;
    std::vector<float> temperature;  ///< thermal scenes (GlobuleArrays::temperature)
    std::vector<uint32_t> index;
    /// With `indexed`, on the AVX-512 path: where the entries came from, block by block:
    /// the places [at, at + 16) of the source arrays, and which of them were kept. The
    /// opposite forces go back the same way (force_kernels.cpp, addBack).
    struct Source {
        uint32_t at;
        uint16_t kept;
    };
    std::vector<Source> sources;
    uint32_t sourceCount = 0;

    /// No entries.
    void clear() {
        count = 0;
        sourceCount = 0;
    }

    /// Room for @p candidates entries.
    void reserve(std::size_t candidates) {
        if (x.size() >= candidates + kPadding) return;
        for (auto* a : {&x, &y, &z, &vx, &vy, &vz, &radius, &temperature}) {
            a->resize(candidates + kPadding);
        }
        index.resize(candidates + kPadding);
        sources.resize(candidates + 1);  // each kept block keeps one entry at least
    }
};

#if defined(__AVX512F__)
/// Sixteen globules from @p j of @p s: their positions, and which of the first @p left lie
/// within reach (@p reach2 squared) of the box [@p lo, @p hi].
struct NearBox {
    __m512 x, y, z;
    __mmask16 near;
};

inline NearBox nearBox(const GlobuleArrays& s, uint32_t j, uint32_t left, const float lo[3],
                       const float hi[3], __m512 reach2) {
    const __m512 zero = _mm512_setzero_ps();
    const auto outside = [&](__m512 v, int axis) {  // distance from the box along an axis
        return _mm512_max_ps(zero, _mm512_max_ps(_mm512_sub_ps(_mm512_set1_ps(lo[axis]), v),
                                                 _mm512_sub_ps(v, _mm512_set1_ps(hi[axis]))));
    };
    const __mmask16 live = firstLanes(left);
    NearBox b;
    b.x = _mm512_maskz_loadu_ps(live, s.x + j);
    b.y = _mm512_maskz_loadu_ps(live, s.y + j);
    b.z = _mm512_maskz_loadu_ps(live, s.z + j);
    const __m512 ex = outside(b.x, 0), ey = outside(b.y, 1), ez = outside(b.z, 2);
    const __m512 d2 = _mm512_fmadd_ps(ez, ez, _mm512_fmadd_ps(ey, ey, _mm512_mul_ps(ex, ex)));
    b.near = _mm512_mask_cmp_ps_mask(live, d2, reach2, _CMP_LE_OQ);
    return b;
}

/// The lanes among the first @p left (at most 16 used) whose material is @p want.
inline __mmask16 materialMask(const uint8_t* material, uint32_t left, uint8_t want) {
#if defined(__AVX512BW__) && defined(__AVX512VL__)
    const __m512i m = _mm512_cvtepu8_epi32(_mm_maskz_loadu_epi8(firstLanes(left), material));
    return _mm512_cmpeq_epi32_mask(m, _mm512_set1_epi32(want));
#else
    __mmask16 mask = 0;
    for (uint32_t l = 0; l < 16 && l < left; ++l) mask |= __mmask16(material[l] == want) << l;
    return mask;
#endif
}

/// The globules of entries [j, j + 16) of @p s (GlobuleArrays::index), in the lanes of
/// @p live.
inline __m512i indicesAt(const GlobuleArrays& s, uint32_t j, __mmask16 live) {
    if (s.index) return _mm512_maskz_loadu_epi32(live, s.index + j);
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    return _mm512_add_epi32(_mm512_set1_epi32(int(j)), lane);
}
#elif defined(__AVX2__)
/// nearBox for eight globules: their positions, and which of the first @p left lie within
/// reach of the box, as a movemask. The globule arrays have no padding: the last step's
/// loads are masked (load).
struct NearBox8 {
    uint32_t j, left;
    __m256i live;
    __m256 x, y, z;
    unsigned near;

    /// Eight values of @p from at j; in the last step, those past the end are 0, not read.
    __m256 load(const float* from) const {
        return left >= 8 ? _mm256_loadu_ps(from + j) : _mm256_maskload_ps(from + j, live);
    }
};

inline NearBox8 nearBox8(const GlobuleArrays& s, uint32_t j, uint32_t left, const float lo[3],
                         const float hi[3], __m256 reach2) {
    const __m256 zero = _mm256_setzero_ps();
    const auto outside = [&](__m256 v, int axis) {  // distance from the box along an axis
        return _mm256_max_ps(zero, _mm256_max_ps(_mm256_sub_ps(_mm256_set1_ps(lo[axis]), v),
                                                 _mm256_sub_ps(v, _mm256_set1_ps(hi[axis]))));
    };
    NearBox8 b{j, left, firstLanes8(left), {}, {}, {}, 0};
    b.x = b.load(s.x);
    b.y = b.load(s.y);
    b.z = b.load(s.z);
    const __m256 ex = outside(b.x, 0), ey = outside(b.y, 1), ez = outside(b.z, 2);
    const __m256 d2 = _mm256_fmadd_ps(ez, ez, _mm256_fmadd_ps(ey, ey, _mm256_mul_ps(ex, ex)));
    b.near = unsigned(_mm256_movemask_ps(
        _mm256_and_ps(_mm256_cmp_ps(d2, reach2, _CMP_LE_OQ), _mm256_castsi256_ps(b.live))));
    return b;
}

/// The lanes among the first @p left (at most 8 used) whose material is @p want, as a
/// movemask.
inline unsigned materialMask8(const uint8_t* material, uint32_t left, uint8_t want) {
    int64_t bytes = 0;
    std::memcpy(&bytes, material, left >= 8 ? 8 : left);
    const __m256i m = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(bytes));
    const __m256i same = _mm256_cmpeq_epi32(m, _mm256_set1_epi32(want));
    const unsigned lanes = left >= 8 ? 0xFFu : (1u << left) - 1;
    return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(same))) & lanes;
}

/// Stores at @p to, in order, the globules of those entries [j, j + 8) of @p s
/// (GlobuleArrays::index) set in @p keep (a movemask).
inline void keepIndices(const GlobuleArrays& s, uint32_t j, unsigned keep, uint32_t* to) {
    for (uint32_t lane = 0; keep; ++lane, keep >>= 1) {
        if (keep & 1u) *to++ = s.index ? s.index[j + lane] : j + lane;
    }
}
#endif

/// Appends to @p out the globules j in [begin, end) of @p s within @p reach of the box
/// [@p lo, @p hi]; with @p material, only those whose material[j] is @p want (several
/// materials: one candidate list per material). @p out has room for them.
inline void collectGroupCandidates(const GlobuleArrays& s, uint32_t begin, uint32_t end,
                                   const float lo[3], const float hi[3], float reach,
                                   GroupCandidates& out, const uint8_t* material = nullptr,
                                   uint8_t want = 0) {
    uint32_t count = out.count;
    const float reach2 = reach * reach;
#if defined(__AVX512F__)
    // Locals, not members: the vector stores below may alias anything, so members would
    // be reloaded on every pass.
    const GlobuleArrays from = s;
    float *ox = out.x.data(), *oy = out.y.data(), *oz = out.z.data();
    float *ovx = out.vx.data(), *ovy = out.vy.data(), *ovz = out.vz.data();
    float *oradius = out.uniformRadius ? nullptr : out.radius.data();
    float* otemperature = from.temperature ? out.temperature.data() : nullptr;
    uint32_t* oindex = out.indexed ? out.index.data() : nullptr;
    GroupCandidates::Source* source = out.sources.data() + out.sourceCount;
    const __m512 reach2v = _mm512_set1_ps(reach2);
    for (uint32_t j = begin; j < end; j += 16) {
        const uint32_t left = end - j;
        const NearBox box = nearBox(from, j, left, lo, hi, reach2v);
        __mmask16 near = box.near;
        if (material) near &= materialMask(material + j, left, want);
        const auto keep = [&](float* to, __m512 v) {
            _mm512_storeu_ps(to + count, _mm512_maskz_compress_ps(near, v));
        };
        const auto keepFrom = [&](float* to, const float* values) {
            keep(to, _mm512_maskz_loadu_ps(near, values + j));
        };
        keep(ox, box.x);
        keep(oy, box.y);
        keep(oz, box.z);
        keepFrom(ovx, from.vx);
        keepFrom(ovy, from.vy);
        keepFrom(ovz, from.vz);
        if (oradius) keepFrom(oradius, from.radius);
        if (otemperature) keepFrom(otemperature, from.temperature);
        if (oindex && near) {
            _mm512_storeu_si512(oindex + count,
                                _mm512_maskz_compress_epi32(near, indicesAt(from, j, near)));
            *source++ = {j, near};
        }
        count += uint32_t(__builtin_popcount(near));
    }
    out.sourceCount = uint32_t(source - out.sources.data());
#elif defined(__AVX2__)
    const __m256 reach2v = _mm256_set1_ps(reach2);
    for (uint32_t j = begin; j < end; j += 8) {
        const uint32_t left = end - j;
        const NearBox8 box = nearBox8(s, j, left, lo, hi, reach2v);
        unsigned near = box.near;
        if (material) near &= materialMask8(material + j, left, want);
        const auto keep = [&](std::vector<float>& to, __m256 v) {
            _mm256_storeu_ps(to.data() + count, leftPack(v, near));
        };
        keep(out.x, box.x);
        keep(out.y, box.y);
        keep(out.z, box.z);
        keep(out.vx, box.load(s.vx));
        keep(out.vy, box.load(s.vy));
        keep(out.vz, box.load(s.vz));
        if (!out.uniformRadius) keep(out.radius, box.load(s.radius));
        if (s.temperature) keep(out.temperature, box.load(s.temperature));
        if (out.indexed) keepIndices(s, j, near, out.index.data() + count);
        count += uint32_t(__builtin_popcount(near));
    }
#else
    for (uint32_t j = begin; j < end; ++j) {
        const float p[3] = {s.x[j], s.y[j], s.z[j]};
        float d2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float e = std::max(0.0f, std::max(lo[axis] - p[axis], p[axis] - hi[axis]));
            d2 += e * e;
        }
        out.x[count] = p[0];
        out.y[count] = p[1];
        out.z[count] = p[2];
        out.vx[count] = s.vx[j];
        out.vy[count] = s.vy[j];
        out.vz[count] = s.vz[j];
        out.radius[count] = s.radius[j];
        if (s.temperature) out.temperature[count] = s.temperature[j];
        if (out.indexed) out.index[count] = s.index ? s.index[j] : j;
        count += d2 <= reach2 && (!material || material[j] == want);
    }
#endif
    out.count = count;
}

/// collectGroupCandidates into one list per material: globule j goes to
/// @p out[material[j]] (every material below out.size()). One pass over the runs.
inline void collectGroupCandidatesByMaterial(const GlobuleArrays& s, uint32_t begin,
                                             uint32_t end, const float lo[3], const float hi[3],
                                             float reach, const uint8_t* material,
                                             std::vector<GroupCandidates>& out) {
#if defined(__AVX512F__)
    const __m512 reach2v = _mm512_set1_ps(reach * reach);
    for (uint32_t j = begin; j < end; j += 16) {
        const uint32_t left = end - j;
        const NearBox box = nearBox(s, j, left, lo, hi, reach2v);
        const __mmask16 near = box.near;
        if (!near) continue;
        const __m512 x = box.x, y = box.y, z = box.z;
        const __m512 vx = _mm512_maskz_loadu_ps(near, s.vx + j);
        const __m512 vy = _mm512_maskz_loadu_ps(near, s.vy + j);
        const __m512 vz = _mm512_maskz_loadu_ps(near, s.vz + j);
        const __m512 r = _mm512_maskz_loadu_ps(near, s.radius + j);
        const __m512 t = s.temperature ? _mm512_maskz_loadu_ps(near, s.temperature + j) : r;
        for (std::size_t kind = 0; kind < out.size(); ++kind) {
            const __mmask16 mine = near & materialMask(material + j, left, uint8_t(kind));
            if (!mine) continue;
            GroupCandidates& c = out[kind];
            const auto keep = [&](std::vector<float>& to, __m512 v) {
                _mm512_storeu_ps(to.data() + c.count, _mm512_maskz_compress_ps(mine, v));
            };
            keep(c.x, x);
            keep(c.y, y);
            keep(c.z, z);
            keep(c.vx, vx);
            keep(c.vy, vy);
            keep(c.vz, vz);
            if (!c.uniformRadius) keep(c.radius, r);
            if (s.temperature) keep(c.temperature, t);
            if (c.indexed) {
                _mm512_storeu_si512(c.index.data() + c.count,
                                    _mm512_maskz_compress_epi32(mine, indicesAt(s, j, mine)));
                c.sources[c.sourceCount++] = {j, mine};
            }
            c.count += uint32_t(__builtin_popcount(mine));
        }
    }
#elif defined(__AVX2__)
    const __m256 reach2v = _mm256_set1_ps(reach * reach);
    for (uint32_t j = begin; j < end; j += 8) {
        const uint32_t left = end - j;
        const NearBox8 box = nearBox8(s, j, left, lo, hi, reach2v);
        const unsigned near = box.near;
        if (!near) continue;
        const __m256 vx = box.load(s.vx), vy = box.load(s.vy), vz = box.load(s.vz);
        const __m256 r = box.load(s.radius);
        const __m256 t = s.temperature ? box.load(s.temperature) : r;
        for (std::size_t kind = 0; kind < out.size(); ++kind) {
            const unsigned mine = near & materialMask8(material + j, left, uint8_t(kind));
            if (!mine) continue;
            GroupCandidates& c = out[kind];
            const auto keep = [&](std::vector<float>& to, __m256 v) {
                _mm256_storeu_ps(to.data() + c.count, leftPack(v, mine));
            };
            keep(c.x, box.x);
            keep(c.y, box.y);
            keep(c.z, box.z);
            keep(c.vx, vx);
            keep(c.vy, vy);
            keep(c.vz, vz);
            if (!c.uniformRadius) keep(c.radius, r);
            if (s.temperature) keep(c.temperature, t);
            if (c.indexed) keepIndices(s, j, mine, c.index.data() + c.count);
            c.count += uint32_t(__builtin_popcount(mine));
        }
    }
#else
    for (std::size_t kind = 0; kind < out.size(); ++kind) {
        collectGroupCandidates(s, begin, end, lo, hi, reach, out[kind], material, uint8_t(kind));
    }
#endif
}

/// Appends to @p out the candidates j of @p c with 0 < |x_i - x_j| < reach (r_i + r_j),
/// reach = PairForce::cutoff(1), for globule i at (x, y, z) with velocity v and radius r.
/// Globule i itself (and any globule at exactly its position, whose force is zero) is
/// left out. @p out has room for them. <Thermal>: also the neighbours' temperatures, for
/// the heat and the blended force (thermal_kernel.h). The heat is not summed here, over
/// the candidates' lanes, but over the compacted neighbours (HeatLanes): which lane a
/// candidate takes follows its place in the list, which a range's cut through a cell's
/// group, or a crowded group's split, changes; the neighbours' order they do not.
template <bool Thermal = false>
inline void collectNeighbors(const GroupCandidates& c, float x, float y, float z, float vx,
                             float vy, float vz, float r, float reach2, NeighborBatch& out) {
    uint32_t count = out.count;
    float *bx = out.dx.data(), *by = out.dy.data(), *bz = out.dz.data();
    float* bvp = out.vDotP.data();
    float* bsum = out.radiusSum.data();
    const uint32_t end = c.count;
    // Locals, not members: the vector stores below may alias anything, so members would
    // be reloaded on every pass.
    const float *cx = c.x.data(), *cy = c.y.data(), *cz = c.z.data();
    const float *cvx = c.vx.data(), *cvy = c.vy.data(), *cvz = c.vz.data();
    const float *cr = c.radius.data(), *ct = c.temperature.data();
    const bool uniformRadius = c.uniformRadius;
    float* bt = out.temperature.data();
#if defined(__AVX512F__)
    const __m512 px = _mm512_set1_ps(x), py = _mm512_set1_ps(y), pz = _mm512_set1_ps(z);
    const __m512 pvx = _mm512_set1_ps(vx), pvy = _mm512_set1_ps(vy), pvz = _mm512_set1_ps(vz);
    const __m512 pr = _mm512_set1_ps(r), reach2v = _mm512_set1_ps(reach2);
    const __m512 zero = _mm512_setzero_ps();
    for (uint32_t j = 0; j < end; j += 16) {
        // The padding past count is readable: plain loads, and a masked test.
        const uint32_t left = end - j;
        const __mmask16 live = firstLanes(left);
        const __m512 dx = _mm512_sub_ps(px, _mm512_loadu_ps(cx + j));
        const __m512 dy = _mm512_sub_ps(py, _mm512_loadu_ps(cy + j));
        const __m512 dz = _mm512_sub_ps(pz, _mm512_loadu_ps(cz + j));
        const __m512 d2 = _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
        const __m512 sum =
            _mm512_add_ps(pr, uniformRadius ? pr : _mm512_loadu_ps(cr + j));
        const __m512 limit = _mm512_mul_ps(_mm512_mul_ps(sum, sum), reach2v);
        const __mmask16 near = _mm512_mask_cmp_ps_mask(live, d2, limit, _CMP_LT_OQ) &
                               _mm512_cmp_ps_mask(d2, zero, _CMP_GT_OQ);
        // No early-out when no lane is near: that branch is unpredictable, and slower.
        const auto keep = [&](float* to, __m512 v) {
            _mm512_storeu_ps(to + count, _mm512_maskz_compress_ps(near, v));
        };
        keep(bx, dx);
        keep(by, dy);
        keep(bz, dz);
        const __m512 dvx = _mm512_sub_ps(pvx, _mm512_loadu_ps(cvx + j));
        const __m512 dvy = _mm512_sub_ps(pvy, _mm512_loadu_ps(cvy + j));
        const __m512 dvz = _mm512_sub_ps(pvz, _mm512_loadu_ps(cvz + j));
        keep(bvp, _mm512_fmadd_ps(dvz, dz, _mm512_fmadd_ps(dvy, dy, _mm512_mul_ps(dvx, dx))));
        if (!uniformRadius) keep(bsum, sum);
        if constexpr (Thermal) keep(bt, _mm512_loadu_ps(ct + j));
        count += uint32_t(__builtin_popcount(near));
    }
#elif defined(__AVX2__)
    const __m256 px = _mm256_set1_ps(x), py = _mm256_set1_ps(y), pz = _mm256_set1_ps(z);
    const __m256 pvx = _mm256_set1_ps(vx), pvy = _mm256_set1_ps(vy), pvz = _mm256_set1_ps(vz);
    const __m256 pr = _mm256_set1_ps(r), reach2v = _mm256_set1_ps(reach2);
    const __m256 zero = _mm256_setzero_ps();
    for (uint32_t j = 0; j < end; j += 8) {
        // The padding past count is readable: plain loads, and a masked test.
        const __m256 live = _mm256_castsi256_ps(firstLanes8(end - j));
        const __m256 dx = _mm256_sub_ps(px, _mm256_loadu_ps(cx + j));
        const __m256 dy = _mm256_sub_ps(py, _mm256_loadu_ps(cy + j));
        const __m256 dz = _mm256_sub_ps(pz, _mm256_loadu_ps(cz + j));
        const __m256 d2 = _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx)));
        const __m256 sum =
            _mm256_add_ps(pr, uniformRadius ? pr : _mm256_loadu_ps(cr + j));
        const __m256 limit = _mm256_mul_ps(_mm256_mul_ps(sum, sum), reach2v);
        const __m256 nearLanes = _mm256_and_ps(
            live, _mm256_and_ps(_mm256_cmp_ps(d2, limit, _CMP_LT_OQ),
                                _mm256_cmp_ps(d2, zero, _CMP_GT_OQ)));
        const unsigned near = unsigned(_mm256_movemask_ps(nearLanes));
        const auto keep = [&](float* to, __m256 v) {
            _mm256_storeu_ps(to + count, leftPack(v, near));
        };
        keep(bx, dx);
        keep(by, dy);
        keep(bz, dz);
        const __m256 dvx = _mm256_sub_ps(pvx, _mm256_loadu_ps(cvx + j));
        const __m256 dvy = _mm256_sub_ps(pvy, _mm256_loadu_ps(cvy + j));
        const __m256 dvz = _mm256_sub_ps(pvz, _mm256_loadu_ps(cvz + j));
        keep(bvp, _mm256_fmadd_ps(dvz, dz, _mm256_fmadd_ps(dvy, dy, _mm256_mul_ps(dvx, dx))));
        if (!uniformRadius) keep(bsum, sum);
        if constexpr (Thermal) keep(bt, _mm256_loadu_ps(ct + j));
        count += uint32_t(__builtin_popcount(near));
    }
#else
    for (uint32_t j = 0; j < end; ++j) {
        const float dx = x - cx[j], dy = y - cy[j], dz = z - cz[j];
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float sum = r + (uniformRadius ? r : cr[j]);
        bx[count] = dx;
        by[count] = dy;
        bz[count] = dz;
        bvp[count] = (vx - cvx[j]) * dx + (vy - cvy[j]) * dy + (vz - cvz[j]) * dz;
        bsum[count] = sum;
        if constexpr (Thermal) bt[count] = ct[j];
        count += d2 < sum * sum * reach2 && d2 > 0;
    }
#endif
    out.count = count;
    out.uniformSum = c.uniformRadius ? r + r : 0.0f;
}

/// The constants one pair's plain arithmetic uses (pairScaleOne).
struct PairTerms {
    float b1, b2, m, n;
    float invCr2, invCd2;  ///< 1/C_r^2, 1/C_d^2
};

/// What eq. (2)-(5) multiply P by for one pair, in plain arithmetic: |P|^2 = @p d2,
/// r_i + r_j = @p sum. <M, N>: integer exponents known at compile time; <0, 0>: pow().
/// sumBatch's plain loop and sumBlendedBatch's (thermal_kernel.h) share it, so that where
/// a pure phase holds the two give the same bits.
template <int M, int N>
inline float pairScaleOne(const PairTerms& c, float d2, float sum, float vDotP) {
    const float minFraction2 = kMinDistanceFraction * kMinDistanceFraction;
    const float invSum2 = 1.0f / (sum * sum);
    const float safeD2 = std::max(d2, minFraction2 * sum * sum);
    const float distance = std::sqrt(safeD2);
    const float invD = 1.0f / distance;
    const float windowR = std::max(0.0f, 1.0f - d2 * invSum2 * c.invCr2);
    const float windowD = std::max(0.0f, 1.0f - d2 * invSum2 * c.invCd2);
    float radial;
    if constexpr (M > 0 && N > 0) {
        float powM = 1, powN = 1;
        for (int k = 0; k < M; ++k) powM *= invD;  // unrolled: M is a constant
        for (int k = 0; k < N; ++k) powN *= invD;
        radial = c.b1 * powM - c.b2 * powN;
    } else {
        radial = c.b1 * std::pow(distance, -c.m) - c.b2 * std::pow(distance, -c.n);
    }
    return windowR * radial - windowD * vDotP * (invD * invD);
}

#if defined(__AVX2__)
// The lane arithmetic that intPow, radiusSumTerms and pairScale need, once per vector
// width, so that those are written once for AVX-512 (16 lanes) and AVX2 (8). The
// estimates are AVX-512's 14-bit ones and AVX2's 12-bit ones; one Newton step leaves
// either within a few units in the last place.
#if defined(__AVX512F__)
inline __m512 lanesMul(__m512 a, __m512 b) { return _mm512_mul_ps(a, b); }
inline __m512 lanesMax(__m512 a, __m512 b) { return _mm512_max_ps(a, b); }
inline __m512 lanesFnmadd(__m512 a, __m512 b, __m512 c) { return _mm512_fnmadd_ps(a, b, c); }
inline __m512 lanesFmsub(__m512 a, __m512 b, __m512 c) { return _mm512_fmsub_ps(a, b, c); }
inline __m512 lanesRsqrtEstimate(__m512 a) { return _mm512_rsqrt14_ps(a); }
inline __m512 lanesRcpEstimate(__m512 a) { return _mm512_rcp14_ps(a); }
inline __m512 lanesSplat(__m512 /*width*/, float v) { return _mm512_set1_ps(v); }
inline __m512 lanesZero(__m512 /*width*/) { return _mm512_setzero_ps(); }
#endif
inline __m256 lanesMul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
inline __m256 lanesMax(__m256 a, __m256 b) { return _mm256_max_ps(a, b); }
inline __m256 lanesFnmadd(__m256 a, __m256 b, __m256 c) { return _mm256_fnmadd_ps(a, b, c); }
inline __m256 lanesFmsub(__m256 a, __m256 b, __m256 c) { return _mm256_fmsub_ps(a, b, c); }
inline __m256 lanesRsqrtEstimate(__m256 a) { return _mm256_rsqrt_ps(a); }
inline __m256 lanesRcpEstimate(__m256 a) { return _mm256_rcp_ps(a); }
inline __m256 lanesSplat(__m256 /*width*/, float v) { return _mm256_set1_ps(v); }
inline __m256 lanesZero(__m256 /*width*/) { return _mm256_setzero_ps(); }

/// x^K by squaring (K >= 1): x^5 = x (x^2)^2, three multiplications.
template <int K, typename Lanes>
inline Lanes intPow(Lanes x) {
    if constexpr (K == 1) {
        return x;
    } else if constexpr (K % 2 == 0) {
        const Lanes root = intPow<K / 2>(x);
        return lanesMul(root, root);
    } else {
        return lanesMul(x, intPow<K - 1>(x));
    }
}

/// 1 / (r_i + r_j)^2 and the smallest squared distance the force takes, for the radius
/// sums @p sum.
template <typename Lanes>
inline void radiusSumTerms(Lanes sum, Lanes& invSum2, Lanes& minD2) {
    const Lanes sum2 = lanesMul(sum, sum);
    invSum2 = lanesRcpEstimate(sum2);  // and one Newton step
    invSum2 = lanesMul(invSum2, lanesFnmadd(sum2, invSum2, lanesSplat(sum, 2)));
    minD2 = lanesMul(lanesSplat(sum, kMinDistanceFraction * kMinDistanceFraction), sum2);
}

/// What eq. (2)-(5) multiply P by, lane by lane: @p d2 = |P|^2 (taken as @p minD2 where
/// smaller), @p invSum2 = 1 / (r_i + r_j)^2, the constants b1, b2, 1/C_r^2 (@p cr2) and
/// 1/C_d^2 (@p cd2), and V.P. 1/D from the estimate and one Newton step: no divisions.
template <int M, int N, typename Lanes>
inline Lanes pairScale(Lanes d2, Lanes invSum2, Lanes minD2, Lanes b1, Lanes b2, Lanes cr2,
                       Lanes cd2, Lanes vDotP) {
    const Lanes one = lanesSplat(d2, 1), zero = lanesZero(d2);
    const Lanes safeD2 = lanesMax(d2, minD2);
    Lanes invD = lanesRsqrtEstimate(safeD2);
    invD = lanesMul(invD, lanesFnmadd(lanesMul(lanesSplat(d2, 0.5f), safeD2),
                                      lanesMul(invD, invD), lanesSplat(d2, 1.5f)));
    const Lanes relative = lanesMul(d2, invSum2);
    const Lanes windowR = lanesMax(zero, lanesFnmadd(relative, cr2, one));
    const Lanes windowD = lanesMax(zero, lanesFnmadd(relative, cd2, one));
    const Lanes powN = intPow<N>(invD);
    const Lanes powM =
        M > N ? lanesMul(powN, intPow<(M > N ? M - N : 1)>(invD)) : intPow<M>(invD);
    const Lanes radial = lanesFmsub(b1, powM, lanesMul(b2, powN));
    const Lanes drag = lanesMul(lanesMul(windowD, vDotP), lanesMul(invD, invD));
    return lanesFmsub(windowR, radial, drag);
}

/// A NeighborBatch 8 lanes at a time, for the AVX2 force sums (sumBatch, sumBlendedBatch):
/// each block's P, |P|^2 and radius terms, and the sum of scale * P over the live lanes.
/// Past count the batch holds stale but readable entries: the sum leaves those lanes out.
class BatchLanes {
public:
    struct Block {
        __m256 live, dx, dy, dz, d2, invSum2, minD2;
    };

    explicit BatchLanes(const NeighborBatch& batch) : mBatch(batch) {
        const float sum2 = batch.uniformSum * batch.uniformSum;
        mUniformInvSum2 = _mm256_set1_ps(batch.uniformSum > 0 ? 1.0f / sum2 : 0.0f);
        mUniformMinD2 = _mm256_set1_ps(kMinDistanceFraction * kMinDistanceFraction * sum2);
    }

    /// Entries [k, k + 8); @p uniform: the batch's uniformSum holds every r_i + r_j.
    Block load(uint32_t k, bool uniform) const {
        Block b;
        b.live = _mm256_castsi256_ps(firstLanes8(mBatch.count - k));
        b.dx = _mm256_loadu_ps(mBatch.dx.data() + k);
        b.dy = _mm256_loadu_ps(mBatch.dy.data() + k);
        b.dz = _mm256_loadu_ps(mBatch.dz.data() + k);
        b.d2 = _mm256_fmadd_ps(b.dz, b.dz, _mm256_fmadd_ps(b.dy, b.dy, _mm256_mul_ps(b.dx, b.dx)));
        b.invSum2 = mUniformInvSum2;
        b.minD2 = mUniformMinD2;
        if (!uniform) {
            const __m256 sum = _mm256_loadu_ps(mBatch.radiusSum.data() + k);
            radiusSumTerms(_mm256_blendv_ps(_mm256_set1_ps(1), sum, b.live), b.invSum2, b.minD2);
        }
        return b;
    }

    /// Adds @p scale * P of @p b's live lanes.
    void add(const Block& b, __m256 scale) {
        mX = _mm256_blendv_ps(mX, _mm256_fmadd_ps(scale, b.dx, mX), b.live);
        mY = _mm256_blendv_ps(mY, _mm256_fmadd_ps(scale, b.dy, mY), b.live);
        mZ = _mm256_blendv_ps(mZ, _mm256_fmadd_ps(scale, b.dz, mZ), b.live);
    }

    /// Adds the sums to (fx, fy, fz).
    void addTo(float& fx, float& fy, float& fz) const {
        fx += sumLanes(mX);
        fy += sumLanes(mY);
        fz += sumLanes(mZ);
    }

private:
    const NeighborBatch& mBatch;
    __m256 mUniformInvSum2, mUniformMinD2;
    __m256 mX = _mm256_setzero_ps(), mY = _mm256_setzero_ps(), mZ = _mm256_setzero_ps();
};
#endif

/// Adds to (fx, fy, fz) the force of eq. (2) from every neighbour in @p batch. On the
/// AVX-512 path (integer exponents) it also calls @p perBlock(k, live, d2) for each block
/// of lanes [k, k + 16): work that needs |P|^2 rides along instead of a pass of its own
/// (the heat, thermal_kernel.h). Elsewhere perBlock is not called.
template <int M, int N, typename PerBlock>
inline void sumBatchWith(const PairForce& p, const NeighborBatch& batch, float& fx, float& fy,
                         float& fz, PerBlock&& perBlock) {
    const float invCr2 = 1.0f / (p.cr * p.cr), invCd2 = 1.0f / (p.cd * p.cd);
    const float *bx = batch.dx.data(), *by = batch.dy.data(), *bz = batch.dz.data();
    const float* bvp = batch.vDotP.data();
    const float* bsum = batch.radiusSum.data();
    const bool uniform = batch.uniformSum > 0;
    const uint32_t count = batch.count;
#if defined(__AVX512F__)
    if constexpr (M > 0 && N > 0) {
        const __m512 one = _mm512_set1_ps(1), zero = _mm512_setzero_ps();
        const __m512 cr2 = _mm512_set1_ps(invCr2), cd2 = _mm512_set1_ps(invCd2);
        const __m512 b1 = _mm512_set1_ps(p.b1), b2 = _mm512_set1_ps(p.b2);
        const float fixedSum2 = batch.uniformSum * batch.uniformSum;
        const __m512 fixedInvSum2 = _mm512_set1_ps(uniform ? 1.0f / fixedSum2 : 0.0f);
        const __m512 fixedMinD2 =
            _mm512_set1_ps(kMinDistanceFraction * kMinDistanceFraction * fixedSum2);
        __m512 ax = zero, ay = zero, az = zero;
        // The loop is instantiated twice so that a uniform radius costs no per-pair work.
        const auto sumAll = [&]<bool Uniform>() {
            for (uint32_t k = 0; k < count; k += 16) {
                const uint32_t left = count - k;
                const __mmask16 live = firstLanes(left);
                const __m512 dx = _mm512_maskz_loadu_ps(live, bx + k);
                const __m512 dy = _mm512_maskz_loadu_ps(live, by + k);
                const __m512 dz = _mm512_maskz_loadu_ps(live, bz + k);
                __m512 invSum2 = fixedInvSum2, minD2 = fixedMinD2;
                if constexpr (!Uniform) {
                    radiusSumTerms(_mm512_mask_loadu_ps(one, live, bsum + k), invSum2, minD2);
                }
                const __m512 d2 = _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
                const __m512 scale = pairScale<M, N>(d2, invSum2, minD2, b1, b2, cr2, cd2,
                                                     _mm512_maskz_loadu_ps(live, bvp + k));
                perBlock(k, live, d2);
                ax = _mm512_mask3_fmadd_ps(scale, dx, ax, live);
                ay = _mm512_mask3_fmadd_ps(scale, dy, ay, live);
                az = _mm512_mask3_fmadd_ps(scale, dz, az, live);
            }
        };
        if (uniform) {
            sumAll.template operator()<true>();
        } else {
            sumAll.template operator()<false>();
        }
        fx += _mm512_reduce_add_ps(ax);
        fy += _mm512_reduce_add_ps(ay);
        fz += _mm512_reduce_add_ps(az);
        return;
    }
#elif defined(__AVX2__)
    if constexpr (M > 0 && N > 0) {
        const __m256 cr2 = _mm256_set1_ps(invCr2), cd2 = _mm256_set1_ps(invCd2);
        const __m256 b1 = _mm256_set1_ps(p.b1), b2 = _mm256_set1_ps(p.b2);
        BatchLanes lanes(batch);
        // Instantiated twice so that a uniform radius costs no per-pair work.
        const auto sumAll = [&]<bool Uniform>() {
            for (uint32_t k = 0; k < count; k += 8) {
                const BatchLanes::Block b = lanes.load(k, Uniform);
                lanes.add(b, pairScale<M, N>(b.d2, b.invSum2, b.minD2, b1, b2, cr2, cd2,
                                             _mm256_loadu_ps(bvp + k)));
            }
        };
        if (uniform) {
            sumAll.template operator()<true>();
        } else {
            sumAll.template operator()<false>();
        }
        lanes.addTo(fx, fy, fz);
        return;
    }
#endif
    static_cast<void>(perBlock);  // (this loop has no blocks)
    const PairTerms terms{p.b1, p.b2, p.m, p.n, invCr2, invCd2};
    float ax = 0, ay = 0, az = 0;
    for (uint32_t k = 0; k < count; ++k) {
        const float dx = bx[k], dy = by[k], dz = bz[k];
        const float sum = uniform ? batch.uniformSum : bsum[k];
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float scale = pairScaleOne<M, N>(terms, d2, sum, bvp[k]);
        ax += scale * dx;
        ay += scale * dy;
        az += scale * dz;
    }
    fx += ax;
    fy += ay;
    fz += az;
}

/// A globule whose force the loop sums: its position, velocity and radius.
struct Member {
    float x, y, z, vx, vy, vz, r;
};

#if defined(__AVX512F__)
/// The first block of 16 of a sum over candidates from @p from on: blocks start at
/// multiples of 16, the lanes before @p from masked off (CandidateLanes::load), so that
/// loads and stores do not straddle cache lines.
inline uint32_t firstBlock(uint32_t from) { return from & ~15u; }

/// One member's candidates (GroupCandidates, every globule of the member's radius: the
/// list's uniformRadius), 16 at a time, for the AVX-512 sums that run straight over them:
/// each block's P, |P|^2 and V.P, and which lanes are neighbours (0 < |P| < reach (r + r),
/// reach^2 = @p reach2). No compaction into a NeighborBatch: the compaction's five
/// compress-and-store sequences per 16 candidates cost more than the force's arithmetic on
/// the candidates that are no neighbours (about half of a crowded part's,
/// force_kernels.cpp): the liquid block stepped 1.09x faster, the dense pile 1.12x. Which
/// lane a neighbour takes follows its place in the list, so a sum's bits follow the list's
/// make-up: the force loop keeps each grid cell's group whole in one task.
class CandidateLanes {
public:
    struct Block {
        __mmask16 near;
        __m512 dx, dy, dz, d2, vDotP;
    };

    CandidateLanes(const GroupCandidates& c, const Member& i, float reach2)
        : mX(c.x.data()), mY(c.y.data()), mZ(c.z.data()),
          mVx(c.vx.data()), mVy(c.vy.data()), mVz(c.vz.data()), mCount(c.count),
          mPx(_mm512_set1_ps(i.x)), mPy(_mm512_set1_ps(i.y)), mPz(_mm512_set1_ps(i.z)),
          mPvx(_mm512_set1_ps(i.vx)), mPvy(_mm512_set1_ps(i.vy)), mPvz(_mm512_set1_ps(i.vz)) {
        const float sum = i.r + i.r, sum2 = sum * sum;
        radiusSum = sum;
        // The radius terms as the batch's uniform ones (sumBatchWith).
        invSum2 = _mm512_set1_ps(1.0f / sum2);
        minD2 = _mm512_set1_ps(kMinDistanceFraction * kMinDistanceFraction * sum2);
        mLimit = _mm512_set1_ps(sum2 * reach2);
    }

    uint32_t count() const { return mCount; }

    /// Candidates [j, j + 16), those before @p from left out. The padding past count is
    /// readable: plain loads, and a masked test. Always inlined: a call returns the block
    /// through memory (GCC 12 left it out of line in the thermal loops, 1.4x slower).
    [[gnu::always_inline]] Block load(uint32_t j, uint32_t from = 0) const {
        Block b;
        const __mmask16 live = firstLanes(mCount - j) & ~firstLanes(from > j ? from - j : 0);
        b.dx = _mm512_sub_ps(mPx, _mm512_loadu_ps(mX + j));
        b.dy = _mm512_sub_ps(mPy, _mm512_loadu_ps(mY + j));
        b.dz = _mm512_sub_ps(mPz, _mm512_loadu_ps(mZ + j));
        b.d2 = _mm512_fmadd_ps(b.dz, b.dz, _mm512_fmadd_ps(b.dy, b.dy, _mm512_mul_ps(b.dx, b.dx)));
        b.near = _mm512_mask_cmp_ps_mask(live, b.d2, mLimit, _CMP_LT_OQ) &
                 _mm512_cmp_ps_mask(b.d2, _mm512_setzero_ps(), _CMP_GT_OQ);
        const __m512 dvx = _mm512_sub_ps(mPvx, _mm512_loadu_ps(mVx + j));
        const __m512 dvy = _mm512_sub_ps(mPvy, _mm512_loadu_ps(mVy + j));
        const __m512 dvz = _mm512_sub_ps(mPvz, _mm512_loadu_ps(mVz + j));
        b.vDotP = _mm512_fmadd_ps(dvz, b.dz, _mm512_fmadd_ps(dvy, b.dy, _mm512_mul_ps(dvx, b.dx)));
        return b;
    }

    float radiusSum;         ///< r_i + r_j of every pair
    __m512 invSum2, minD2;  ///< 1 / (r_i + r_j)^2 and the smallest |P|^2 the force takes

private:
    const float *mX, *mY, *mZ, *mVx, *mVy, *mVz;
    uint32_t mCount;
    __m512 mPx, mPy, mPz, mPvx, mPvy, mPvz, mLimit;
};

/// Where a member's sum over the candidates after it (the loop that evaluates each pair
/// once) leaves each pair's opposite force and heat: one entry per candidate, plain
/// pointers into Reactions' arrays, so that the vector stores (which may alias anything)
/// do not make the loop reload them.
struct ReactionLanes {
    float *x, *y, *z, *heat;

    /// Takes -@p scale P of the lanes @p near of block [j, j + 16).
    void add(uint32_t j, __mmask16 near, __m512 scale, __m512 dx, __m512 dy, __m512 dz) const {
        const auto take = [&](float* to, __m512 p) {
            float* at = to + j;
            _mm512_storeu_ps(at, _mm512_mask3_fnmadd_ps(scale, p, _mm512_loadu_ps(at), near));
        };
        take(x, dx);
        take(y, dy);
        take(z, dz);
    }

    /// Takes -@p conductance @p term of the lanes @p near of block [j, j + 16): the
    /// opposite of the heat the member took in (HeatLanes).
    void addHeat(uint32_t j, __mmask16 near, __m512 term, float conductance) const {
        float* at = heat + j;
        _mm512_storeu_ps(at, _mm512_mask3_fnmadd_ps(_mm512_set1_ps(conductance), term,
                                                    _mm512_loadu_ps(at), near));
    }
};

/// The opposite of the forces a list's members feel from its candidates (Newton's third
/// law), one entry per candidate: the loop that evaluates each pair once sums a member's
/// force over the candidates after it and leaves each pair's opposite here (ReactionLanes),
/// to be added to the candidate's globule once the list is done (each_pair_once.h).
/// Thermal scenes keep the opposite heat too.
struct Reactions {
    static constexpr uint32_t kPadding = 16;  ///< vector stores write up to 16 past count
    std::vector<float> x, y, z, heat;

    /// @p count zeroed entries (and the padding); @p withHeat: the heat's too.
    void clear(uint32_t count, bool withHeat) {
        for (auto* a : {&x, &y, &z, &heat}) {
            if (a == &heat && !withHeat) continue;
            if (a->size() < count + kPadding) a->resize(count + kPadding);
            std::fill(a->begin(), a->begin() + count + kPadding, 0.0f);
        }
    }

    ReactionLanes lanes() { return {x.data(), y.data(), z.data(), heat.data()}; }
};

/// Where a sum that evaluates each pair from both sides puts the opposite forces: nowhere.
struct NoReactions {
    void add(uint32_t, __mmask16, __m512, __m512, __m512, __m512) const {}
    void addHeat(uint32_t, __mmask16, __m512, float) const {}
};

/// Adds to (fx, fy, fz) the force of eq. (2) from every neighbour among @p lanes'
/// candidates [@p from, count), calls @p perBlock(j, near, d2) for each block [j, j + 16)
/// (the heat, thermal_kernel.h) and leaves each pair's opposite force in @p reactions.
/// <M, N>: integer exponents (the pow() kernels compact first).
template <int M, int N, typename PerBlock, typename Opposite>
inline void sumCandidatesWith(const PairForce& p, const CandidateLanes& candidates, float& fx,
                              float& fy, float& fz, PerBlock&& perBlock, uint32_t from,
                              Opposite reactions) {
    const CandidateLanes lanes = candidates;  // a local: the stores cannot alias it
    static_assert(M > 0 && N > 0, "integer exponents: the pow() kernels compact first");
    const __m512 cr2 = _mm512_set1_ps(1.0f / (p.cr * p.cr));
    const __m512 cd2 = _mm512_set1_ps(1.0f / (p.cd * p.cd));
    const __m512 b1 = _mm512_set1_ps(p.b1), b2 = _mm512_set1_ps(p.b2);
    __m512 ax = _mm512_setzero_ps(), ay = ax, az = ax;
    for (uint32_t j = firstBlock(from); j < lanes.count(); j += 16) {
        const CandidateLanes::Block b = lanes.load(j, from);
        const __m512 scale =
            pairScale<M, N>(b.d2, lanes.invSum2, lanes.minD2, b1, b2, cr2, cd2, b.vDotP);
        perBlock(j, b.near, b.d2);
        reactions.add(j, b.near, scale, b.dx, b.dy, b.dz);
        ax = _mm512_mask3_fmadd_ps(scale, b.dx, ax, b.near);
        ay = _mm512_mask3_fmadd_ps(scale, b.dy, ay, b.near);
        az = _mm512_mask3_fmadd_ps(scale, b.dz, az, b.near);
    }
    fx += _mm512_reduce_add_ps(ax);
    fy += _mm512_reduce_add_ps(ay);
    fz += _mm512_reduce_add_ps(az);
}
#endif

/// What sumBatchWith and sumCandidatesWith do besides the force where the caller wants
/// nothing more.
struct NoBlockWork {
    template <typename Mask, typename Lanes>
    void operator()(uint32_t /*k*/, Mask /*live*/, Lanes /*d2*/) const {}
};

#if defined(__AVX512F__)
/// sumCandidatesWith with nothing besides the force.
template <int M, int N>
inline void sumCandidates(const PairForce& p, const CandidateLanes& lanes, float& fx, float& fy,
                          float& fz) {
    sumCandidatesWith<M, N>(p, lanes, fx, fy, fz, NoBlockWork{}, 0, NoReactions{});
}

/// sumCandidatesWith over the candidates [@p from, count), each pair's opposite force left
/// in @p reactions.
template <int M, int N>
inline void sumLaterCandidates(const PairForce& p, const CandidateLanes& lanes, uint32_t from,
                               ReactionLanes reactions, float& fx, float& fy, float& fz) {
    sumCandidatesWith<M, N>(p, lanes, fx, fy, fz, NoBlockWork{}, from, reactions);
}
#endif

/// sumBatchWith with nothing besides the force.
template <int M, int N>
inline void sumBatch(const PairForce& p, const NeighborBatch& batch, float& fx, float& fy,
                     float& fz) {
    sumBatchWith<M, N>(p, batch, fx, fy, fz, NoBlockWork{});
}

}  // namespace globular
