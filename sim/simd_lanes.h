#pragma once
// Lane masks for the vector loops of the force kernel and the neighbour grid: AVX-512's
// 16-lane masks, and for AVX2 (8 lanes, no compress instruction) the left-packing that
// stands in for AVX-512's compress.

#include <array>
#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace globular {

#if defined(__AVX512F__)
/// The lanes of a 16-wide step with @p left elements still to go.
inline __mmask16 firstLanes(uint32_t left) {
    return left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1);
}
#endif

#if defined(__AVX2__)
/// For each 8-bit lane mask, the indices of its set lanes in ascending order, one byte
/// each: the permutation that moves the kept lanes to the front, keeping their order.
/// 2 KiB. A table of whole 32-byte permutations (8 KiB, no widening) measured no faster
/// here; BMI2's pdep/pext would spare the table but are microcoded on AMD before Zen 3.
/// Not inline: a const at namespace scope is local to each build (cmake/isolated_build.cmake
/// exports one symbol).
constexpr std::array<uint64_t, 256> kLeftPackIndices = [] {
    std::array<uint64_t, 256> table{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        unsigned slot = 0;
        for (unsigned lane = 0; lane < 8; ++lane) {
            if ((mask >> lane) & 1u) table[mask] |= uint64_t(lane) << (8 * slot++);
        }
    }
    return table;
}();

/// @p v with the lanes set in @p mask (movemask order) moved to the front, in order; the
/// other lanes hold copies. Storing it at the end of a list appends the kept lanes (and
/// scribbles up to 8 floats past them, which the lists' padding absorbs): AVX-512's
/// compress and store in two instructions.
inline __m256 leftPack(__m256 v, unsigned mask) {
    const auto* bytes = reinterpret_cast<const __m128i*>(&kLeftPackIndices[mask]);
    const __m256i order = _mm256_cvtepu8_epi32(_mm_loadl_epi64(bytes));
    return _mm256_permutevar8x32_ps(v, order);
}

/// All bits set in the first @p left lanes of 8 (all of them from 8 on).
inline __m256i firstLanes8(uint32_t left) {
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    return _mm256_cmpgt_epi32(_mm256_set1_epi32(int(left >= 8 ? 8 : left)), lane);
}

/// The sum of the 8 lanes of @p v, in a fixed order.
inline float sumLanes(__m256 v) {
    __m128 half = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    half = _mm_add_ps(half, _mm_movehl_ps(half, half));
    half = _mm_add_ss(half, _mm_movehdup_ps(half));
    return _mm_cvtss_f32(half);
}

/// The least of the 8 lanes of @p v.
inline float minLanes(__m256 v) {
    __m128 half = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    half = _mm_min_ps(half, _mm_movehl_ps(half, half));
    half = _mm_min_ss(half, _mm_movehdup_ps(half));
    return _mm_cvtss_f32(half);
}

/// The greatest of the 8 lanes of @p v.
inline float maxLanes(__m256 v) {
    __m128 half = _mm_max_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    half = _mm_max_ps(half, _mm_movehl_ps(half, half));
    half = _mm_max_ss(half, _mm_movehdup_ps(half));
    return _mm_cvtss_f32(half);
}
#endif

}  // namespace globular
