#pragma once
// The inter-globule force of eq. (2)-(5), read literally (PAPER_NOTES.md):
//   f_ip = P [ S_r (b1/D^m - b2/D^n) - S_d (V.P)/D^2 ],  P = x_p - x_i, V = v_p - v_i,
//   b2 = b1 r0^(n-m), S = 1 - D^2 / (C^2 (r_i + r_p)^2) inside the window, 0 outside.
// Inline so the force loops vectorise; evaluated in single precision.

#include <cmath>
#include <cstdint>

namespace globular {

struct ForceConstants;

/// Distances below this fraction of r_i + r_p are treated as this distance, so two
/// coincident globules (P = 0) feel no force and near-coincident ones a large but finite
/// push instead of infinity.
inline constexpr float kMinDistanceFraction = 1e-3f;

/// The material constants in the form the force loops use.
struct PairForce {
    float b1 = 2, b2 = 2;  ///< b2 = b1 r0^(n-m)
    float m = 5, n = 3;
    float cr = 1, cd = 1.5f;  ///< window constants, numbers
    int mInt = 5, nInt = 3;   ///< m, n when both are whole numbers
    bool integerExponents = true;

    static PairForce fromMaterial(const ForceConstants& material);

    /// Largest reach of either window for radii summing to @p radiusSum.
    float cutoff(float radiusSum) const { return (cr > cd ? cr : cd) * radiusSum; }

    /// b1/D^m - b2/D^n for a distance D with 1/D = @p invD.
    float radialCoefficient(float invD, float distance) const {
        if (integerExponents) return b1 * intPow(invD, mInt) - b2 * intPow(invD, nInt);
        return b1 * std::pow(distance, -m) - b2 * std::pow(distance, -n);
    }

    /// Force on globule p from globule i given P = x_p - x_i (@p dx, @p dy, @p dz),
    /// V = v_p - v_i and the radius sum; accumulates into @p f.
    void accumulate(float dx, float dy, float dz, float dvx, float dvy, float dvz,
                    float radiusSum, float f[3]) const {
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float sum2 = radiusSum * radiusSum;
        const float crWindow = cr * cr * sum2, cdWindow = cd * cd * sum2;
        if (d2 >= crWindow && d2 >= cdWindow) return;
        const float minD = kMinDistanceFraction * radiusSum;
        const float safeD2 = d2 > minD * minD ? d2 : minD * minD;
        const float distance = std::sqrt(safeD2);
        const float invD = 1.0f / distance;
        const float sr = d2 < crWindow ? 1.0f - d2 / crWindow : 0.0f;
        const float sd = d2 < cdWindow ? 1.0f - d2 / cdWindow : 0.0f;
        const float vDotP = dvx * dx + dvy * dy + dvz * dz;
        const float scale = sr * radialCoefficient(invD, distance) - sd * vDotP / safeD2;
        f[0] += scale * dx;
        f[1] += scale * dy;
        f[2] += scale * dz;
    }

    static float intPow(float x, int k) {
        float result = 1.0f;
        for (; k > 0; --k) result *= x;
        return result;
    }
};

}  // namespace globular
