#pragma once
// The force loop's pieces for thermal scenes (thermal_settings.h). A globule's neighbours
// are taken one material at a time, as without temperature (forces.cpp), and for each
// material the pair (ThermalPair) decides:
//   - phaseOf: whether every pair the globule forms with that material is solid, every
//     one liquid, or whether their constants blend by each pair's mean temperature;
//   - the force is pair_kernel.h's sumBatch with the phase's constants (sumBatchAndHeat),
//     or, where pairs melt, sumBlendedBatch below;
//   - the heat flowing in is summed over the neighbours once collected (HeatLanes), in
//     the force's loop with AVX-512;
//   - with AVX-512, shared integer exponents and a uniform radius, all three run straight
//     over the candidates instead (sumCandidatesAndHeat, sumBlendedCandidates), in the
//     same lanes, as the plain loop does (pair_kernel.h, CandidateLanes).
// The blend is of what the kernel uses, b1, b2, 1/C_r^2 and 1/C_d^2 (and m, n on the
// generic path), as (1 - s) solid + s liquid: exactly the solid's at s = 0 and exactly
// the liquid's at s = 1, so the three ways agree bit for bit where they overlap. Where
// every pair is evaluated from both sides it is with the same arithmetic, so the force
// stays equal and opposite; where each pair is evaluated once (AVX-512, a uniform radius:
// each_pair_once.h) the opposite force and heat are the same lanes negated. The blend's
// weight follows the pair's mean temperature and the heat's weight d^2 alone: both are
// the same seen from either globule.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "material_pairs.h"
#include "pair_kernel.h"

namespace globular {

enum class ThermalPhase { Solid, Liquid, Blend };

/// The phase of the pairs a globule at @p ti forms with neighbours whose temperatures lie
/// within [@p lowest, @p highest].
inline ThermalPhase phaseOf(const ThermalPair& pair, float ti, float lowest, float highest) {
    if (pair.invRange == 0 || 0.5f * (ti + highest) <= pair.tSolid) return ThermalPhase::Solid;
    if (0.5f * (ti + lowest) >= pair.tLiquid) return ThermalPhase::Liquid;
    return ThermalPhase::Blend;
}

/// The blend weight s of a pair whose mean temperature is @p t: smoothstep over the
/// melting range, exactly 0 at or below T_solid and exactly 1 at or above T_liquid.
inline float meltFraction(float t, const ThermalPair& pair) {
    if (pair.invRange == 0 || t <= pair.tSolid) return 0.0f;
    if (t >= pair.tLiquid) return 1.0f;
    const float x = std::min(1.0f, (t - pair.tSolid) * pair.invRange);
    return x * x * (3.0f - 2.0f * x);
}

/// The lowest and highest of @p count temperatures (count > 0).
inline std::pair<float, float> temperatureRange(const float* t, uint32_t count) {
#if defined(__AVX512F__)
    __m512 lo = _mm512_set1_ps(t[0]), hi = lo;
    for (uint32_t k = 0; k < count; k += 16) {
        const __m512 v = _mm512_mask_loadu_ps(lo, firstLanes(count - k), t + k);
        lo = _mm512_min_ps(lo, v);
        hi = _mm512_max_ps(hi, v);
    }
    return {_mm512_reduce_min_ps(lo), _mm512_reduce_max_ps(hi)};
#elif defined(__AVX2__)
    // Lanes past count are not read; they repeat t[0], which leaves the range as it is.
    const __m256 first = _mm256_set1_ps(t[0]);
    __m256 lo = first, hi = first;
    for (uint32_t k = 0; k < count; k += 8) {
        const __m256i live = firstLanes8(count - k);
        const __m256 v = _mm256_blendv_ps(first, _mm256_maskload_ps(t + k, live),
                                          _mm256_castsi256_ps(live));
        lo = _mm256_min_ps(lo, v);
        hi = _mm256_max_ps(hi, v);
    }
    return {minLanes(lo), maxLanes(hi)};
#else
    float lo = t[0], hi = t[0];
    for (uint32_t k = 1; k < count; ++k) {
        lo = std::min(lo, t[k]);
        hi = std::max(hi, t[k]);
    }
    return {lo, hi};
#endif
}

/// The heat flowing into a globule at temperature @p ti from the neighbours in a batch
/// (their temperatures kept by collectNeighbors<true>), per unit conductance, summed a
/// block of lanes at a time: w (T_j - T_i) with w = 1 - d^2 / (reach^2 (r_i + r_j)^2),
/// reach^2 = @p reach2. The weight comes from a division, not an estimate, so w_ij equals
/// w_ji bit for bit and conduction conserves heat to the sum's rounding. The sum runs over
/// the batch in its order, in the build's widest lanes (16 with AVX-512, 8 with AVX2), or
/// over a member's candidates in theirs (CandidateLanes); the force loop hands every task
/// whole cells, so a globule meets the same candidates and neighbours in the same order on
/// any thread count, and its heat has the same bits. Every kernel below sums it with this
/// one class, in the force's own loop or in a pass of its own (batchHeat), so its bits do
/// not depend on which kernel the pair's phase picks either.
class HeatLanes {
public:
    HeatLanes(const NeighborBatch& batch, float ti, float reach2)
        : HeatLanes(batch.radiusSum.data(), batch.temperature.data(), batch.uniformSum, ti,
                    reach2) {}

    /// Over a member's candidates (CandidateLanes), whose pairs all have r_i + r_j =
    /// @p uniformSum: the sum then runs in the candidates' lanes.
    HeatLanes(const GroupCandidates& c, float uniformSum, float ti, float reach2)
        : HeatLanes(nullptr, c.temperature.data(), uniformSum, ti, reach2) {}

private:
    HeatLanes(const float* sums, const float* temperatures, float uniformSum, float ti,
              float reach2)
        : mSums(sums), mTemperatures(temperatures), mUniform(uniformSum > 0) {
        const float uniformInvLimit = mUniform ? 1.0f / (uniformSum * uniformSum * reach2) : 0;
#if defined(__AVX512F__)
        mTi = _mm512_set1_ps(ti);
        mReach2 = _mm512_set1_ps(reach2);
        mUniformInvLimit = _mm512_set1_ps(uniformInvLimit);
#elif defined(__AVX2__)
        mTi = _mm256_set1_ps(ti);
        mReach2 = _mm256_set1_ps(reach2);
        mUniformInvLimit = _mm256_set1_ps(uniformInvLimit);
#else
        mTi = ti;
        mReach2 = reach2;
        mUniformInvLimit = uniformInvLimit;
#endif
    }

public:

#if defined(__AVX512F__)
    /// Adds the terms of the live lanes of [k, k + 16), whose |P|^2 is @p d2. @return the
    /// terms, w (T_j - T_i) (the opposite heat of a loop that evaluates each pair once).
    __m512 add(uint32_t k, __mmask16 live, __m512 d2) {
        const __m512 one = _mm512_set1_ps(1);
        __m512 invLimit = mUniformInvLimit;
        if (!mUniform) {
            const __m512 sum = _mm512_mask_loadu_ps(one, live, mSums + k);
            invLimit = _mm512_div_ps(one, _mm512_mul_ps(_mm512_mul_ps(sum, sum), mReach2));
        }
        const __m512 w = _mm512_fnmadd_ps(d2, invLimit, one);
        const __m512 tj = _mm512_maskz_loadu_ps(live, mTemperatures + k);
        const __m512 difference = _mm512_sub_ps(tj, mTi);
        mHeat = _mm512_mask3_fmadd_ps(w, difference, mHeat, live);
        return _mm512_mul_ps(w, difference);
    }
    float total() const { return _mm512_reduce_add_ps(mHeat); }
#elif defined(__AVX2__)
    /// Adds the terms of the live lanes of [k, k + 8), whose |P|^2 is @p d2. Past count
    /// the batch holds stale but readable entries.
    void add(uint32_t k, __m256 live, __m256 d2) {
        const __m256 one = _mm256_set1_ps(1);
        __m256 invLimit = mUniformInvLimit;
        if (!mUniform) {
            const __m256 sum = _mm256_loadu_ps(mSums + k);
            invLimit = _mm256_div_ps(one, _mm256_mul_ps(_mm256_mul_ps(sum, sum), mReach2));
        }
        const __m256 w = _mm256_fnmadd_ps(d2, invLimit, one);
        const __m256 difference = _mm256_sub_ps(_mm256_loadu_ps(mTemperatures + k), mTi);
        mHeat = _mm256_blendv_ps(mHeat, _mm256_fmadd_ps(w, difference, mHeat), live);
    }
    float total() const { return sumLanes(mHeat); }
#else
    /// Adds neighbour k's term; its |P|^2 is @p d2.
    void add(uint32_t k, float d2) {
        const float invLimit = mUniform ? mUniformInvLimit : 1.0f / (mSums[k] * mSums[k] * mReach2);
        mHeat += (1.0f - d2 * invLimit) * (mTemperatures[k] - mTi);
    }
    float total() const { return mHeat; }
#endif

private:
    const float *mSums, *mTemperatures;
    bool mUniform;
#if defined(__AVX512F__)
    __m512 mTi, mReach2, mUniformInvLimit, mHeat = _mm512_setzero_ps();
#elif defined(__AVX2__)
    __m256 mTi, mReach2, mUniformInvLimit, mHeat = _mm256_setzero_ps();
#else
    float mTi, mReach2, mUniformInvLimit, mHeat = 0;
#endif
};

/// HeatLanes' sum over @p batch in a pass of its own, for the kernels whose force loop
/// has no blocks (pow() exponents, the plain build).
inline float batchHeat(const NeighborBatch& batch, float ti, float reach2) {
    const float *bx = batch.dx.data(), *by = batch.dy.data(), *bz = batch.dz.data();
    const uint32_t count = batch.count;
    HeatLanes heat(batch, ti, reach2);
#if defined(__AVX512F__)
    for (uint32_t k = 0; k < count; k += 16) {
        const __mmask16 live = firstLanes(count - k);
        const __m512 dx = _mm512_maskz_loadu_ps(live, bx + k);
        const __m512 dy = _mm512_maskz_loadu_ps(live, by + k);
        const __m512 dz = _mm512_maskz_loadu_ps(live, bz + k);
        heat.add(k, live, _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx))));
    }
#elif defined(__AVX2__)
    for (uint32_t k = 0; k < count; k += 8) {
        const __m256 live = _mm256_castsi256_ps(firstLanes8(count - k));
        const __m256 dx = _mm256_loadu_ps(bx + k), dy = _mm256_loadu_ps(by + k);
        const __m256 dz = _mm256_loadu_ps(bz + k);
        heat.add(k, live, _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx))));
    }
#else
    for (uint32_t k = 0; k < count; ++k) heat.add(k, bx[k] * bx[k] + by[k] * by[k] + bz[k] * bz[k]);
#endif
    return heat.total();
}

/// sumBatch<M, N> that also returns the heat flowing in (HeatLanes). With AVX-512 it is
/// summed in the force's loop, which spares the heat's own pass over the batch: the
/// temperature block's step 1.08x faster, the dense pile's 1.10x (medians). With AVX2 it
/// keeps its own pass (batchHeat, the same lanes and bits): in the force's loop, with 16
/// vector registers, the dense pile stepped 1.1x slower.
template <int M, int N>
inline float sumBatchAndHeat(const PairForce& p, const NeighborBatch& batch, float ti,
                             float reach2, float& fx, float& fy, float& fz) {
#if defined(__AVX512F__)
    if constexpr (M > 0 && N > 0) {
        HeatLanes heat(batch, ti, reach2);
        sumBatchWith<M, N>(p, batch, fx, fy, fz,
                           [&](uint32_t k, auto live, auto d2) { heat.add(k, live, d2); });
        return heat.total();
    }
#endif
    sumBatch<M, N>(p, batch, fx, fy, fz);
    return batchHeat(batch, ti, reach2);
}

#if defined(__AVX512F__)
/// The blended constants of a globule at @p ti's pairs, 16 lanes at a time (the AVX-512
/// blended sums): b1, b2, 1/C_r^2 and 1/C_d^2 as (1 - s) solid + s liquid, s the
/// smoothstep of each pair's mean temperature.
class BlendLanes {
public:
    struct Constants {
        __m512 b1, b2, cr2, cd2;
    };

    BlendLanes(const ThermalPair& pair, float ti)
        : mTi(_mm512_set1_ps(ti)), mTs(_mm512_set1_ps(pair.tSolid)),
          mTl(_mm512_set1_ps(pair.tLiquid)), mInvRange(_mm512_set1_ps(pair.invRange)),
          mSolid(constantsOf(pair.solid)), mLiquid(constantsOf(pair.liquid)) {}

    /// For the neighbours at temperatures @p tj.
    Constants at(__m512 tj) const {
        const __m512 one = _mm512_set1_ps(1), zero = _mm512_setzero_ps();
        // s: smoothstep of the pair's mean temperature; exactly 1 from T_liquid up,
        // whatever (t - T_solid) / range rounds to.
        const __m512 t = _mm512_mul_ps(_mm512_set1_ps(0.5f), _mm512_add_ps(mTi, tj));
        __m512 x = _mm512_mul_ps(_mm512_sub_ps(t, mTs), mInvRange);
        x = _mm512_min_ps(one, _mm512_max_ps(zero, x));
        x = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(t, mTl, _CMP_GE_OQ), x, one);
        const __m512 s =
            _mm512_mul_ps(_mm512_mul_ps(x, x),
                          _mm512_fnmadd_ps(_mm512_set1_ps(2), x, _mm512_set1_ps(3)));
        const __m512 r = _mm512_sub_ps(one, s);
        const auto blend = [&](__m512 a, __m512 b) {
            return _mm512_fmadd_ps(s, b, _mm512_mul_ps(r, a));
        };
        return {blend(mSolid.b1, mLiquid.b1), blend(mSolid.b2, mLiquid.b2),
                blend(mSolid.cr2, mLiquid.cr2), blend(mSolid.cd2, mLiquid.cd2)};
    }

private:
    static Constants constantsOf(const PairForce& p) {
        return {_mm512_set1_ps(p.b1), _mm512_set1_ps(p.b2), _mm512_set1_ps(1.0f / (p.cr * p.cr)),
                _mm512_set1_ps(1.0f / (p.cd * p.cd))};
    }

    __m512 mTi, mTs, mTl, mInvRange;
    Constants mSolid, mLiquid;
};

/// sumBatchAndHeat straight over a member's candidates (CandidateLanes) [@p from, count),
/// which carry their temperatures; the heat in the same blocks. Each pair's opposite force
/// and heat (@p conductance times the heat's term) go to @p reactions (NoReactions: none).
template <int M, int N, typename Opposite>
inline float candidatesAndHeat(const PairForce& p, const CandidateLanes& lanes,
                               const GroupCandidates& c, float ti, float reach2, float& fx,
                               float& fy, float& fz, uint32_t from, Opposite reactions,
                               float conductance) {
    HeatLanes heat(c, lanes.radiusSum, ti, reach2);
    sumCandidatesWith<M, N>(
        p, lanes, fx, fy, fz,
        [&](uint32_t j, __mmask16 near, __m512 d2) {
            reactions.addHeat(j, near, heat.add(j, near, d2), conductance);
        },
        from, reactions);
    return heat.total();
}

/// sumBlendedBatch straight over a member's candidates: the same blocks and heat lanes as
/// candidatesAndHeat, so that where a pure phase holds the two give the same bits.
template <int M, int N, typename Opposite>
inline float blendedCandidates(const ThermalPair& pair, const CandidateLanes& candidates,
                               const GroupCandidates& c, float ti, float reach2, float& fx,
                               float& fy, float& fz, uint32_t from, Opposite reactions,
                               float conductance) {
    const CandidateLanes lanes = candidates;  // a local: the stores cannot alias it
    const BlendLanes blend(pair, ti);
    HeatLanes heat(c, lanes.radiusSum, ti, reach2);
    const float* ct = c.temperature.data();
    __m512 ax = _mm512_setzero_ps(), ay = ax, az = ax;
    for (uint32_t j = firstBlock(from); j < lanes.count(); j += 16) {
        const CandidateLanes::Block b = lanes.load(j, from);
        const BlendLanes::Constants k = blend.at(_mm512_loadu_ps(ct + j));
        const __m512 scale = pairScale<M, N>(b.d2, lanes.invSum2, lanes.minD2, k.b1, k.b2,
                                             k.cr2, k.cd2, b.vDotP);
        reactions.addHeat(j, b.near, heat.add(j, b.near, b.d2), conductance);
        reactions.add(j, b.near, scale, b.dx, b.dy, b.dz);
        ax = _mm512_mask3_fmadd_ps(scale, b.dx, ax, b.near);
        ay = _mm512_mask3_fmadd_ps(scale, b.dy, ay, b.near);
        az = _mm512_mask3_fmadd_ps(scale, b.dz, az, b.near);
    }
    fx += _mm512_reduce_add_ps(ax);
    fy += _mm512_reduce_add_ps(ay);
    fz += _mm512_reduce_add_ps(az);
    return heat.total();
}

/// candidatesAndHeat over all of a member's candidates, every pair from both sides.
template <int M, int N>
inline float sumCandidatesAndHeat(const PairForce& p, const CandidateLanes& lanes,
                                  const GroupCandidates& c, float ti, float reach2, float& fx,
                                  float& fy, float& fz) {
    return candidatesAndHeat<M, N>(p, lanes, c, ti, reach2, fx, fy, fz, 0, NoReactions{}, 0.0f);
}

/// blendedCandidates over all of a member's candidates, every pair from both sides.
template <int M, int N>
inline float sumBlendedCandidates(const ThermalPair& pair, const CandidateLanes& lanes,
                                  const GroupCandidates& c, float ti, float reach2, float& fx,
                                  float& fy, float& fz) {
    return blendedCandidates<M, N>(pair, lanes, c, ti, reach2, fx, fy, fz, 0, NoReactions{},
                                   0.0f);
}
#endif

/// Adds to (fx, fy, fz) the force of every neighbour in @p batch (which holds their
/// temperatures) on a globule at temperature @p ti, each pair's constants blended by its
/// mean temperature, and returns the heat flowing in (HeatLanes, @p reach2). <M, N>: the
/// exponents both phases share, unrolled; <0, 0>: pow() with blended exponents.
template <int M, int N>
inline float sumBlendedBatch(const ThermalPair& pair, float ti, float reach2,
                             const NeighborBatch& batch, float& fx, float& fy, float& fz) {
    const PairForce &solid = pair.solid, &liquid = pair.liquid;
    const float *bx = batch.dx.data(), *by = batch.dy.data(), *bz = batch.dz.data();
    const float* bvp = batch.vDotP.data();
    const float* bsum = batch.radiusSum.data();
    const float* bt = batch.temperature.data();
    const bool uniform = batch.uniformSum > 0;
    const uint32_t count = batch.count;
#if defined(__AVX512F__)
    if constexpr (M > 0 && N > 0) {
        const __m512 one = _mm512_set1_ps(1), zero = _mm512_setzero_ps();
        const float fixedSum2 = batch.uniformSum * batch.uniformSum;
        const __m512 fixedInvSum2 = _mm512_set1_ps(uniform ? 1.0f / fixedSum2 : 0.0f);
        const __m512 fixedMinD2 =
            _mm512_set1_ps(kMinDistanceFraction * kMinDistanceFraction * fixedSum2);
        const BlendLanes blend(pair, ti);
        __m512 ax = zero, ay = zero, az = zero;
        HeatLanes heat(batch, ti, reach2);
        for (uint32_t k = 0; k < count; k += 16) {
            const uint32_t left = count - k;
            const __mmask16 live = firstLanes(left);
            const __m512 dx = _mm512_maskz_loadu_ps(live, bx + k);
            const __m512 dy = _mm512_maskz_loadu_ps(live, by + k);
            const __m512 dz = _mm512_maskz_loadu_ps(live, bz + k);
            __m512 invSum2 = fixedInvSum2, minD2 = fixedMinD2;
            if (!uniform) radiusSumTerms(_mm512_mask_loadu_ps(one, live, bsum + k), invSum2, minD2);
            const BlendLanes::Constants c = blend.at(_mm512_maskz_loadu_ps(live, bt + k));
            const __m512 d2 = _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
            const __m512 scale = pairScale<M, N>(d2, invSum2, minD2, c.b1, c.b2, c.cr2, c.cd2,
                                                 _mm512_maskz_loadu_ps(live, bvp + k));
            heat.add(k, live, d2);
            ax = _mm512_mask3_fmadd_ps(scale, dx, ax, live);
            ay = _mm512_mask3_fmadd_ps(scale, dy, ay, live);
            az = _mm512_mask3_fmadd_ps(scale, dz, az, live);
        }
        fx += _mm512_reduce_add_ps(ax);
        fy += _mm512_reduce_add_ps(ay);
        fz += _mm512_reduce_add_ps(az);
        return heat.total();
    }
#elif defined(__AVX2__)
    if constexpr (M > 0 && N > 0) {
        const __m256 one = _mm256_set1_ps(1), zero = _mm256_setzero_ps();
        const __m256 half = _mm256_set1_ps(0.5f), two = _mm256_set1_ps(2);
        const __m256 three = _mm256_set1_ps(3), tI = _mm256_set1_ps(ti);
        const __m256 tS = _mm256_set1_ps(pair.tSolid), tL = _mm256_set1_ps(pair.tLiquid);
        const __m256 invRange = _mm256_set1_ps(pair.invRange);
        const __m256 b1S = _mm256_set1_ps(solid.b1), b2S = _mm256_set1_ps(solid.b2);
        const __m256 cr2S = _mm256_set1_ps(1.0f / (solid.cr * solid.cr));
        const __m256 cd2S = _mm256_set1_ps(1.0f / (solid.cd * solid.cd));
        const __m256 b1L = _mm256_set1_ps(liquid.b1), b2L = _mm256_set1_ps(liquid.b2);
        const __m256 cr2L = _mm256_set1_ps(1.0f / (liquid.cr * liquid.cr));
        const __m256 cd2L = _mm256_set1_ps(1.0f / (liquid.cd * liquid.cd));
        BatchLanes lanes(batch);
        for (uint32_t k = 0; k < count; k += 8) {
            const BatchLanes::Block b = lanes.load(k, uniform);
            // s: smoothstep of the pair's mean temperature; exactly 1 from T_liquid up.
            const __m256 t = _mm256_mul_ps(half, _mm256_add_ps(tI, _mm256_loadu_ps(bt + k)));
            __m256 x = _mm256_mul_ps(_mm256_sub_ps(t, tS), invRange);
            x = _mm256_min_ps(one, _mm256_max_ps(zero, x));
            x = _mm256_blendv_ps(x, one, _mm256_cmp_ps(t, tL, _CMP_GE_OQ));
            const __m256 s = _mm256_mul_ps(_mm256_mul_ps(x, x), _mm256_fnmadd_ps(two, x, three));
            const __m256 r = _mm256_sub_ps(one, s);
            const auto blend = [&](__m256 a, __m256 c) {
                return _mm256_fmadd_ps(s, c, _mm256_mul_ps(r, a));
            };
            lanes.add(b, pairScale<M, N>(b.d2, b.invSum2, b.minD2, blend(b1S, b1L),
                                         blend(b2S, b2L), blend(cr2S, cr2L), blend(cd2S, cd2L),
                                         _mm256_loadu_ps(bvp + k)));
        }
        lanes.addTo(fx, fy, fz);
        return batchHeat(batch, ti, reach2);  // (not in this loop: see sumBatchAndHeat)
    }
#endif
    const float cr2S = 1.0f / (solid.cr * solid.cr), cd2S = 1.0f / (solid.cd * solid.cd);
    const float cr2L = 1.0f / (liquid.cr * liquid.cr), cd2L = 1.0f / (liquid.cd * liquid.cd);
    float ax = 0, ay = 0, az = 0;
    for (uint32_t k = 0; k < count; ++k) {
        const float s = meltFraction(0.5f * (ti + bt[k]), pair), r = 1.0f - s;
        const auto blend = [&](float a, float b) { return s * b + r * a; };
        const PairTerms terms{blend(solid.b1, liquid.b1), blend(solid.b2, liquid.b2),
                              blend(solid.m, liquid.m),   blend(solid.n, liquid.n),
                              blend(cr2S, cr2L),          blend(cd2S, cd2L)};
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
    return batchHeat(batch, ti, reach2);
}

}  // namespace globular
