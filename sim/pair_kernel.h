#pragma once
// The force loop's inner kernel: eq. (2)-(5) summed over a contiguous run of candidate
// globules, branch-free so the compiler vectorises it. Candidates outside both windows
// contribute exactly zero (S_r = S_d = 0), and so does the globule itself (P = 0), so
// no test is needed to skip them. Same arithmetic as PairForce::accumulate.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pair_force.h"

namespace globular {

/// Globule data in neighbour-grid order: contiguous runs per grid bucket.
struct SortedGlobules {
    std::vector<float> x, y, z, vx, vy, vz, radius;
};

/// b1/D^M - b2/D^N with integer exponents known at compile time (0 = use pow()).
template <int M, int N>
inline float radialTerm(const PairForce& p, float invD, float distance) {
    if constexpr (M > 0 && N > 0) {
        float powM = 1, powN = 1;
        for (int k = 0; k < M; ++k) powM *= invD;  // unrolled: M is a constant
        for (int k = 0; k < N; ++k) powN *= invD;
        return p.b1 * powM - p.b2 * powN;
    } else {
        return p.b1 * std::pow(distance, -p.m) - p.b2 * std::pow(distance, -p.n);
    }
}

/// Adds to (fx, fy, fz) the force on the globule at (x, y, z) with velocity (vx, vy, vz)
/// and radius r from the sorted globules [begin, end).
template <int M, int N>
inline void accumulateRun(const PairForce& p, const SortedGlobules& s, uint32_t begin,
                          uint32_t end, float x, float y, float z, float vx, float vy, float vz,
                          float r, float& fx, float& fy, float& fz) {
    const float* __restrict sx = s.x.data();
    const float* __restrict sy = s.y.data();
    const float* __restrict sz = s.z.data();
    const float* __restrict svx = s.vx.data();
    const float* __restrict svy = s.vy.data();
    const float* __restrict svz = s.vz.data();
    const float* __restrict sr = s.radius.data();
    const float invCr2 = 1.0f / (p.cr * p.cr), invCd2 = 1.0f / (p.cd * p.cd);
    const float minFraction2 = kMinDistanceFraction * kMinDistanceFraction;
    float ax = 0, ay = 0, az = 0;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
    for (uint32_t j = begin; j < end; ++j) {
        const float dx = x - sx[j], dy = y - sy[j], dz = z - sz[j];
        const float dvx = vx - svx[j], dvy = vy - svy[j], dvz = vz - svz[j];
        const float sum = r + sr[j];
        const float invSum2 = 1.0f / (sum * sum);
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float safeD2 = std::max(d2, minFraction2 * sum * sum);
        const float distance = std::sqrt(safeD2);
        const float invD = 1.0f / distance;
        const float windowR = std::max(0.0f, 1.0f - d2 * invSum2 * invCr2);
        const float windowD = std::max(0.0f, 1.0f - d2 * invSum2 * invCd2);
        const float vDotP = dvx * dx + dvy * dy + dvz * dz;
        const float scale = windowR * radialTerm<M, N>(p, invD, distance) -
                            windowD * vDotP * (invD * invD);
        ax += scale * dx;
        ay += scale * dy;
        az += scale * dz;
    }
    fx += ax;
    fy += ay;
    fz += az;
}

}  // namespace globular
